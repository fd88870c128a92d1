#include "uff58.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/core/text.h"
#include "time_data_csv.h"

namespace ltp::cli {

namespace {

// Columns [from, from + width) of a fixed-format line (blank beyond its end).
std::string Columns(const std::string& line, size_t from, size_t width) {
  return from >= line.size() ? std::string() : line.substr(from, width);
}

// A Fortran number: E or D exponent, blanks around it.
std::optional<double> FortranNumber(std::string text) {
  std::replace(text.begin(), text.end(), 'D', 'E');
  std::replace(text.begin(), text.end(), 'd', 'e');
  return NumberIn(Trim(text));
}

// The file's bytes read line by line, and raw bytes for 58b data.
class Reader {
 public:
  Reader(std::string bytes, std::string path) : bytes_(std::move(bytes)), path_(std::move(path)) {}
  bool AtEnd() const { return pos_ >= bytes_.size(); }
  // The next line without its end of line ("\n" or "\r\n"); false at the end of the file.
  bool Line(std::string* line) {
    if (AtEnd()) return false;
    const size_t end = bytes_.find('\n', pos_);
    *line = bytes_.substr(pos_, (end == std::string::npos ? bytes_.size() : end) - pos_);
    if (!line->empty() && line->back() == '\r') line->pop_back();
    pos_ = end == std::string::npos ? bytes_.size() : end + 1;
    ++line_;
    return true;
  }
  std::string RequireLine(const std::string& what) {
    std::string line;
    if (!Line(&line)) throw InputError(Where() + ": the file ends inside " + what);
    return line;
  }
  std::string Bytes(size_t count, const std::string& what) {
    if (bytes_.size() - pos_ < count)
      throw InputError(Where() + ": " + what + " announces " + std::to_string(count) +
                       " bytes, the file holds " + std::to_string(bytes_.size() - pos_));
    std::string out = bytes_.substr(pos_, count);
    pos_ += count;
    return out;
  }
  std::string Where() const { return path_ + ":" + std::to_string(line_); }
  const std::string& path() const { return path_; }

 private:
  std::string bytes_, path_;
  size_t pos_ = 0, line_ = 0;
};

bool IsSeparator(const std::string& line) { return Trim(line) == "-1"; }

int IntegerField(const std::string& text, const std::string& where, const std::string& what) {
  const std::optional<double> x = FortranNumber(text);
  if (!x || *x != std::round(*x) || std::abs(*x) > 2e9)
    throw InputError(where + ": " + what + " '" + Trim(text) + "' is not an integer");
  return static_cast<int>(*x);
}

// Record 8–11: I10, 3I5, 1X, 20A1 (label), 1X, 20A1 (unit).
void AxisRecord(const std::string& line, const std::string& where, int* type, std::string* label,
                std::string* unit) {
  *type = IntegerField(Columns(line, 0, 10), where, "the axis's data type");
  *label = Trim(Columns(line, 26, 20));
  *unit = Trim(Columns(line, 47, 20));
}

// The field widths of one ASCII data line (record 12's cases), by ordinate type and spacing.
std::vector<size_t> LineFormat(int ordinate_type, bool even) {
  if (ordinate_type == 2 || ordinate_type == 5) return std::vector<size_t>(6, 13);
  if (even) return std::vector<size_t>(4, 20);
  if (ordinate_type == 4) return {13, 20, 13, 20};
  return {13, 20, 20};
}

// The numbers of one data line: the fixed-width fields of its format; a line written in free
// format (fields not at their columns) read by blanks instead.
std::vector<double> DataLine(const std::string& line, const std::vector<size_t>& widths,
                             const std::string& where) {
  std::vector<double> values;
  size_t at = 0;
  bool fixed = true;
  for (size_t w : widths) {
    if (at >= line.size() || Trim(Columns(line, at, w)).empty()) break;
    const std::optional<double> x = FortranNumber(Columns(line, at, w));
    if (!x) {
      fixed = false;
      break;
    }
    values.push_back(*x);
    at += w;
  }
  if (fixed && Trim(Columns(line, at, std::string::npos)).empty()) return values;
  values.clear();
  std::istringstream in(line);
  for (std::string token; in >> token;) {
    const std::optional<double> x = FortranNumber(token);
    if (!x) throw InputError(where + ": '" + token + "' is not a number");
    values.push_back(*x);
  }
  return values;
}

double Decode(const std::string& bytes, size_t at, size_t size, bool big_endian) {
  unsigned char b[8];
  std::memcpy(b, bytes.data() + at, size);
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + size);
  if (size == 4) {
    float f;
    std::memcpy(&f, b, 4);
    return f;
  }
  double d;
  std::memcpy(&d, b, 8);
  return d;
}

// The values of a dataset's record 12: ASCII lines up to the closing separator, or the
// announced bytes of a 58b dataset.
std::vector<double> DataValues(Reader& in, int ordinate_type, bool even, size_t count,
                               const std::vector<int>& binary_fields) {
  std::vector<double> values;
  if (binary_fields.empty()) {
    const std::vector<size_t> format = LineFormat(ordinate_type, even);
    for (std::string line;;) {
      line = in.RequireLine("a dataset 58's data (no closing -1)");
      if (IsSeparator(line)) break;
      const std::vector<double> row = DataLine(line, format, in.Where());
      values.insert(values.end(), row.begin(), row.end());
    }
  } else {
    const int byte_order = binary_fields[0], fp_format = binary_fields[1];
    if (byte_order != 1 && byte_order != 2)
      throw InputError(in.Where() + ": byte ordering " + std::to_string(byte_order) +
                       " (1 little endian, 2 big endian)");
    if (fp_format != 2)
      throw InputError(in.Where() + ": floating-point format " + std::to_string(fp_format) +
                       " is not IEEE 754 (2); DEC VMS and IBM 370 numbers are not read");
    const size_t size = ordinate_type == 2 || ordinate_type == 5 ? 4 : 8;
    const long announced = binary_fields[3];
    if (announced < 0 || static_cast<size_t>(announced) != count * size)
      throw InputError(in.Where() + ": the 58b line announces " + std::to_string(announced) +
                       " bytes; " + std::to_string(count) + " numbers of " + std::to_string(size) +
                       " bytes need " + std::to_string(count * size));
    const std::string bytes = in.Bytes(count * size, "the 58b line");
    for (size_t k = 0; k < count; ++k)
      values.push_back(Decode(bytes, k * size, size, byte_order == 2));
    std::string rest = in.RequireLine("a dataset 58b (no closing -1)");
    if (Trim(rest).empty()) rest = in.RequireLine("a dataset 58b (no closing -1)");
    if (!IsSeparator(rest))
      throw InputError(in.Where() +
                       ": the binary data are not followed by -1 (the byte count "
                       "does not match the data)");
  }
  if (values.size() != count)
    throw InputError(in.Where() + ": " + std::to_string(values.size()) +
                     " numbers, record 7 "
                     "announces " +
                     std::to_string(count));
  return values;
}

// Half a unit of the last digit a number was written with ("4.908739E-02": 5e-9); 0 for 0.
double HalfLastDigit(const std::string& text) {
  std::string t = Trim(text);
  const size_t e = t.find_first_of("EeDd");
  const std::string mantissa = t.substr(0, e);
  const size_t point = mantissa.find('.');
  const long decimals =
      point == std::string::npos ? 0 : static_cast<long>(mantissa.size() - point - 1);
  const std::optional<double> value = FortranNumber(t);
  if (!value || *value == 0) return 0;
  const long exponent =
      e == std::string::npos ? 0 : static_cast<long>(FortranNumber(t.substr(e + 1)).value_or(0));
  return 0.5 * std::pow(10.0, static_cast<double>(exponent - decimals));
}

// One dataset 58 after its dataset line; `binary_fields` are the 58b line's numbers.
Uff58Function ReadFunction(Reader& in, const std::vector<int>& binary_fields) {
  Uff58Function f;
  f.description = Trim(in.RequireLine("a dataset 58's ID lines"));
  f.id2 = Trim(in.RequireLine("a dataset 58's ID lines"));
  for (int k = 0; k < 3; ++k) in.RequireLine("a dataset 58's ID lines");
  const std::string r6 = in.RequireLine("a dataset 58's record 6");
  const std::string w6 = in.Where();
  f.function_type = IntegerField(Columns(r6, 0, 5), w6, "the function type");
  f.sequence = IntegerField(Columns(r6, 15, 5), w6, "the version number");
  f.response_name = Trim(Columns(r6, 31, 10));
  f.response_node = IntegerField(Columns(r6, 41, 10), w6, "the response node");
  f.response_direction = IntegerField(Columns(r6, 51, 4), w6, "the response direction");
  f.reference_name = Trim(Columns(r6, 56, 10));
  const std::string r7 = in.RequireLine("a dataset 58's record 7");
  const std::string w7 = in.Where();
  std::istringstream fields(r7);
  std::vector<double> form;
  std::vector<std::string> tokens;
  for (std::string token; fields >> token; tokens.push_back(token)) {
    const std::optional<double> x = FortranNumber(token);
    if (!x) throw InputError(w7 + ": record 7 field '" + token + "' is not a number");
    form.push_back(*x);
  }
  if (form.size() < 5)
    throw InputError(w7 + ": record 7 has " + std::to_string(form.size()) +
                     " fields (ordinate type, count, spacing, start, increment, z value)");
  const int ordinate_type = static_cast<int>(form[0]);
  if (form[0] != ordinate_type ||
      (ordinate_type != 2 && ordinate_type != 4 && ordinate_type != 5 && ordinate_type != 6))
    throw InputError(w7 + ": ordinate data type " + Trim(Columns(r7, 0, 10)) +
                     " (2/4 real single/double, 5/6 complex single/double)");
  if (!(form[1] >= 1 && form[1] <= 5e8 && form[1] == std::round(form[1])))
    throw InputError(w7 + ": " + Trim(Columns(r7, 10, 10)) + " values");
  const size_t points = static_cast<size_t>(form[1]);
  const bool even = form[2] == 1;
  f.start = form[3];
  f.increment = form[4];
  int type = 0;
  AxisRecord(in.RequireLine("a dataset 58's record 8"), in.Where(), &f.abscissa_type,
             &f.abscissa_label, &f.abscissa_unit);
  AxisRecord(in.RequireLine("a dataset 58's record 9"), in.Where(), &type, &f.ordinate_label,
             &f.ordinate_unit);
  in.RequireLine("a dataset 58's record 10");
  in.RequireLine("a dataset 58's record 11");
  const bool complex = ordinate_type >= 5;
  const size_t per_point = (complex ? 2 : 1) + (even ? 0 : 1);
  const std::vector<double> v =
      DataValues(in, ordinate_type, even, points * per_point, binary_fields);
  // The abscissa's digits: the start and step of record 7 (the k-th sample off by up to
  // error(start) + k·error(step)), or each value (E13.5 in ASCII; a float's 24 bits in 58b).
  if (even)
    f.abscissa_error =
        HalfLastDigit(tokens[3]) + static_cast<double>(points - 1) * HalfLastDigit(tokens[4]);
  for (size_t k = 0; k < points; ++k) {
    const double* p = v.data() + k * per_point;
    if (!even) {
      const double x = std::abs(*p);
      const bool single = ordinate_type == 2 || ordinate_type == 5;
      f.abscissa_error = std::max(
          f.abscissa_error, binary_fields.empty()
                                ? (x > 0 ? 0.5 * std::pow(10.0, std::floor(std::log10(x)) - 5) : 0)
                                : (single ? 6e-8 * x : 0.0));
      f.x.push_back(*p++);
    }
    if (complex)
      f.complex.emplace_back(p[0], p[1]);
    else
      f.real.push_back(p[0]);
  }
  return f;
}

std::string ReadBytes(const std::string& path) {
  RequireRegularFile(path);
  // The file is held in memory while it is parsed: beyond 2 GiB, split it into records.
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (!error && size > (std::uintmax_t{1} << 31))
    throw InputError(path + ": " + std::to_string(size >> 20) +
                     " MiB; UFF files are read whole, up to 2 GiB (write one file per record)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read '" + path + "'");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string ChannelName(const Uff58Function& f) {
  if (!f.description.empty() && f.description != "NONE") return f.description;
  return f.response_name + " " + std::to_string(f.response_node) + ":" +
         std::to_string(f.response_direction);
}

// Fixed-width E fields of the format: 7 significant digits where the sign's column is free.
std::string E13(double x) {
  char s[32];
  std::snprintf(s, sizeof s, x >= 0 ? "%13.6E" : "%13.5E", x);
  return s;
}
std::string E20(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%20.12E", x);
  return s;
}
std::string Padded(const std::string& s, size_t width) {
  return s.substr(0, width) + std::string(width - std::min(width, s.size()), ' ');
}
std::string RightAligned(long x, int width) {
  char s[32];
  std::snprintf(s, sizeof s, "%*ld", width, x);
  return s;
}

std::string AxisLine(int type, const std::string& label, const std::string& unit) {
  return RightAligned(type, 10) + "    0    0    0 " + Padded(label.empty() ? "NONE" : label, 20) +
         " " + Padded(unit.empty() ? "NONE" : unit, 20) + "\n";
}

void WriteFunction(std::ostream& out, const Uff58Function& f, bool binary) {
  const bool complex = !f.complex.empty(), even = f.x.empty();
  const size_t n = f.size();
  std::vector<double> values;
  for (size_t k = 0; k < n; ++k) {
    if (!even) values.push_back(f.x[k]);
    if (complex) {
      values.push_back(f.complex[k].real());
      values.push_back(f.complex[k].imag());
    } else {
      values.push_back(f.real[k]);
    }
  }
  out << "    -1\n    58";
  if (binary)
    out << "b     1     2          11" << RightAligned(static_cast<long>(8 * values.size()), 12)
        << "     0     0           0           0\n";
  else
    out << std::string(74, ' ') << "\n";
  const auto id = [](const std::string& s) { return Padded(s.empty() ? "NONE" : s, 80) + "\n"; };
  out << id(f.description) << id(f.id2) << id("NONE") << id("NONE") << id("NONE");
  out << RightAligned(f.function_type, 5) << RightAligned(1, 10) << RightAligned(f.sequence, 5)
      << RightAligned(0, 10) << " "
      << Padded(f.response_name.empty() ? "NONE" : f.response_name, 10)
      << RightAligned(f.response_node, 10) << RightAligned(f.response_direction, 4) << " "
      << Padded(f.reference_name.empty() ? "NONE" : f.reference_name, 10)
      << RightAligned(f.reference_node, 10) << RightAligned(f.reference_direction, 4) << "\n";
  out << RightAligned(complex ? 6 : 4, 10) << RightAligned(static_cast<long>(n), 10)
      << RightAligned(even ? 1 : 0, 10) << E13(even ? f.start : 0) << E13(even ? f.increment : 0)
      << E13(0) << "\n";
  out << AxisLine(f.abscissa_type, f.abscissa_label, f.abscissa_unit)
      << AxisLine(0, f.ordinate_label, f.ordinate_unit) << AxisLine(0, "NONE", "NONE")
      << AxisLine(0, "NONE", "NONE");
  if (binary) {
    for (double v : values) {
      unsigned char b[8];
      std::memcpy(b, &v, 8);
      if (std::endian::native == std::endian::big) std::reverse(b, b + 8);
      out.write(reinterpret_cast<const char*>(b), 8);
    }
  } else {
    // Record 12's cases 5/7 (even: 4E20.12), 6 (2(E13.5,E20.12)), 8 (E13.5,2E20.12).
    const size_t per_line = even ? 4 : (complex ? 3 : 4);
    for (size_t k = 0; k < values.size(); ++k) {
      const size_t column = k % per_line;
      const bool abscissa = !even && (complex ? column == 0 : column % 2 == 0);
      out << (abscissa ? E13(values[k]) : E20(values[k]));
      if (column + 1 == per_line || k + 1 == values.size()) out << "\n";
    }
  }
  out << "    -1\n";
}

}  // namespace

bool IsUffName(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".uff" || extension == ".unv";
}

bool IsUffFile(const std::string& path) {
  RequireRegularFile(path);
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (int k = 0; k < 100 && ReadTextLine(in, line, path); ++k)
    if (!Trim(line).empty()) return IsSeparator(line);
  return false;
}

std::vector<Uff58Function> ReadUff58(const std::string& path) {
  Reader in(ReadBytes(path), path);
  std::vector<Uff58Function> functions;
  std::string line;
  while (in.Line(&line)) {
    if (Trim(line).empty()) continue;
    if (!IsSeparator(line))
      throw InputError(in.Where() + ": '" + Trim(line).substr(0, 40) +
                       "' where a dataset should start (-1)");
    const std::string head = in.RequireLine("a dataset's number");
    std::istringstream fields(head);
    std::string number;
    fields >> number;
    const bool binary = !number.empty() && number.back() == 'b';
    if (binary) number.pop_back();
    std::vector<int> binary_fields;
    for (std::string token; binary && fields >> token;)
      binary_fields.push_back(
          IntegerField(token, in.Where(), "a field of the binary dataset line"));
    if (binary && binary_fields.size() < 4)
      throw InputError(in.Where() +
                       ": a binary dataset line needs byte order, format, ASCII "
                       "lines and bytes");
    if (number == "58") {
      functions.push_back(ReadFunction(in, binary_fields));
      continue;
    }
    // Another dataset: skip it (a binary one by its announced lines and bytes).
    if (binary) {
      for (int k = 0; k < binary_fields[2]; ++k) in.RequireLine("a binary dataset's header");
      in.Bytes(static_cast<size_t>(std::max(0, binary_fields[3])), "a binary dataset's line");
    }
    for (bool closed = false; !closed;) closed = IsSeparator(in.RequireLine("a dataset " + number));
  }
  if (functions.empty()) throw InputError(path + ": no dataset 58 (function at nodal DOF)");
  return functions;
}

std::vector<ChannelTable> ReadUffTimeRecords(const std::string& path) {
  std::vector<ChannelTable> tables;
  std::vector<std::vector<double>> columns;
  const auto close = [&]() {
    if (columns.empty()) return;
    ChannelTable& t = tables.back();
    t.values.resize(static_cast<Eigen::Index>(t.time.size()),
                    static_cast<Eigen::Index>(columns.size()));
    for (size_t c = 0; c < columns.size(); ++c)
      for (size_t i = 0; i < t.time.size(); ++i)
        t.values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) = columns[c][i];
    columns.clear();
  };
  int index = 0;
  for (const Uff58Function& f : ReadUff58(path)) {
    const std::string where =
        path + ", function " + std::to_string(++index) + " ('" + ChannelName(f) + "')";
    const bool time_axis = f.abscissa_type == 17 || f.abscissa_type == 0 || f.abscissa_type == 1;
    if (!(f.function_type == 1 || (f.function_type == 0 && time_axis)) || !time_axis)
      throw InputError(where + ": function type " + std::to_string(f.function_type) +
                       " on abscissa type " + std::to_string(f.abscissa_type) +
                       " is not a time record (type 1 on a time abscissa)");
    if (!f.complex.empty()) throw InputError(where + ": complex values are not a time record");
    std::vector<double> time = f.x;
    if (time.empty()) {
      if (!(f.increment > 0))
        throw InputError(where + ": abscissa increment " + MessageNumber(f.increment, 6) +
                         " (a time step must be > 0)");
      for (size_t k = 0; k < f.real.size(); ++k)
        time.push_back(f.start + static_cast<double>(k) * f.increment);
    }
    const std::string name = ChannelName(f);
    if (tables.empty() ||
        std::count(tables.back().names.begin(), tables.back().names.end(), name) > 0) {
      close();
      ChannelTable t;
      t.path = path + " record " + std::to_string(tables.size() + 1);
      t.time = time;
      tables.push_back(std::move(t));
    }
    ChannelTable& t = tables.back();
    t.time_error = std::max(t.time_error, f.abscissa_error);
    const double step = time.size() > 1 ? std::abs(time[1] - time[0]) : 1.0;
    bool same = time.size() == t.time.size();
    for (size_t k = 0; same && k < time.size(); ++k)
      same = std::abs(time[k] - t.time[k]) <= 1e-9 * step;
    if (!same)
      throw InputError(where + ": sampled at other times than '" + t.names.front() +
                       "' of the same record (" + std::to_string(time.size()) + " against " +
                       std::to_string(t.time.size()) + " samples)");
    t.names.push_back(name);
    columns.push_back(f.real);
  }
  close();
  return tables;
}

void WriteUff58(const std::string& path, const std::vector<Uff58Function>& functions, bool binary) {
  std::ofstream out(path, std::ios::binary);
  for (const Uff58Function& f : functions) WriteFunction(out, f, binary);
  if (!out) throw InputError("cannot write '" + path + "'");
}

double WriteTimeDataUff(const std::string& path, const TimeData& data, const std::string& comment,
                        bool binary) {
  std::vector<Uff58Function> functions;
  double rounding = 0;
  for (size_t r = 0; r < data.records.size(); ++r) {
    const TimeRecord& rec = data.records[r];
    Uff58Function f;
    f.sequence = static_cast<int>(r + 1);
    f.id2 = "record " + std::to_string(r + 1) +
            (rec.excitation_hz > 0 ? ", " + MessageNumber(rec.excitation_hz, 12) + " Hz" : "") +
            ", " + comment;
    const size_t n = rec.time.size();
    const double step = (rec.time.back() - rec.time.front()) / static_cast<double>(n - 1);
    bool even = true;
    for (size_t k = 0; even && k < n; ++k)
      even =
          std::abs(rec.time[k] - (rec.time.front() + static_cast<double>(k) * step)) <= 1e-9 * step;
    if (even) {
      f.start = *FortranNumber(E13(rec.time.front()));
      f.increment = *FortranNumber(E13(step));
      for (size_t k = 0; k < n; ++k)
        rounding = std::max(rounding,
                            std::abs(f.start + static_cast<double>(k) * f.increment - rec.time[k]));
    } else {
      f.x = rec.time;
      for (double t : rec.time)
        if (!binary) rounding = std::max(rounding, std::abs(*FortranNumber(E13(t)) - t));
    }
    const auto add = [&](const Eigen::MatrixXd& channels, const std::vector<std::string>& names,
                         const std::string& fallback) {
      for (Eigen::Index c = 0; c < channels.cols(); ++c) {
        f.description = ChannelNameOr(names, c, fallback);
        f.response_name = f.description;
        f.response_node = static_cast<int>(c + 1);
        f.real.assign(channels.col(c).data(), channels.col(c).data() + channels.rows());
        functions.push_back(f);
      }
    };
    add(rec.inputs, data.input_names, "u");
    add(rec.outputs, data.output_names, "y");
    add(rec.auxiliary, data.auxiliary_names, "a");
  }
  WriteUff58(path, functions, binary);
  return rounding;
}

}  // namespace ltp::cli
