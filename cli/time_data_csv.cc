#include "time_data_csv.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <vector>

#include "ltp/core/error.h"
#include "ltp/core/text.h"

namespace ltp::cli {

namespace {

double Number(const std::string& text, const std::string& where) {
  const std::optional<double> x = NumberIn(text);
  if (!x) throw InputError(where + ": '" + text + "' is not a number");
  return *x;
}

}  // namespace

std::string ChannelNameOr(const std::vector<std::string>& names, Eigen::Index i,
                          const std::string& fallback) {
  if (static_cast<size_t>(i) < names.size()) return names[static_cast<size_t>(i)];
  std::string text = fallback;  // (not fallback + to_string: g++ 12 warns falsely, -Wrestrict)
  return text += std::to_string(i + 1);
}

void WriteTimeDataCsv(const std::string& path, const TimeData& data, const std::string& comment) {
  std::ofstream out(path);
  out.precision(15);
  out << "# ltp time data: " << comment << "\n# period_s: " << data.period << "\n";
  if (data.rotor_speed) out << "# rotor_speed_rad_s: " << *data.rotor_speed << "\n";
  out << "record,excitation_hz,t";
  const TimeRecord& first = data.records.front();
  for (Eigen::Index i = 0; i < first.inputs.cols(); ++i)
    out << ",in:" << ChannelNameOr(data.input_names, i, "u");
  for (Eigen::Index i = 0; i < first.outputs.cols(); ++i)
    out << ",out:" << ChannelNameOr(data.output_names, i, "y");
  for (Eigen::Index i = 0; i < first.auxiliary.cols(); ++i)
    out << ",aux:" << ChannelNameOr(data.auxiliary_names, i, "a");
  out << "\n";
  for (size_t r = 0; r < data.records.size(); ++r) {
    const TimeRecord& rec = data.records[r];
    for (size_t s = 0; s < rec.time.size(); ++s) {
      out << r + 1 << "," << rec.excitation_hz << "," << rec.time[s];
      for (Eigen::Index i = 0; i < rec.inputs.cols(); ++i)
        out << "," << rec.inputs(static_cast<Eigen::Index>(s), i);
      for (Eigen::Index i = 0; i < rec.outputs.cols(); ++i)
        out << "," << rec.outputs(static_cast<Eigen::Index>(s), i);
      for (Eigen::Index i = 0; i < rec.auxiliary.cols(); ++i)
        out << "," << rec.auxiliary(static_cast<Eigen::Index>(s), i);
      out << "\n";
    }
  }
  if (!out) throw InputError("cannot write '" + path + "'");
}

std::optional<double> NumberIn(const std::string& text) {
  size_t used = 0;
  double x = 0;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used == 0 || text.find_first_not_of(" \t\r", used) != std::string::npos) return std::nullopt;
  return x;
}

void RequireRegularFile(const std::string& path) {
  std::error_code error;
  if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error))
    throw InputError("'" + path + "' is not a regular file (a device, a pipe or a directory)");
}

bool ReadTextLine(std::istream& in, std::string& line, const std::string& where) {
  constexpr std::streamsize kLongest = 1 << 20;
  static thread_local std::vector<char> buffer(static_cast<size_t>(kLongest) + 1);
  line.clear();
  in.getline(buffer.data(), kLongest + 1);
  const std::streamsize read = in.gcount();
  if (in.fail() && !in.eof()) {
    if (read >= kLongest)
      throw InputError(where +
                       ": a line longer than 1 MiB — not a text table (a binary file, "
                       "or one without line ends)");
    return false;
  }
  if (read == 0 && in.eof()) return false;
  // The newline was extracted (and counted) unless the file ended first.
  line.assign(buffer.data(), static_cast<size_t>(in.eof() ? read : read - 1));
  if (in.eof()) in.clear(std::ios::eofbit);
  // Channel names end up in JSON and on terminals.
  if (const auto problem = NotUtf8(line, "tables are text (ASCII or UTF-8)"))
    throw InputError(where + ": " + *problem);
  return true;
}

namespace {

// A comment line's `# period_s: T` or `# rotor_speed_rad_s: W` into the data (a second period
// line must agree with the first).
void ReadCommentLine(const std::string& line, const std::string& where, TimeData& data,
                     std::optional<double>& file_period) {
  for (const auto& [key, field] :
       {std::pair<std::string, int>{"period_s:", 0}, {"rotor_speed_rad_s:", 1}}) {
    const size_t at = line.find(key);
    if (at == std::string::npos) continue;
    const double x = Number(line.substr(at + key.size()), where);
    if (!(x > 0) || !std::isfinite(x))
      throw InputError(where + ": " + key + " " + MessageNumber(x, 10) + " must be finite and > 0");
    if (field == 1) {
      data.rotor_speed = x;
    } else if (file_period && *file_period != x) {
      throw InputError(where + ": a second period_s line (" + MessageNumber(x, 15) +
                       ") disagrees with the first (" + MessageNumber(*file_period, 15) + ")");
    } else {
      file_period = x;
      data.period = x;
    }
  }
}

// The header record,excitation_hz,t,in:…,out:…,aux:… into the data's channel names.
void ReadHeader(const std::vector<std::string>& cells, const std::string& where, TimeData& data) {
  if (cells.size() < 5 || cells[0] != "record" || cells[1] != "excitation_hz" || cells[2] != "t")
    throw InputError(where + ": expected the header record,excitation_hz,t,in:NAME...,out:NAME...");
  for (size_t c = 3; c < cells.size(); ++c) {
    if (cells[c].rfind("in:", 0) == 0 && data.output_names.empty() && data.auxiliary_names.empty())
      data.input_names.push_back(cells[c].substr(3));
    else if (cells[c].rfind("out:", 0) == 0 && data.auxiliary_names.empty())
      data.output_names.push_back(cells[c].substr(4));
    else if (cells[c].rfind("aux:", 0) == 0)
      data.auxiliary_names.push_back(cells[c].substr(4));
    else
      throw InputError(where + ": column '" + cells[c] +
                       "' is not in:NAME, out:NAME or aux:NAME (in that order)");
  }
  if (data.input_names.empty() || data.output_names.empty())
    throw InputError(where + ": needs at least one in: and one out: column");
  for (const auto* names : {&data.input_names, &data.output_names, &data.auxiliary_names})
    for (size_t a = 0; a < names->size(); ++a)
      for (size_t b = a + 1; b < names->size(); ++b)
        if ((*names)[a] == (*names)[b])
          throw InputError(where + ": two columns are named '" + (*names)[a] +
                           "': a channel chosen by name would be ambiguous");
}

// One record's rows (record, excitation_hz, t, inputs, outputs, auxiliaries) as a TimeRecord.
TimeRecord RecordOf(const std::vector<std::vector<double>>& rows, const TimeData& data,
                    const std::string& path, long number) {
  const size_t inputs = data.input_names.size(), outputs = data.output_names.size();
  const size_t auxiliaries = data.auxiliary_names.size();
  TimeRecord rec;
  rec.excitation_hz = rows[0][1];
  for (const std::vector<double>& row : rows)
    if (!(row[1] == rec.excitation_hz))
      throw InputError(path + ": record " + std::to_string(number) + " has excitation_hz " +
                       MessageNumber(rec.excitation_hz, 10) + " and " + MessageNumber(row[1], 10) +
                       ": one frequency per record");
  const auto n = static_cast<Eigen::Index>(rows.size());
  rec.inputs.resize(n, static_cast<Eigen::Index>(inputs));
  rec.outputs.resize(n, static_cast<Eigen::Index>(outputs));
  rec.auxiliary.resize(n, static_cast<Eigen::Index>(auxiliaries));
  for (Eigen::Index s = 0; s < n; ++s) {
    const std::vector<double>& row = rows[static_cast<size_t>(s)];
    rec.time.push_back(row[2]);
    for (size_t i = 0; i < inputs; ++i) rec.inputs(s, static_cast<Eigen::Index>(i)) = row[3 + i];
    for (size_t i = 0; i < outputs; ++i)
      rec.outputs(s, static_cast<Eigen::Index>(i)) = row[3 + inputs + i];
    for (size_t i = 0; i < auxiliaries; ++i)
      rec.auxiliary(s, static_cast<Eigen::Index>(i)) = row[3 + inputs + outputs + i];
  }
  return rec;
}

}  // namespace

TimeData ReadTimeDataCsv(const std::string& path, double period, bool require_period) {
  RequireRegularFile(path);
  std::ifstream in(path);
  if (!in) throw InputError("cannot read '" + path + "'");
  TimeData data;
  std::string line;
  size_t number = 0;
  bool header = false;
  long current = -1;
  std::vector<std::vector<double>> rows;
  std::optional<double> file_period;
  const auto flush = [&]() {
    if (!rows.empty()) data.records.push_back(RecordOf(rows, data, path, current));
    rows.clear();
  };
  while (ReadTextLine(in, line, path + ":" + std::to_string(number + 1))) {
    const std::string where = path + ":" + std::to_string(++number);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] == '#') {
      ReadCommentLine(line, where, data, file_period);
      continue;
    }
    const std::vector<std::string> cells = SplitAt(line, ',');
    if (!header) {
      ReadHeader(cells, where, data);
      header = true;
      continue;
    }
    const size_t columns =
        3 + data.input_names.size() + data.output_names.size() + data.auxiliary_names.size();
    if (cells.size() != columns)
      throw InputError(where + ": " + std::to_string(cells.size()) + " cells, the header has " +
                       std::to_string(columns));
    std::vector<double> row;
    for (const std::string& c : cells) row.push_back(Number(c, where));
    if (!(row[0] == std::round(row[0])) || std::abs(row[0]) > 1e9)
      throw InputError(where + ": record '" + cells[0] + "' is not a whole number");
    if (const long record = std::lround(row[0]); record != current) {
      flush();
      current = record;
    }
    rows.push_back(std::move(row));
  }
  flush();
  if (!header) throw InputError(path + ": no header line (record,excitation_hz,t,in:...,out:...)");
  if (period > 0) data.period = period;
  if (!(data.period > 0) && !require_period) return data;  // the caller measures it
  if (!(data.period > 0))
    throw InputError(path +
                     ": no '# period_s:' line: give the period with --period T or --rotor-speed W");
  data.Validate();
  return data;
}

}  // namespace ltp::cli
