#include "chart_record.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <set>
#include <sstream>

#include "ltp/core/error.h"

namespace ltp::cli {

namespace {

using nlohmann::json;

// JSON has no NaN or infinity: those travel as strings.
json Number(double x) {
  if (std::isfinite(x)) return x;
  return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
}
double FromNumber(const json& j) {
  if (j.is_number()) return j.get<double>();
  const std::string s = j.get<std::string>();
  if (s == "inf") return INFINITY;
  if (s == "-inf") return -INFINITY;
  return NAN;
}

StabilityVerdict VerdictFrom(const std::string& s) {
  if (s == "stable") return StabilityVerdict::kStable;
  if (s == "marginal") return StabilityVerdict::kMarginal;
  if (s == "unstable") return StabilityVerdict::kUnstable;
  return StabilityVerdict::kFailed;
}

std::string CsvText(std::string s) {
  for (char& c : s)
    if (c == '"' || c == '\n') c = '\'';
  return "\"" + s + "\"";
}

std::string Full(double x) {
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  std::ostringstream s;
  s << std::setprecision(12) << x;
  return s.str();
}

// FNV-1a (64 bit) of a journal line: detects a forged or damaged record, not an adversary.
std::string Checksum(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  std::ostringstream s;
  s << std::hex << std::setw(16) << std::setfill('0') << h;
  return s.str();
}

std::string JournalLine(const json& j) {
  const std::string text = j.dump();
  return text + "\t" + Checksum(text) + "\n";
}

// The JSON of a journal line whose checksum matches; nullopt for a torn or altered line.
std::optional<json> ParseJournalLine(const std::string& line) {
  const size_t tab = line.rfind('\t');
  if (tab == std::string::npos) return std::nullopt;
  const std::string text = line.substr(0, tab);
  if (Checksum(text) != line.substr(tab + 1)) return std::nullopt;
  try {
    return json::parse(text);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

json PointToJson(const SweepPoint& p, bool with_shapes) {
  json j = {{"index", p.index},
            {"values", json::array()},
            {"ok", p.ok},
            {"verdict", std::string(ToString(p.verdict))},
            {"period", Number(p.period)},
            {"max_real_exponent", Number(p.max_real_exponent)},
            {"max_log_multiplier", Number(p.max_log_multiplier)},
            {"error_estimate", Number(p.error_estimate)},
            {"elapsed_s", p.elapsed_s}};
  for (double v : p.values) j["values"].push_back(Number(v));
  if (!p.failure.empty()) j["failure"] = p.failure;
  if (std::isfinite(p.rotor_speed)) j["rotor_speed"] = Number(p.rotor_speed);
  if (!p.modes.empty()) {
    json& modes = j["modes"];
    for (const FloquetMode& m : p.modes)
      modes.push_back({Number(m.exponent.real()), Number(m.exponent.imag()), Number(m.frequency_hz),
                       Number(m.damping_ratio), Number(m.log_multiplier.real()),
                       Number(m.log_multiplier.imag()), m.branch});
  }
  if (with_shapes && p.shapes.size()) {
    json& shapes = j["shapes"];
    for (Eigen::Index k = 0; k < p.shapes.cols(); ++k) {
      json col = json::array();
      for (Eigen::Index i = 0; i < p.shapes.rows(); ++i)
        col.push_back({Number(p.shapes(i, k).real()), Number(p.shapes(i, k).imag())});
      shapes.push_back(col);
    }
  }
  auto eigenvalues = [](const std::vector<std::complex<double>>& e) {
    json a = json::array();
    for (const auto& x : e) a.push_back({Number(x.real()), Number(x.imag())});
    return a;
  };
  if (!p.snapshot_eigenvalues.empty()) j["snapshot"] = eigenvalues(p.snapshot_eigenvalues);
  if (!p.averaged_eigenvalues.empty()) j["averaged"] = eigenvalues(p.averaged_eigenvalues);
  if (!p.diagnostics.empty()) j["diagnostics"] = p.diagnostics;
  return j;
}

SweepPoint PointFromJson(const json& j) {
  SweepPoint p;
  const json empty = json::array();
  auto field = [&](const char* key) -> const json& { return j.contains(key) ? j.at(key) : empty; };
  p.index = j.at("index").get<size_t>();
  for (const auto& v : j.at("values")) p.values.push_back(FromNumber(v));
  p.ok = j.at("ok").get<bool>();
  p.failure = j.value("failure", std::string());
  p.verdict = VerdictFrom(j.at("verdict").get<std::string>());
  p.period = FromNumber(j.at("period"));
  if (j.contains("rotor_speed")) p.rotor_speed = FromNumber(j.at("rotor_speed"));
  p.max_real_exponent = FromNumber(j.at("max_real_exponent"));
  p.max_log_multiplier = FromNumber(j.at("max_log_multiplier"));
  p.error_estimate = FromNumber(j.at("error_estimate"));
  for (const auto& m : field("modes")) {
    FloquetMode mode;
    mode.exponent = {FromNumber(m.at(0)), FromNumber(m.at(1))};
    mode.frequency_hz = FromNumber(m.at(2));
    mode.damping_ratio = FromNumber(m.at(3));
    mode.log_multiplier = {FromNumber(m.at(4)), FromNumber(m.at(5))};
    mode.branch = m.at(6).get<int>();
    p.modes.push_back(mode);
  }
  const json& shapes = field("shapes");
  if (!shapes.empty()) {
    p.shapes.resize(static_cast<Eigen::Index>(shapes.at(0).size()),
                    static_cast<Eigen::Index>(shapes.size()));
    for (size_t k = 0; k < shapes.size(); ++k)
      for (size_t i = 0; i < shapes[k].size(); ++i)
        p.shapes(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = {
            FromNumber(shapes[k][i].at(0)), FromNumber(shapes[k][i].at(1))};
  }
  for (const auto& x : field("snapshot"))
    p.snapshot_eigenvalues.emplace_back(FromNumber(x.at(0)), FromNumber(x.at(1)));
  for (const auto& x : field("averaged"))
    p.averaged_eigenvalues.emplace_back(FromNumber(x.at(0)), FromNumber(x.at(1)));
  for (const auto& d : field("diagnostics")) p.diagnostics.push_back(d.get<std::string>());
  p.elapsed_s = j.at("elapsed_s").get<double>();
  return p;
}

ChartRecord::ChartRecord(std::string path, const SweepGrid& grid, int states, const json& identity,
                         bool resume)
    : path_(std::move(path)), grid_(grid), states_(states) {
  if (path_.empty()) {
    if (resume) throw InputError("--resume needs --csv FILE: the file of the interrupted sweep");
    return;
  }
  const std::string journal = journal_path();
  if (resume) {
    std::ifstream in(journal);
    if (!in)
      throw InputError("--resume: no journal '" + journal + "' (the sweep of '" + path_ +
                       "' completed, or never started); run without --resume");
    std::string line;
    if (!std::getline(in, line)) throw InputError("--resume: journal '" + journal + "' is empty");
    const std::optional<json> header = ParseJournalLine(line);
    if (!header) throw InputError("--resume: '" + journal + "' line 1 is not a journal header");
    if (header->value("identity", json()) != identity)
      throw InputError(
          "--resume: '" + journal +
          "' belongs to a different sweep (scene, "
          "parameters, sweep ranges or method differ); run without --resume to start over");
    Lock();
    // A line cut short by a kill, altered after the fact, or naming an index this grid does
    // not have (or a second time) is not a point: it is simply computed again.
    std::set<size_t> seen;
    std::map<int, std::string> diagnostic_texts;
    while (std::getline(in, line)) {
      const std::optional<json> j = ParseJournalLine(line);
      if (!j) continue;
      try {
        if (j->contains("diagnostic")) {
          diagnostic_texts[j->at("diagnostic").get<int>()] = j->at("text").get<std::string>();
          continue;
        }
        json point = *j;
        if (point.contains("diagnostics")) {  // ids → texts; an unknown id drops the point
          json texts = json::array();
          for (const json& id : point.at("diagnostics"))
            texts.push_back(diagnostic_texts.at(id.get<int>()));
          point["diagnostics"] = texts;
        }
        SweepPoint p = PointFromJson(point);
        if (p.index >= grid_.size() || p.values != grid_.PointValues(p.index) ||
            !seen.insert(p.index).second)
          continue;
        resumed_.push_back(std::move(p));
      } catch (const std::exception&) {
      }
    }
    in.close();
    // Rewrite the journal with only the good records, then append to it.
    {
      std::ofstream out(journal, std::ios::trunc);
      out << JournalLine(*header);
      for (const SweepPoint& p : resumed_) out << JournalRecord(p);
      if (!out) throw InputError("cannot write '" + journal + "'");
    }
    journal_.open(journal, std::ios::app);
    csv_.open(path_, std::ios::trunc);
    if (!csv_) throw InputError("cannot write '" + path_ + "'");
    csv_ << Header(states_);
    for (const SweepPoint& p : resumed_) csv_ << Row(p, nullptr, 0);
    csv_.flush();
  } else {
    Lock();
    journal_.open(journal, std::ios::trunc);
    if (!journal_) throw InputError("cannot write '" + journal + "'");
    journal_ << JournalLine(json{{"identity", identity}});
    journal_.flush();
    csv_.open(path_, std::ios::trunc);
    if (!csv_) throw InputError("cannot write '" + path_ + "'");
    csv_ << Header(states_);
    csv_.flush();
  }
}

std::string ChartRecord::Header(int modes) const {
  std::ostringstream h;
  for (const auto& axis : grid_.axes) h << axis.name << ",";
  h << "max_real_exponent,stable,verdict,error_estimate";
  if (grid_.axes.size() == 1)
    for (int k = 1; k <= modes; ++k) h << ",freq_hz_" << k << ",real_" << k << ",damping_" << k;
  h << ",failure\n";
  return h.str();
}

std::string ChartRecord::Row(const SweepPoint& p, const CampbellDiagram* campbell, size_t i) const {
  std::ostringstream r;
  for (double v : p.values) r << Full(v) << ",";
  r << Full(p.max_real_exponent) << ","
    << (p.ok ? (p.verdict == StabilityVerdict::kUnstable ? "0" : "1") : "") << ","
    << ToString(p.verdict) << "," << Full(p.error_estimate);
  const auto cells = [&](double f, double re, double zeta) {
    if (std::isfinite(f))
      r << "," << Full(f) << "," << Full(re) << "," << Full(zeta);
    else
      r << ",,,";
  };
  if (campbell) {
    for (const CampbellLine& line : campbell->lines)
      cells(line.frequency_hz[i], line.real_part[i], line.damping_ratio[i]);
  } else if (grid_.axes.size() == 1) {
    for (int k = 0; k < states_; ++k) {
      if (k < static_cast<int>(p.modes.size())) {
        const FloquetMode& m = p.modes[static_cast<size_t>(k)];
        cells(m.frequency_hz, m.exponent.real(), m.damping_ratio);
      } else {
        cells(NAN, NAN, NAN);
      }
    }
  }
  r << "," << (p.failure.empty() ? "" : CsvText(p.failure)) << "\n";
  return r.str();
}

void ChartRecord::Add(const SweepPoint& point) {
  if (path_.empty()) return;
  const std::string row = Row(point, nullptr, 0);
  std::lock_guard<std::mutex> lock(mutex_);
  journal_ << JournalRecord(point);
  csv_ << row;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ > std::chrono::milliseconds(200)) {
    journal_.flush();
    csv_.flush();
    last_flush_ = now;
  }
  if (!journal_ || !csv_) throw InputError("cannot write '" + path_ + "' (disk full?)");
}

void ChartRecord::Finish(const std::vector<SweepPoint>& sorted, const CampbellDiagram* campbell) {
  if (path_.empty()) return;
  csv_.close();
  journal_.close();
  // Write beside, then rename: an interruption here leaves the old file and the journal.
  const std::string tmp = path_ + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << Header(campbell ? static_cast<int>(campbell->lines.size()) : states_);
    for (size_t i = 0; i < sorted.size(); ++i) out << Row(sorted[i], campbell, i);
    if (!out) throw InputError("cannot write '" + tmp + "'");
  }
  std::filesystem::rename(tmp, path_);
  std::filesystem::remove(journal_path());
}

std::string ChartRecord::JournalRecord(const SweepPoint& point) {
  std::string definitions;
  json ids = json::array();
  for (const std::string& d : point.diagnostics) {
    auto [it, added] = diagnostic_ids_.emplace(d, static_cast<int>(diagnostic_ids_.size()));
    if (added) definitions += JournalLine(json{{"diagnostic", it->second}, {"text", d}});
    ids.push_back(it->second);
  }
  json j = PointToJson(point, grid_.axes.size() == 1);  // only 1-D sweeps track by shapes
  if (!ids.empty()) j["diagnostics"] = ids;
  return definitions + JournalLine(j);
}

// One writer per FILE: the lock file holds the writer's pid; a lock whose process is gone
// (kill -9) is stale and taken over.
void ChartRecord::Lock() {
  const std::string lock = path_ + ".lock";
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int fd = ::open(lock.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0) {
      const std::string pid = std::to_string(::getpid()) + "\n";
      const ssize_t written = ::write(fd, pid.data(), pid.size());
      ::close(fd);
      if (written != static_cast<ssize_t>(pid.size()))
        throw InputError("cannot write '" + lock + "'");
      locked_ = true;
      return;
    }
    std::ifstream in(lock);
    long owner = 0;
    in >> owner;
    if (owner > 0 && owner != ::getpid() &&
        (::kill(static_cast<pid_t>(owner), 0) == 0 || errno == EPERM))
      throw InputError("another ltp chart (process " + std::to_string(owner) + ") is writing '" +
                       path_ + "'; wait for it, or use another --csv file");
    std::filesystem::remove(lock);  // stale: its writer is gone
  }
  throw InputError("cannot lock '" + path_ + "' (" + lock + ")");
}

ChartRecord::~ChartRecord() {
  if (locked_) {
    std::error_code ignored;
    std::filesystem::remove(path_ + ".lock", ignored);
  }
}

}  // namespace ltp::cli
