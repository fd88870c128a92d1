#pragma once
// The files of `ltp chart --csv FILE`: nothing computed is lost.
//
//   FILE                 one CSV row per point, appended and flushed as points complete
//                        (completion order, modes in each point's own order) and rewritten
//                        sorted by grid index with one column set per Campbell line when the sweep
//                        ends;
//   FILE.journal         every completed point as one checksummed binary record (format in
//                        chart_journal.h), flushed; `--resume` reads it and computes only the
//                        missing points. A record that is torn, forged (checksum), or names a
//                        grid index the sweep does not have (or has twice) is dropped and its
//                        point computed again. Removed when the sweep completes. Compact: a
//                        diagnostic text is written once and points refer to it by id (a point
//                        whose id is unknown is recomputed); mode shapes are kept only where
//                        they are used (1-D sweeps track modes by them).
//   FILE.lock            held while a sweep writes FILE (with the writer's process id): a
//                        second `ltp chart` on the same FILE is refused, a stale lock left by a
//                        killed process is taken over.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "chart_journal.h"
#include "ltp/studies/campbell.h"
#include "ltp/studies/sweep.h"

namespace ltp::cli {

class ChartRecord {
 public:
  /// `path` empty: nothing is written. `resume`: load the journal of an interrupted run of
  /// the same sweep (grid and scene checked against its header line).
  /// @throws InputError when the files cannot be written, or on --resume without a journal
  /// or with one from a different sweep.
  ChartRecord(std::string path, const SweepGrid& grid, int states, const nlohmann::json& identity,
              bool resume);
  ~ChartRecord();
  ChartRecord(const ChartRecord&) = delete;
  ChartRecord& operator=(const ChartRecord&) = delete;

  /// Points already done (from the journal on --resume), in no particular order.
  const std::vector<SweepPoint>& resumed() const { return resumed_; }
  /// Appends a completed point to the journal and the CSV; thread-safe (the formatting runs
  /// outside the lock). Both files are flushed at least every 0.2 s and at Finish, so a killed
  /// sweep loses at most the last fraction of a second.
  void Add(const SweepPoint& point);
  /// Rewrites the CSV sorted, with one column set per Campbell line (1-D: `campbell`, numbered
  /// as in its legend), and removes the journal.
  void Finish(const std::vector<SweepPoint>& sorted, const CampbellDiagram* campbell);
  const std::string& path() const { return path_; }
  std::string journal_path() const { return path_ + ".journal"; }

 private:
  /// Per-mode columns for `modes` modes (1-D sweeps).
  std::string Header(int modes) const;
  /// Point `i` of the sweep: with `campbell`, its lines at that point (final file); without,
  /// the point's own modes in its own order and chosen branch (streamed rows).
  std::string Row(const SweepPoint& point, const CampbellDiagram* campbell, size_t i) const;

  void Lock();
  /// The journal records of a point (its new diagnostic texts first). Call with mutex_ held.
  std::string JournalRecord(const SweepPoint& point);
  /// Whether journal records keep mode shapes: only 1-D sweeps track modes by them.
  bool JournalShapes() const { return grid_.axes.size() == 1; }

  PointWriter writer_;
  std::string path_;
  bool locked_ = false;
  const SweepGrid& grid_;
  int states_ = 0;
  std::vector<SweepPoint> resumed_;
  std::ofstream csv_, journal_;
  /// Maps: every streamed row by grid index; the sorted file reuses them (a map's row does not
  /// depend on the other points, unlike a Campbell diagram's line columns).
  std::vector<std::string> rows_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
};

}  // namespace ltp::cli
