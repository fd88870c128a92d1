#pragma once
// Number formatting shared by the command writers: never prints "nan" silently, keeps columns.
#include <complex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace ltp::cli {

/// Fixed-width number for tables: "%.*g", with non-finite values spelled out.
std::string Num(double x, int precision = 6, int width = 0);
/// A quantity that may not have been computed: "n/a" (padded to `width`) when empty.
std::string Num(std::optional<double> x, int precision = 6, int width = 0);
/// A JSON value for a double: the number if finite, else the string "inf", "-inf" or "nan".
nlohmann::json JsonNumber(double x);
/// null when the quantity was not computed.
nlohmann::json JsonNumber(std::optional<double> x);
/// An array of JsonNumber.
nlohmann::json JsonNumbers(const std::vector<double>& x);
/// A CSV cell: 12 significant digits ("%.12g"), non-finite values spelled out; appended to
/// `out` (a row is built in one string: a stream per number was a fifth of a map's time).
void AppendCsvNumber(std::string& out, double x);
/// The same as a string; empty (an empty cell) when the quantity was not computed.
std::string CsvNumber(std::optional<double> x);
/// A CSV text cell: quoted, with '"' and line breaks replaced by "'" (so a cell never spans
/// lines and readers that do not undo doubled quotes read it too).
std::string CsvText(std::string s);
/// "about 47 s of CPU work ahead" (minutes or hours when longer): how a command announces a
/// WorkEstimate before the work.
std::string WorkAhead(double seconds);
/// exp(log_abs) as a number that under- or overflows to 0 or inf on purpose.
double ExpClamped(double log_abs);

}  // namespace ltp::cli
