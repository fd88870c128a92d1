#pragma once
// Typed errors. Library code throws these for bad input; the CLI turns each into one line on
// stderr and exit code 2. Numerical outcomes (an integrator that gave up) are *not* thrown:
// they are reported in the result structs' diagnostics.
#include <concepts>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ltp {

/// Base of every error ltp throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input from the user: an unknown scene or parameter, wrong sizes, NaN, T <= 0.
class InputError : public Error {
 public:
  using Error::Error;
};

/// A scene file that cannot be read or is malformed. The message names the file, the line
/// (when known) and the entry.
class SceneError : public InputError {
 public:
  using InputError::InputError;
};

/// The mass matrix of a second-order system is singular or not finite at some time.
class SingularMassError : public InputError {
 public:
  using InputError::InputError;
};

/// A computation would not fit in memory, or was asked for something it cannot do.
class ResourceError : public Error {
 public:
  using Error::Error;
};

/// A number as messages and diagnostics write it: `significant` digits, "%g"-style.
std::string MessageNumber(double x, int significant = 6);

/// The refusals of an options struct's Validate(), all in one style:
///   "FloquetOptions::segments = -1. Violated constraint: segments >= 0 (0 = automatic)".
/// `owner` names the struct (or the function whose argument is checked).
class OptionCheck {
 public:
  explicit OptionCheck(std::string_view owner) : owner_(owner) {}

  /// Throws InputError "<owner>::<field> = <value>. Violated constraint: <constraint>". A
  /// double is written in its shortest exact form: six digits could print a violating
  /// 0.0100000001 as the bound 0.01.
  [[noreturn]] void Fail(std::string_view field, double value, std::string_view constraint) const;
  template <std::integral Int>
  [[noreturn]] void Fail(std::string_view field, Int value, std::string_view constraint) const {
    Fail(field, std::string_view(std::to_string(value)), constraint);
  }
  /// For a value that is not one number ("{}", "unset", "3..1"), or a check that spans fields
  /// (field "min_order..max_order").
  [[noreturn]] void Fail(std::string_view field, std::string_view value,
                         std::string_view constraint) const;

 private:
  std::string_view owner_;
};

}  // namespace ltp
