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

#include "format.h"
#include "ltp/core/error.h"
#include "time_data_csv.h"

namespace ltp::cli {

namespace {

using nlohmann::json;

}  // namespace

ChartRecord::ChartRecord(std::string path, const SweepGrid& grid, int states, const json& identity,
                         bool resume)
    : path_(std::move(path)), grid_(grid), states_(states) {
  if (path_.empty()) {
    if (resume) throw InputError("--resume needs --csv FILE: the file of the interrupted sweep");
    return;
  }
  const std::string journal = journal_path();
  if (resume) {
    RequireRegularFile(journal);  // a directory, /dev/zero or a FIFO is not a journal
    std::ifstream in(journal, std::ios::binary);
    if (!in)
      throw InputError("--resume: no journal '" + journal + "' (the sweep of '" + path_ +
                       "' completed, or never started); run without --resume");
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    in.close();
    const size_t magic = sizeof(kJournalMagic) - 1;
    if (bytes.compare(0, magic, kJournalMagic) != 0)
      throw InputError("--resume: '" + journal +
                       "' is not a journal of this version of ltp; run without --resume");
    const std::vector<std::string> payloads = FramedPayloads(bytes, magic);
    const std::optional<std::string> header =
        payloads.empty() ? std::nullopt : DecodeHeader(payloads.front());
    if (!header) throw InputError("--resume: '" + journal + "' has no intact header record");
    // A header that is not JSON compares unequal to nothing (nlohmann's discarded value), so
    // it is refused by name, not waved through.
    const json recorded = json::parse(*header, nullptr, false);
    if (recorded.is_discarded())
      throw InputError("--resume: '" + journal +
                       "' has a damaged header record (its identity is not JSON); run without "
                       "--resume to start over");
    if (recorded != identity)
      throw InputError(
          "--resume: '" + journal +
          "' belongs to a different sweep (scene, "
          "parameters, sweep ranges or method differ); run without --resume to start over");
    Lock();
    // A record cut short by a kill, altered after the fact, or naming an index this grid does
    // not have (or a second time) is not a point: it is simply computed again.
    std::set<size_t> seen;
    PointReader reader;
    for (size_t k = 1; k < payloads.size(); ++k) {
      std::optional<SweepPoint> p = reader.Read(payloads[k]);
      if (!p || p->index >= grid_.size() || p->values != grid_.PointValues(p->index) ||
          !seen.insert(p->index).second)
        continue;
      resumed_.push_back(std::move(*p));
    }
    // Rewrite the journal with only the good records, then append to it.
    {
      std::ofstream out(journal, std::ios::binary | std::ios::trunc);
      out << kJournalMagic << JournalFrame(EncodeHeader(*header));
      for (const SweepPoint& p : resumed_) out << JournalRecord(p);
      if (!out) throw InputError("cannot write '" + journal + "'");
    }
    journal_.open(journal, std::ios::binary | std::ios::app);
    csv_.open(path_, std::ios::trunc);
    if (!csv_) throw InputError("cannot write '" + path_ + "'");
    csv_ << Header(states_);
    for (const SweepPoint& p : resumed_) csv_ << Row(p, nullptr, 0);
    csv_.flush();
  } else {
    Lock();
    journal_.open(journal, std::ios::binary | std::ios::trunc);
    if (!journal_) throw InputError("cannot write '" + journal + "'");
    journal_ << kJournalMagic << JournalFrame(EncodeHeader(identity.dump()));
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
  std::string r;
  r.reserve(128);
  for (double v : p.values) {
    AppendCsvNumber(r, v);
    r += ',';
  }
  AppendCsvNumber(r, p.max_real_exponent);
  r += ',';
  r += p.ok ? (p.verdict == StabilityVerdict::kUnstable ? "0" : "1") : "";
  r += ',';
  r += ToString(p.verdict);
  r += ',';
  if (p.error_estimate) AppendCsvNumber(r, *p.error_estimate);  // empty: not checked
  const auto cells = [&](double f, double re, double zeta) {
    if (std::isfinite(f)) {
      for (double x : {f, re, zeta}) {
        r += ',';
        AppendCsvNumber(r, x);
      }
    } else {
      r += ",,,";
    }
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
  r += ',';
  if (!p.failure.empty()) r += CsvText(p.failure);
  r += '\n';
  return r;
}

void ChartRecord::Add(const SweepPoint& point) {
  if (path_.empty()) return;
  std::string row = Row(point, nullptr, 0);
  // Most points carry no diagnostics: their record needs no shared state and is encoded before
  // the lock (two threads queued on it for a fifth of a 401 × 401 map's CSV time).
  std::string record;
  if (point.diagnostics.empty()) record = PointWriter::Record(point, JournalShapes());
  std::lock_guard<std::mutex> lock(mutex_);
  journal_ << (record.empty() ? JournalRecord(point) : record);
  csv_ << row;
  if (grid_.axes.size() == 2 && point.index < grid_.size()) {  // a map's final row is this one
    if (rows_.empty()) rows_.resize(grid_.size());
    rows_[point.index] = std::move(row);
  }
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
    for (size_t i = 0; i < sorted.size(); ++i) {
      const size_t index = sorted[i].index;
      if (!campbell && index < rows_.size() && !rows_[index].empty())
        out << rows_[index];
      else
        out << Row(sorted[i], campbell, i);
    }
    if (!out) throw InputError("cannot write '" + tmp + "'");
  }
  std::filesystem::rename(tmp, path_);
  std::filesystem::remove(journal_path());
}

std::string ChartRecord::JournalRecord(const SweepPoint& point) {
  return writer_.Records(point, JournalShapes());
}

// Whether process `pid` runs ltp (its /proc command name): a lock whose pid was reused by an
// unrelated process is stale. Without /proc, any live process counts.
static bool IsLtp(long pid) {
  std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
  std::string name;
  if (!(comm >> name)) return true;
  return name.rfind("ltp", 0) == 0 || name.rfind("cli_tests", 0) == 0;
}

// One writer per FILE: the lock file holds the writer's pid; a lock whose process is gone
// (kill -9) or is not ltp (its pid reused) is stale and taken over.
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
        (::kill(static_cast<pid_t>(owner), 0) == 0 || errno == EPERM) && IsLtp(owner))
      throw InputError("another ltp chart (process " + std::to_string(owner) + ") is writing '" +
                       path_ +
                       "'; wait for it, or use another --csv file (if it is not a chart "
                       "of this file, the lock is stale: remove '" +
                       lock + "')");
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
