#pragma once
// Typed errors. Library code throws these for bad input; the CLI turns each into one line on
// stderr and exit code 2. Numerical outcomes (an integrator that gave up) are *not* thrown:
// they are reported in the result structs' diagnostics.
#include <stdexcept>
#include <string>

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

}  // namespace ltp
