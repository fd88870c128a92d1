#pragma once
// Sweep points as binary records: the journal of `ltp chart --csv FILE` (FILE.journal: every
// completed point, appended as it completes, so that `--resume` computes only the missing
// ones) and the points MPI ranks send to rank 0. Doubles travel bit for bit, so a resumed sweep
// reproduces the uninterrupted one exactly; about a third of the size of the same points in
// JSON and read back with no parsing of decimal text.
//
//   file    = magic "ltp-journal 3\n", then records
//   record  = u32 payload length, u64 FNV-1a of the payload, payload     (little-endian)
//   payload = 'H' identity JSON text                 (first record: which sweep)
//           | 'D' u32 id, u32 code, u8 severity, text (a diagnostic, written once)
//           | 'P' point                               (see EncodePoint)
//
// Reading stops at a record that runs past the end of the file (torn by a kill) or whose length
// is implausible; a record whose checksum does not match (altered after the fact) is skipped.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "ltp/studies/sweep.h"

namespace ltp::cli {

inline constexpr char kJournalMagic[] = "ltp-journal 3\n";

/// One framed record around `payload`.
std::string JournalFrame(const std::string& payload);

/// The payloads of the intact records in `bytes` from `from` on, in order. Records with a bad
/// checksum are left out; a torn tail ends the list.
std::vector<std::string> FramedPayloads(const std::string& bytes, size_t from = 0);

/// Points to records: a diagnostic is written once ('D'), the points that carry it refer to its
/// id. `with_shapes` false leaves out the mode shapes.
class PointWriter {
 public:
  /// A point's records, its diagnostics not written before first. Not thread-safe: the
  /// diagnostics' ids are shared.
  std::string Records(const SweepPoint& point, bool with_shapes);
  /// The record of a point without diagnostics (Records without the shared ids): any thread.
  static std::string Record(const SweepPoint& point, bool with_shapes);

 private:
  std::map<std::tuple<DiagnosticCode, Severity, std::string>, std::uint32_t> ids_;
};

/// Records back to points, in the order PointWriter wrote them.
class PointReader {
 public:
  /// A 'D' payload is remembered (nullopt); a 'P' payload is its point, nullopt when it is not
  /// well formed or refers to a diagnostic not seen before; other payloads are nullopt.
  std::optional<SweepPoint> Read(const std::string& payload);

 private:
  std::map<std::uint32_t, Diagnostic> diagnostics_;
};

/// The 'H' payload: which sweep a journal belongs to.
std::string EncodeHeader(const std::string& identity_json);
std::optional<std::string> DecodeHeader(const std::string& payload);

}  // namespace ltp::cli
