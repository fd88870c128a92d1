#include "expression.h"

#include <muParser.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <set>
#include <sstream>

namespace ltp::internal {
namespace {

// muParser's built-in functions and constants, plus the names scenes define themselves.
const std::set<std::string>& ReservedNames() {
  static const std::set<std::string> names = {
      "t",    "pi",   "_pi",  "_e",    "sin",   "cos",   "tan",  "asin",  "acos", "atan",
      "sinh", "cosh", "tanh", "asinh", "acosh", "atanh", "log2", "log10", "log",  "ln",
      "exp",  "sqrt", "sign", "rint",  "abs",   "sum",   "avg",  "min",   "max"};
  return names;
}

// A parser with pi, the constants and (if `t` is given) the variable t bound to *t.
std::unique_ptr<mu::Parser> MakeParser(const std::string& text, const Constants& constants,
                                       double* t) {
  auto parser = std::make_unique<mu::Parser>();
  if (t != nullptr) parser->DefineVar("t", t);
  parser->DefineConst("pi", std::numbers::pi);
  for (const auto& [name, value] : constants) parser->DefineConst(name, value);
  parser->SetExpr(text);
  return parser;
}

// An expression as quoted in a message: a 1 MB expression must not become a 1 MB error line.
std::string Quoted(const std::string& text) {
  constexpr size_t kMax = 120;
  return text.size() <= kMax
             ? text
             : text.substr(0, kMax) + "… (" + std::to_string(text.size()) + " characters)";
}

ExpressionError Translate(const mu::ParserError& e, const std::string& text) {
  if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN)
    return ExpressionError("unknown name '" + e.GetToken() + "' in expression '" + Quoted(text) +
                           "'");
  return ExpressionError("bad expression '" + Quoted(text) + "': " + e.GetMsg());
}

// Throws for a name called like a function that muParser does not know; muParser itself would
// only report an unexpected parenthesis.
void CheckFunctionNames(const mu::Parser& parser, const std::string& text) {
  std::string word;
  for (size_t i = 0; i <= text.size(); ++i) {
    const char c = i < text.size() ? text[i] : ' ';
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.') {
      word += c;
      continue;
    }
    size_t next = i;
    while (next < text.size() && std::isspace(static_cast<unsigned char>(text[next]))) ++next;
    const bool called = next < text.size() && text[next] == '(';
    if (called && IsIdentifier(word) && parser.GetFunDef().count(word) == 0)
      throw ExpressionError("unknown function '" + word + "' in expression '" + Quoted(text) + "'");
    word.clear();
  }
}

// Compiles the parser's expression and checks it names no unknown variable or function and
// gives exactly one value. Returns whether it uses t.
bool Check(mu::Parser& parser, const std::string& text, bool allow_t) {
  try {
    CheckFunctionNames(parser, text);
    bool uses_t = false;
    // GetUsedVar also lists names that are not defined at all: those are the unknown ones.
    for (const auto& [name, pointer] : parser.GetUsedVar()) {
      if (name != "t" || !allow_t)
        throw ExpressionError("unknown variable '" + name + "' in expression '" + Quoted(text) +
                              "'");
      uses_t = true;
    }
    parser.Eval();
    if (parser.GetNumResults() != 1)
      throw ExpressionError("expression '" + Quoted(text) + "' gives " +
                            std::to_string(parser.GetNumResults()) + " values, expected one");
    return uses_t;
  } catch (const mu::ParserError& e) {
    throw Translate(e, text);
  }
}

// Functions and operators whose value can jump as t varies.
bool MayJump(const std::string& text) {
  if (text.find_first_of("<>?=!&|") != std::string::npos) return true;
  std::string word;
  for (size_t i = 0; i <= text.size(); ++i) {
    const char c = i < text.size() ? text[i] : ' ';
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      word += c;
    } else {
      if (word == "sign" || word == "rint") return true;
      word.clear();
    }
  }
  return false;
}

std::atomic<std::uint64_t> next_pool_id{1};  // 0 marks an empty cache slot

}  // namespace

std::string FormatValue(double value) {
  if (std::isnan(value)) return "NaN";
  std::ostringstream s;
  s << value;
  return s.str();
}

bool IsReservedName(const std::string& name) { return ReservedNames().count(name) > 0; }

bool IsIdentifier(const std::string& name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

std::optional<double> PlainNumber(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t");
  if (first == std::string::npos) return std::nullopt;
  const std::string core = text.substr(first, last - first + 1);
  if (core.find_first_not_of("0123456789.eE+-") != std::string::npos ||
      core.find_first_of("0123456789") == std::string::npos)
    return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(core.c_str(), &end);
  if (end != core.c_str() + core.size()) return std::nullopt;
  return value;
}

double EvaluateConstant(const std::string& text, const Constants& constants) {
  if (const std::optional<double> value = PlainNumber(text)) return *value;
  try {
    auto parser = MakeParser(text, constants, nullptr);
    Check(*parser, text, false);
    return parser->Eval();
  } catch (const mu::ParserError& e) {
    throw Translate(e, text);
  }
}

struct TimeExpression::State {
  double t = 0;
  std::unique_ptr<mu::Parser> parser;
};

TimeExpression::TimeExpression(const std::string& text, const Constants& constants)
    : state_(std::make_unique<State>()), may_jump_(MayJump(text)) {
  try {
    state_->parser = MakeParser(text, constants, &state_->t);
  } catch (const mu::ParserError& e) {
    throw Translate(e, text);
  }
  depends_on_t_ = Check(*state_->parser, text, true);
}

TimeExpression::TimeExpression(TimeExpression&&) noexcept = default;
TimeExpression& TimeExpression::operator=(TimeExpression&&) noexcept = default;
TimeExpression::~TimeExpression() = default;

double TimeExpression::operator()(double t) const {
  state_->t = t;
  return state_->parser->Eval();
}

TimeExpressionPool::Evaluator::Evaluator(const std::vector<std::string>& texts,
                                         const Constants& constants) {
  parsers_.reserve(texts.size());
  for (const auto& text : texts) {
    parsers_.push_back(MakeParser(text, constants, &t_));
    parsers_.back()->Eval();  // compile now, so the first real call is as fast as the rest
  }
}

TimeExpressionPool::Evaluator::~Evaluator() = default;

double TimeExpressionPool::Evaluator::Value(int index) const {
  return parsers_[static_cast<size_t>(index)]->Eval();
}

TimeExpressionPool::TimeExpressionPool(std::vector<std::string> texts, Constants constants)
    : texts_(std::move(texts)), constants_(std::move(constants)), id_(next_pool_id++) {}

TimeExpressionPool::~TimeExpressionPool() = default;

TimeExpressionPool::Evaluator& TimeExpressionPool::ForThisThread() const {
  // Cache of this thread's recent (pool id, evaluator) pairs. An id is never reused, so a slot
  // whose pool has died is simply never matched again.
  struct Slot {
    std::uint64_t id = 0;
    Evaluator* evaluator = nullptr;
  };
  thread_local std::array<Slot, 4> cache;
  thread_local size_t next_slot = 0;
  for (const Slot& slot : cache)
    if (slot.id == id_) return *slot.evaluator;

  std::lock_guard<std::mutex> lock(mutex_);
  auto& evaluator = evaluators_[std::this_thread::get_id()];
  if (!evaluator) evaluator = std::make_unique<Evaluator>(texts_, constants_);
  cache[next_slot++ % cache.size()] = {id_, evaluator.get()};
  return *evaluator;
}

}  // namespace ltp::internal
