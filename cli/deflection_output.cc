#include "deflection_output.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <utility>

#include "format.h"
#include "ltp/core/error.h"
#include "plot.h"

namespace ltp::cli {

void WriteDeflectionCsv(const std::string& file, const ModeDeflections& deflections) {
  std::ofstream csv(file);
  if (!csv) throw InputError("cannot write '" + file + "'");
  csv << "mode,t,body,node,x_rest,y_rest,z_rest,x,y,z\n";
  std::string row;
  for (const ModeDeflection& m : deflections.modes)
    for (const DeflectionFrame& f : m.frames)
      for (size_t b = 0; b < deflections.bodies.size(); ++b)
        for (int j = 0; j < f.rest[b].cols(); ++j) {
          row = std::to_string(m.mode + 1) + ",";
          AppendCsvNumber(row, f.t);
          row += "," + CsvText(deflections.bodies[b]) + "," + std::to_string(j);
          for (int i = 0; i < 3; ++i) {
            row += ",";
            AppendCsvNumber(row, f.rest[b](i, j));
          }
          for (int i = 0; i < 3; ++i) {
            row += ",";
            AppendCsvNumber(row, f.moved[b](i, j));
          }
          csv << row << "\n";
        }
  if (!csv) throw InputError("cannot write '" + file + "'");
}

namespace {

constexpr int kMaxPlottedModes = 4;

// The three views of a row: horizontal and vertical coordinate (0 = x, 1 = y, 2 = z), title.
struct View {
  int horizontal, vertical;
  const char* title;
};
constexpr View kViews[] = {{0, 2, "seen along the shaft"},
                           {0, 1, "seen from the side"},
                           {2, 1, "seen along the cantilever"}};

// One data block per body (gnuplot `index`): each frame's polyline on the structure as it
// stands at t = 0 (or, `rest`, its rest shape), frames apart by a blank line.
std::string Blocks(const ModeDeflection& m, size_t bodies, const View& v, bool rest) {
  std::ostringstream s;
  s.precision(9);
  for (size_t body = 0; body < bodies; ++body) {
    for (const DeflectionFrame& f : m.frames) {
      const Eigen::Matrix3Xd& p = rest ? m.frames.front().rest[body] : f.standing[body];
      for (int j = 0; j < p.cols(); ++j) s << p(v.horizontal, j) << " " << p(v.vertical, j) << "\n";
      s << "\n";
      if (rest) break;
    }
    s << "\n";
  }
  return s.str();
}

// Row title: the mode, its frequency and damping, what carries it.
std::string ModeTitle(const ModeDeflection& m) {
  const double hz = m.exponent.imag() / (2 * std::numbers::pi);
  const double zeta = std::abs(m.exponent) > 0 ? -m.exponent.real() / std::abs(m.exponent) : 0;
  std::ostringstream s;
  s << "mode " << m.mode + 1 << ": " << Num(hz, 4) << " Hz, ζ " << Num(100 * zeta, 3) << " %";
  if (!m.description.empty()) s << " — " << m.description;
  return GnuplotEscape(s.str());
}

// One range for every axis of every view, so that the views share a scale (ratio 1).
std::pair<double, double> CommonRange(const ModeDeflections& d) {
  double lo = 0, hi = 0;
  for (const ModeDeflection& m : d.modes)
    for (const DeflectionFrame& f : m.frames)
      for (const Eigen::Matrix3Xd& p : f.standing) {
        lo = std::min(lo, p.minCoeff());
        hi = std::max(hi, p.maxCoeff());
      }
  const double pad = 0.05 * (hi - lo);
  return {lo - pad, hi + pad};
}

}  // namespace

void PlotDeflection(const std::string& file, const ModeDeflections& deflections) {
  const int rows = static_cast<int>(deflections.modes.size());
  if (rows > kMaxPlottedModes)
    throw InputError("--deflection-plot draws at most " + std::to_string(kMaxPlottedModes) +
                     " modes, " + std::to_string(rows) +
                     " chosen: pick them with --deflection-mode");
  static const char* colours[] = {"1f77b4", "333333", "d62728", "2ca02c", "9467bd"};
  const size_t bodies = deflections.bodies.size();
  const auto [lo, hi] = CommonRange(deflections);
  const int height = 380;
  std::ostringstream s;
  s << GnuplotTerminal(file, 1250, 70 + height * rows) << "set output '" << file << "'\n"
    << "set multiplot title \"each mode's deflection over one period, drawn on the structure as "
       "it stands at t = 0 (rest shape dashed)\\n"
    << GnuplotEscape(deflections.axes) << "\"\n"
    << "set size ratio -1\nset grid\nset xrange [" << lo << ":" << hi << "]\nset yrange [" << lo
    << ":" << hi << "]\nset format x '%.2g'\nset format y '%.2g'\n";
  const double top = 1 - 70.0 / (70 + height * rows), row_height = top / rows;
  for (int r = 0; r < rows; ++r) {
    const ModeDeflection& m = deflections.modes[static_cast<size_t>(r)];
    s << "set label 1 \"" << ModeTitle(m) << "\" at screen 0.5, screen "
      << top - r * row_height - 0.01 << " center font ',12'\n";
    for (int v = 0; v < 3; ++v) {
      const View& view = kViews[v];
      const std::string tag = std::to_string(r) + std::to_string(v);
      s << "$M" << tag << " << EOD\n"
        << Blocks(m, bodies, view, false) << "EOD\n$R" << tag << " << EOD\n"
        << Blocks(m, bodies, view, true) << "EOD\n"
        << "set origin " << v * 0.31 << "," << top - (r + 1) * row_height << "\nset size "
        << (v == 2 ? 0.38 : 0.31) << "," << row_height * 0.93 << "\n"
        << "set title '" << view.title << "' font ',10'\nset xlabel '"
        << "xyz"[view.horizontal] << " [m]'\nset ylabel '"
        << "xyz"[view.vertical] << " [m]'\n"
        << (v == 2 ? "set key outside right center\n" : "unset key\n") << "plot ";
      for (size_t body = 0; body < bodies; ++body)
        s << "$M" << tag << " index " << body << " with lines lw 1 lc rgb '#70" << colours[body % 5]
          << "' title '" << GnuplotEscape(deflections.bodies[body]) << "', $R" << tag << " index "
          << body << " with lines dt 2 lw 1.5 lc rgb '#777777' notitle"
          << (body + 1 < bodies ? ", " : "\n");
      if (v == 0) s << "unset label 1\n";
    }
  }
  s << "unset multiplot\n";
  RunGnuplot(file, s.str());
}

}  // namespace ltp::cli
