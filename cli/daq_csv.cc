#include "daq_csv.h"

#include <algorithm>
#include <cctype>
#include <fstream>

#include "ltp/core/channel.h"
#include "ltp/core/error.h"
#include "ltp/core/text.h"
#include "time_data_csv.h"

namespace ltp::cli {

namespace {

std::string Trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\"'");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r\"'");
  return s.substr(a, b - a + 1);
}

// "Force [N]" / "Force (N)" / "Force_N"? Only brackets and parentheses count as units.
std::string WithoutBracketedUnit(const std::string& name) {
  const size_t at = name.find_first_of("[(");
  return Trim(at == std::string::npos ? name : name.substr(0, at));
}

// The trimmed cells of a table line.
std::vector<std::string> Cells(const std::string& line, char separator) {
  std::vector<std::string> cells = SplitAt(line, separator);
  for (std::string& cell : cells) cell = Trim(cell);
  return cells;
}

bool ParseNumber(std::string text, bool decimal_comma, double* x) {
  if (decimal_comma) std::replace(text.begin(), text.end(), ',', '.');
  const std::optional<double> value = NumberIn(text);
  if (value) *x = *value;
  return value.has_value();
}

bool IsComment(const std::string& line) {
  const size_t a = line.find_first_not_of(" \t");
  return a == std::string::npos || line[a] == '#' || line[a] == '%';
}

bool IsTimeName(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name == "time" || name == "t" || name == "time_s" || name == "zeit";
}

}  // namespace

bool IsLtpTimeData(const std::string& path) {
  RequireRegularFile(path);
  std::ifstream in(path);
  std::string line;
  while (ReadTextLine(in, line, path))
    if (!IsComment(line)) return line.rfind("record,", 0) == 0;
  return false;
}

// The separator a line uses most (comma, semicolon or tab).
static char SeparatorOf(const std::string& line) {
  char separator = ',';
  size_t best = 0;
  for (char c : {',', ';', '\t'})
    if (const auto k = static_cast<size_t>(std::count(line.begin(), line.end(), c)); k > best)
      best = k, separator = c;
  return separator;
}

ChannelTable ReadDaqCsv(const std::string& path, double sample_rate) {
  RequireRegularFile(path);
  std::ifstream in(path);
  if (!in) throw InputError("cannot read '" + path + "'");
  // The header is the last line before the first one that starts with a number (a DAQ may
  // write a preamble above it).
  std::vector<std::pair<size_t, std::string>> lines;
  std::string line;
  for (size_t number = 1; ReadTextLine(in, line, path + ":" + std::to_string(number)); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!IsComment(line)) lines.emplace_back(number, line);
  }
  size_t first = 0;
  for (; first < lines.size(); ++first) {
    const std::string& text = lines[first].second;
    double x = 0;
    bool numeric = false;
    for (char sep : {';', '\t', ','})
      numeric = numeric || ParseNumber(Cells(text, sep)[0], sep == ';', &x);
    if (numeric) break;
  }
  if (first == 0 || first == lines.size())
    throw InputError(path + ": " +
                     (first == 0 ? "numbers before any header of channel names (Time [s],Force "
                                   "[N],…)"
                                 : "no line of numbers under a header of channel names"));
  ChannelTable table;
  table.path = path;
  const char separator = SeparatorOf(lines[first - 1].second);
  const bool decimal_comma = separator == ';';  // a semicolon file may write decimal commas
  const std::vector<std::string> header = Cells(lines[first - 1].second, separator);
  int time_column = -1;
  for (size_t c = 0; c < header.size(); ++c) {
    const std::string name = WithoutBracketedUnit(header[c]);
    if (time_column < 0 && IsTimeName(name)) {
      time_column = static_cast<int>(c);
      continue;
    }
    table.names.push_back(name.empty() ? "column " + std::to_string(c + 1) : name);
  }
  std::vector<std::vector<double>> rows;
  for (size_t l = first; l < lines.size(); ++l) {
    const std::string where = path + ":" + std::to_string(lines[l].first);
    const std::vector<std::string> cells = Cells(lines[l].second, separator);
    if (cells.size() != header.size())
      throw InputError(where + ": " + std::to_string(cells.size()) + " cells, the header has " +
                       std::to_string(header.size()));
    std::vector<double> row;
    for (size_t c = 0; c < cells.size(); ++c) {
      double x = 0;
      if (!ParseNumber(cells[c], decimal_comma, &x))
        throw InputError(where + ": '" + cells[c] + "' is not a number");
      if (static_cast<int>(c) == time_column)
        table.time.push_back(x);
      else
        row.push_back(x);
    }
    rows.push_back(std::move(row));
  }
  if (rows.size() < 2) throw InputError(path + ": fewer than 2 rows of samples");
  if (table.names.empty()) throw InputError(path + ": no channel besides the time");
  for (size_t a = 0; a < table.names.size(); ++a)
    for (size_t b = a + 1; b < table.names.size(); ++b)
      if (table.names[a] == table.names[b])
        throw InputError(path + ": two columns are named '" + table.names[a] +
                         "': a channel chosen by name would be ambiguous");
  if (time_column < 0) {
    if (!(sample_rate > 0))
      throw InputError(path + ": no time column (Time, t) and no --sample-rate");
    for (size_t i = 0; i < rows.size(); ++i)
      table.time.push_back(static_cast<double>(i) / sample_rate);
  }
  table.values.resize(static_cast<Eigen::Index>(rows.size()),
                      static_cast<Eigen::Index>(table.names.size()));
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t c = 0; c < rows[i].size(); ++c)
      table.values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) = rows[i][c];
  return table;
}

TimeData TimeDataFromTables(const std::vector<ChannelTable>& tables, const std::string& input,
                            const std::vector<std::string>& outputs, double period) {
  TimeData data;
  data.period = period;
  for (const ChannelTable& t : tables) {
    const int count = static_cast<int>(t.names.size());
    const int in = ResolveChannel(input, t.names, count, "--input", "channel of " + t.path);
    std::vector<std::string> output_names;
    Eigen::MatrixXd response(t.values.rows(), static_cast<Eigen::Index>(outputs.size()));
    for (size_t k = 0; k < outputs.size(); ++k) {
      const int out =
          ResolveChannel(outputs[k], t.names, count, "--output", "channel of " + t.path);
      if (in == out)
        throw InputError("--input and --output name the same channel '" +
                         t.names[static_cast<size_t>(in)] + "' of " + t.path +
                         ": name the excitation and the response (--input NAME --output NAME)");
      output_names.push_back(t.names[static_cast<size_t>(out)]);
      response.col(static_cast<Eigen::Index>(k)) = t.values.col(out);
    }
    if (data.records.empty()) {
      data.input_names = {t.names[static_cast<size_t>(in)]};
      data.output_names = output_names;
      data.auxiliary_names = t.names;
    } else if (t.names != data.auxiliary_names) {
      throw InputError(t.path + ": other channels than " + tables.front().path);
    }
    TimeRecord r;
    r.time = t.time;
    r.time_error = t.time_error;
    r.inputs = t.values.col(in);
    r.outputs = response;
    r.auxiliary = t.values;
    data.records.push_back(std::move(r));
  }
  return data;
}

}  // namespace ltp::cli
