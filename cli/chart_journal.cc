// The binary chart journal (format in chart_journal.h).
#include "chart_journal.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <type_traits>
#include <utility>

namespace ltp::cli {
namespace {

static_assert(std::endian::native == std::endian::little, "the journal is little-endian");

// A payload larger than this is not one ltp wrote (a point with 1000 states and its shapes is
// ~16 MB): the length field is damaged.
constexpr std::uint32_t kMaxPayload = 1u << 28;

// FNV-1a (64 bit): detects a damaged or altered record, not an adversary.
std::uint64_t Fnv1a(const char* data, size_t size) {
  std::uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

class Writer {
 public:
  explicit Writer(char type) { out_.push_back(type); }
  template <typename T>
  void Put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out_.append(bytes, sizeof(T));
  }
  void Complex(std::complex<double> z) {
    Put(z.real());
    Put(z.imag());
  }
  void Text(const std::string& s) {
    Put(static_cast<std::uint32_t>(s.size()));
    out_ += s;
  }
  std::string Take() { return std::move(out_); }

 private:
  std::string out_;
};

// Reads fields in order; any read past the end marks the payload bad (ok() false).
class Reader {
 public:
  Reader(const std::string& payload, char type)
      : data_(payload), at_(1), ok_(!payload.empty() && payload[0] == type) {}
  template <typename T>
  T Get() {
    T value{};
    if (!ok_ || data_.size() - at_ < sizeof(T)) {
      ok_ = false;
      return value;
    }
    std::memcpy(&value, data_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::complex<double> Complex() {
    const double re = Get<double>();
    return {re, Get<double>()};
  }
  /// A count of items of at least `item_bytes` each: no more than the bytes left can hold.
  size_t Count(size_t item_bytes) {
    const std::uint32_t n = Get<std::uint32_t>();
    if (!ok_ || n > (data_.size() - at_) / std::max<size_t>(item_bytes, 1)) ok_ = false;
    return ok_ ? n : 0;
  }
  std::string Text() {
    const size_t n = Count(1);
    if (!ok_) return {};
    std::string s = data_.substr(at_, n);
    at_ += n;
    return s;
  }
  bool ok() const { return ok_; }
  bool done() const { return ok_ && at_ == data_.size(); }

 private:
  const std::string& data_;
  size_t at_;
  bool ok_;
};

}  // namespace

std::string JournalFrame(const std::string& payload) {
  std::string frame(sizeof(std::uint32_t) + sizeof(std::uint64_t), '\0');
  const auto size = static_cast<std::uint32_t>(payload.size());
  const std::uint64_t sum = Fnv1a(payload.data(), payload.size());
  std::memcpy(frame.data(), &size, sizeof size);
  std::memcpy(frame.data() + sizeof size, &sum, sizeof sum);
  return frame + payload;
}

std::vector<std::string> FramedPayloads(const std::string& bytes, size_t from) {
  std::vector<std::string> payloads;
  constexpr size_t kFrame = sizeof(std::uint32_t) + sizeof(std::uint64_t);
  for (size_t at = from; at <= bytes.size() && bytes.size() - at >= kFrame;) {
    std::uint32_t size = 0;
    std::uint64_t sum = 0;
    std::memcpy(&size, bytes.data() + at, sizeof size);
    std::memcpy(&sum, bytes.data() + at + sizeof size, sizeof sum);
    at += kFrame;
    if (size > kMaxPayload || bytes.size() - at < size) break;  // torn or damaged length
    if (Fnv1a(bytes.data() + at, size) == sum) payloads.emplace_back(bytes, at, size);
    at += size;
  }
  return payloads;
}

namespace {

std::string EncodePoint(const SweepPoint& p, const std::vector<std::uint32_t>& diagnostic_ids,
                        bool with_shapes) {
  Writer w('P');
  w.Put(static_cast<std::uint64_t>(p.index));
  w.Put(static_cast<std::uint8_t>(p.ok));
  w.Put(static_cast<std::int32_t>(p.verdict));
  // An unchecked point's estimate is stored as -1 (estimates are never negative).
  for (double x : {p.period, p.rotor_speed, p.max_real_exponent, p.max_log_multiplier,
                   p.error_estimate.value_or(-1.0), p.elapsed_s})
    w.Put(x);
  w.Put(static_cast<std::uint32_t>(p.values.size()));
  for (double v : p.values) w.Put(v);
  w.Text(p.failure);
  w.Put(static_cast<std::uint32_t>(p.modes.size()));
  for (const FloquetMode& m : p.modes) {
    w.Complex(m.exponent);
    w.Complex(m.log_multiplier);
    w.Put(m.frequency_hz);
    w.Put(m.damping_ratio);
    w.Put(static_cast<std::int32_t>(m.branch));
  }
  const bool shapes = with_shapes && p.shapes.size() > 0;
  w.Put(static_cast<std::uint32_t>(shapes ? p.shapes.rows() : 0));
  w.Put(static_cast<std::uint32_t>(shapes ? p.shapes.cols() : 0));
  if (shapes)
    for (Eigen::Index k = 0; k < p.shapes.cols(); ++k)
      for (Eigen::Index i = 0; i < p.shapes.rows(); ++i) w.Complex(p.shapes(i, k));
  for (const auto* e : {&p.snapshot_eigenvalues, &p.averaged_eigenvalues}) {
    w.Put(static_cast<std::uint32_t>(e->size()));
    for (const auto& z : *e) w.Complex(z);
  }
  w.Put(static_cast<std::uint32_t>(diagnostic_ids.size()));
  for (std::uint32_t id : diagnostic_ids) w.Put(id);
  return w.Take();
}

struct DecodedPoint {
  SweepPoint point;
  std::vector<std::uint32_t> diagnostic_ids;
};

std::optional<DecodedPoint> DecodePoint(const std::string& payload) {
  Reader r(payload, 'P');
  DecodedPoint d;
  SweepPoint& p = d.point;
  p.index = static_cast<size_t>(r.Get<std::uint64_t>());
  p.ok = r.Get<std::uint8_t>() != 0;
  const auto verdict = r.Get<std::int32_t>();
  if (verdict < 0 || verdict > static_cast<std::int32_t>(StabilityVerdict::kFailed)) return {};
  p.verdict = static_cast<StabilityVerdict>(verdict);
  double estimate = -1;
  for (double* x : {&p.period, &p.rotor_speed, &p.max_real_exponent, &p.max_log_multiplier,
                    &estimate, &p.elapsed_s})
    *x = r.Get<double>();
  if (estimate >= 0) p.error_estimate = estimate;
  p.values.resize(r.Count(sizeof(double)));
  for (double& v : p.values) v = r.Get<double>();
  p.failure = r.Text();
  p.modes.resize(r.Count(6 * sizeof(double)));
  for (FloquetMode& m : p.modes) {
    m.exponent = r.Complex();
    m.log_multiplier = r.Complex();
    m.frequency_hz = r.Get<double>();
    m.damping_ratio = r.Get<double>();
    m.branch = r.Get<std::int32_t>();
  }
  const size_t rows = r.Get<std::uint32_t>(), cols = r.Count(0);
  if (!r.ok() || (rows > 0 && cols > payload.size() / (16 * rows))) return {};
  p.shapes.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  for (Eigen::Index k = 0; k < p.shapes.cols(); ++k)
    for (Eigen::Index i = 0; i < p.shapes.rows(); ++i) p.shapes(i, k) = r.Complex();
  for (auto* e : {&p.snapshot_eigenvalues, &p.averaged_eigenvalues}) {
    e->resize(r.Count(2 * sizeof(double)));
    for (auto& z : *e) z = r.Complex();
  }
  d.diagnostic_ids.resize(r.Count(sizeof(std::uint32_t)));
  for (std::uint32_t& id : d.diagnostic_ids) id = r.Get<std::uint32_t>();
  if (!r.done()) return {};
  return d;
}

std::string EncodeDiagnostic(std::uint32_t id, const Diagnostic& d) {
  Writer w('D');
  w.Put(id);
  w.Put(static_cast<std::uint32_t>(d.code));
  w.Put(static_cast<std::uint8_t>(d.severity));
  w.Text(d.text);
  return w.Take();
}

std::optional<std::pair<std::uint32_t, Diagnostic>> DecodeDiagnostic(const std::string& payload) {
  Reader r(payload, 'D');
  const auto id = r.Get<std::uint32_t>();
  const auto code = r.Get<std::uint32_t>();
  const auto severity = r.Get<std::uint8_t>();
  std::string text = r.Text();
  if (!r.done() || code >= static_cast<std::uint32_t>(DiagnosticCode::kCount) ||
      severity > static_cast<std::uint8_t>(Severity::kFailure))
    return {};
  return std::make_pair(id, Diagnostic{static_cast<DiagnosticCode>(code),
                                       static_cast<Severity>(severity), std::move(text)});
}

}  // namespace

std::string PointWriter::Records(const SweepPoint& point, bool with_shapes) {
  std::string definitions;
  std::vector<std::uint32_t> ids;
  for (const Diagnostic& d : point.diagnostics) {
    const auto next = static_cast<std::uint32_t>(ids_.size());
    const auto [it, added] = ids_.emplace(std::tuple{d.code, d.severity, d.text}, next);
    if (added) definitions += JournalFrame(EncodeDiagnostic(it->second, d));
    ids.push_back(it->second);
  }
  return definitions + JournalFrame(EncodePoint(point, ids, with_shapes));
}

std::string PointWriter::Record(const SweepPoint& point, bool with_shapes) {
  return JournalFrame(EncodePoint(point, {}, with_shapes));
}

std::optional<SweepPoint> PointReader::Read(const std::string& payload) {
  if (const auto d = DecodeDiagnostic(payload)) {
    diagnostics_[d->first] = d->second;
    return std::nullopt;
  }
  std::optional<DecodedPoint> decoded = DecodePoint(payload);
  if (!decoded) return std::nullopt;
  for (std::uint32_t id : decoded->diagnostic_ids) {
    const auto it = diagnostics_.find(id);
    if (it == diagnostics_.end()) return std::nullopt;
    decoded->point.diagnostics.push_back(it->second);
  }
  return std::move(decoded->point);
}

std::string EncodeHeader(const std::string& identity_json) {
  Writer w('H');
  w.Text(identity_json);
  return w.Take();
}

std::optional<std::string> DecodeHeader(const std::string& payload) {
  Reader r(payload, 'H');
  std::string text = r.Text();
  if (!r.done()) return {};
  return text;
}

}  // namespace ltp::cli
