#pragma once
// Internal: muParser expressions in the time `t`, `pi` and named constants (scene parameters).
// muParser binds variables by pointer and keeps mutable parse state, so one parser must never
// be used by two threads at once; TimeExpressionPool gives every thread its own parsers.
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace mu {
class Parser;
}

namespace ltp::internal {

using Constants = std::map<std::string, double>;

/// A malformed expression. what() is one line naming the expression, e.g.
/// "unknown variable 'kk' in expression '-kk*cos(t)'".
class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// True for names an expression already gives a meaning to (t, pi, muParser's functions and
/// constants): a parameter with such a name would be shadowed or would shadow.
bool IsReservedName(const std::string& name);
/// True for a valid identifier: a letter or '_' followed by letters, digits or '_'.
bool IsIdentifier(const std::string& name);

/// A number for a message: shortest round-trip-free form ("0.785", "1e-17", "NaN", "inf").
std::string FormatValue(double value);

/// Value of an expression in numbers, pi and `constants` (no t). @throws ExpressionError.
double EvaluateConstant(const std::string& text, const Constants& constants = {});

/// The value of a text that is just a decimal number ("0", "-1.5e3", blanks around it), without
/// a parser; nullopt for anything else (names, operators, hex, inf). A 1000-state scene is a
/// million entries, mostly "0": one muParser each took 19 s to load.
std::optional<double> PlainNumber(const std::string& text);

/// One expression in t and `constants`, for single-threaded use (checks at build time).
class TimeExpression {
 public:
  /// Compiles the expression. @throws ExpressionError (syntax, unknown name, not one value).
  TimeExpression(const std::string& text, const Constants& constants);
  TimeExpression(TimeExpression&&) noexcept;
  TimeExpression& operator=(TimeExpression&&) noexcept;
  ~TimeExpression();

  bool depends_on_t() const { return depends_on_t_; }
  /// True if the expression uses an operation that can jump (sign, rint, comparisons, ?:).
  bool may_jump() const { return may_jump_; }
  double operator()(double t) const;

 private:
  struct State;
  std::unique_ptr<State> state_;  // heap-allocated: the parser holds a pointer to its t
  bool depends_on_t_ = false;
  bool may_jump_ = false;
};

/// Expressions in t evaluated concurrently from many threads. Each thread gets its own set of
/// parsers, made on its first call and owned by the pool (freed with it). A small thread_local
/// cache keyed by a never-reused pool id makes the lookup lock-free after the first call.
class TimeExpressionPool {
 public:
  /// The expressions must already have been checked (e.g. with TimeExpression).
  TimeExpressionPool(std::vector<std::string> texts, Constants constants);
  ~TimeExpressionPool();
  TimeExpressionPool(const TimeExpressionPool&) = delete;
  TimeExpressionPool& operator=(const TimeExpressionPool&) = delete;

  int size() const { return static_cast<int>(texts_.size()); }

  /// One thread's parsers. Use only from the thread that obtained it.
  class Evaluator {
   public:
    Evaluator(const std::vector<std::string>& texts, const Constants& constants);
    ~Evaluator();
    /// Sets the time for the following Value() calls.
    void SetTime(double t) { t_ = t; }
    double Value(int index) const;

   private:
    double t_ = 0;  // bound by pointer in every parser: an Evaluator never moves
    std::vector<std::unique_ptr<mu::Parser>> parsers_;
  };

  /// The calling thread's evaluator.
  Evaluator& ForThisThread() const;

 private:
  std::vector<std::string> texts_;
  Constants constants_;
  std::uint64_t id_;
  mutable std::mutex mutex_;
  mutable std::map<std::thread::id, std::unique_ptr<Evaluator>> evaluators_;
};

}  // namespace ltp::internal
