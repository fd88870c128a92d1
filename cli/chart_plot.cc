#include "chart_plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

#include "format.h"
#include "ltp/core/error.h"
#include "plot.h"

namespace ltp::cli {

namespace {

constexpr double kPi = std::numbers::pi;
const char* kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf",
                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#000080", "#808000"};
constexpr size_t kColorCount = sizeof kColors / sizeof kColors[0];
// Filled and open markers at the computed points, cycled with the colours (every point on a
// sparse diagram such as an OpenFAST set; a subset on a dense sweep).
const int kPointTypes[] = {7, 5, 9, 11, 13, 4, 6, 8, 10, 12};
constexpr size_t kPointTypeCount = sizeof kPointTypes / sizeof kPointTypes[0];

// Line k's style: colour, marker at each point and, once the colours repeat, a dash pattern,
// so no two of up to kColorCount × 4 lines look alike.
// On a dense sweep every `pi`-th point carries its marker (about 25 per line).
std::string LineStyle(size_t k, size_t points) {
  return "lc rgb '" + std::string(kColors[k % kColorCount]) + "' pt " +
         std::to_string(kPointTypes[k % kPointTypeCount]) + " pi " +
         std::to_string(std::max<size_t>(1, points / 25)) + " dt " +
         std::to_string(1 + (k / kColorCount) % 4);
}

std::string V(double x) { return std::isfinite(x) ? Num(x, 9) : std::string("NaN"); }

// The title and, under it, the caption wrapped at ", " to lines of at most `width` characters,
// as the text of a double-quoted gnuplot title.
std::string TitleText(const std::string& title, const std::string& caption, size_t width) {
  std::string text = GnuplotEscape(title), line;
  size_t from = 0;
  while (from < caption.size()) {
    size_t end = caption.find(", ", from);
    end = end == std::string::npos ? caption.size() : end + 2;
    const std::string piece = caption.substr(from, end - from);
    if (!line.empty() && line.size() + piece.size() > width) {
      text += "\\n" + GnuplotEscape(line);
      line.clear();
    }
    line += piece;
    from = end;
  }
  if (!line.empty()) text += "\\n" + GnuplotEscape(line);
  return text;
}

// Bands over the unstable intervals (light red) and the weakly damped ones (light yellow),
// in both panels.
void Bands(std::ostringstream& g, const ChartPlotInput& in) {
  int id = 1;
  if (in.intervals)
    for (const auto& band : *in.intervals)
      g << "set object " << id++ << " rect from " << V(band.lo.value) << ", graph 0 to "
        << V(band.hi.value)
        << ", graph 1 behind fillcolor rgb '#f6c6c6' fillstyle solid 0.6 noborder\n";
  for (const auto& [lo, hi] : in.campbell->weakly_damped)
    g << "set object " << id++ << " rect from " << V(lo) << ", graph 0 to " << V(hi)
      << ", graph 1 behind fillcolor rgb '#fbf0c0' fillstyle solid 0.6 noborder\n";
}

// A legend entry: "3 support x 61%, zeta cyclic 37%", cut to fit beside the panel.
std::string LegendTitle(size_t k, const std::string& description) {
  std::string t = std::to_string(k + 1) + " " + description;
  if (t.size() > 62) t = t.substr(0, 60) + "…";
  return GnuplotEscape(t);
}

// Right margin (characters) that fits the longest legend entry.
int LegendMargin(const CampbellDiagram& d) {
  size_t longest = 36;  // the per-rev entry
  for (size_t k = 0; k < d.lines.size(); ++k)
    longest = std::max(longest, LegendTitle(k, d.lines[k].description).size());
  return static_cast<int>(std::min<size_t>(longest, 64) * 3 / 4 + 8);
}

// What the Campbell panels draw besides the mode lines.
struct CampbellExtras {
  double ytop = 1;       // top of the frequency panel
  bool lost = false;     // some line ends at a failed point ($L)
  bool compare = false;  // snapshot and averaged eigenvalues ($S, $A)
};

// The data blocks: $M (x, then per line frequency, Re λ, ζ in % and the sidebands f ± kΩp/2π), $R
// (per-rev lines), $X (crossings), $L (lost lines), $S/$A (frozen eigenvalues).
CampbellExtras CampbellData(const ChartPlotInput& in, std::ostringstream& g) {
  const CampbellDiagram& d = *in.campbell;
  const auto& points = *in.points;
  const size_t P = d.parameter.size();
  CampbellExtras x;
  g << "$M << EOD\n";
  double fmax = 0;
  for (size_t p = 0; p < P; ++p) {
    g << V(d.parameter[p]);
    const double fp = points[p].period > 0 ? 1.0 / points[p].period : NAN;  // Ωp/2π in Hz
    for (const CampbellLine& line : d.lines) {
      const double f = line.frequency_hz[p];
      if (std::isfinite(f)) fmax = std::max(fmax, f);
      g << " " << V(f) << " " << V(line.real_part[p]) << " " << V(100 * line.damping_ratio[p]);
      for (int s = 1; s <= in.sidebands; ++s) g << " " << V(f + s * fp) << " " << V(f - s * fp);
    }
    g << "\n";
  }
  g << "EOD\n";
  x.ytop = fmax > 0 ? 1.15 * fmax : 1.0;
  if (!d.per_rev.empty()) {
    g << "$R << EOD\n";
    for (size_t p = 0; p < P; ++p) {
      g << V(d.parameter[p]);
      for (int n : d.per_rev) g << " " << V(n * d.rotor_speed[p] / (2 * kPi));
      g << "\n";
    }
    g << "EOD\n";
  }
  if (!d.crossings.empty()) {
    g << "$X << EOD\n";
    for (const auto& c : d.crossings) g << V(c.parameter) << " " << V(c.frequency_hz) << "\n";
    g << "EOD\n";
  }
  for (const CampbellLine& line : d.lines) x.lost = x.lost || line.lost_after.has_value();
  if (x.lost) {
    g << "$L << EOD\n";
    for (const CampbellLine& line : d.lines)
      if (line.lost_after) {
        const size_t p = *line.lost_after;
        g << V(d.parameter[p]) << " " << V(line.frequency_hz[p]) << " " << V(line.real_part[p])
          << "\n";
      }
    g << "EOD\n";
  }
  x.compare = in.compare && !points.empty() && !points.front().snapshot_eigenvalues.empty();
  if (x.compare) {
    g << "$S << EOD\n";
    for (const SweepPoint& pt : points)
      for (const auto& e : pt.snapshot_eigenvalues)
        if (e.imag() >= 0) g << V(pt.values[0]) << " " << V(e.imag() / (2 * kPi)) << "\n";
    g << "EOD\n$A << EOD\n";
    for (const SweepPoint& pt : points)
      for (const auto& e : pt.averaged_eigenvalues)
        if (e.imag() >= 0) g << V(pt.values[0]) << " " << V(e.imag() / (2 * kPi)) << "\n";
    g << "EOD\n";
  }
  return x;
}

// "nP" where each per-rev line leaves the frequency panel (its last point below the top).
void PerRevLabels(const CampbellDiagram& d, double ytop, std::ostringstream& g) {
  const size_t P = d.parameter.size();
  for (size_t k = 0; k < d.per_rev.size(); ++k) {
    size_t last = P;
    for (size_t p = 0; p < P; ++p)
      if (d.per_rev[k] * d.rotor_speed[p] / (2 * kPi) <= ytop) last = p;
    if (last == P) continue;
    const bool right = last + 1 == P;
    g << "set label " << 100 + k << " '" << d.per_rev[k] << "P' at " << V(d.parameter[last]) << ", "
      << V(d.per_rev[k] * d.rotor_speed[last] / (2 * kPi))
      << (right ? " offset 0.5,0" : " offset -1,-0.6") << " font ',8' tc rgb '#606060'\n";
  }
}

// Top panel: sidebands (light), per-rev lines (dashed), the modes, crossings, lost lines and
// the frozen eigenvalues.
void FrequencyPanel(const ChartPlotInput& in, const CampbellExtras& x, std::ostringstream& g) {
  const CampbellDiagram& d = *in.campbell;
  const size_t L = d.lines.size();
  std::string shading;
  if (in.intervals && !in.intervals->empty()) shading += "; red: unstable";
  if (!d.weakly_damped.empty()) shading += "; yellow: weakly damped";
  const size_t every = std::max<size_t>(1, d.parameter.size() / 25);
  g << "set title '" << in.eigenvalues << ", tracked by MAC; markers: "
    << (every == 1 ? std::string("computed points")
                   : "one per " + std::to_string(every) + " computed points")
    << (d.per_rev.empty() ? "" : "; dashed: n·Ω/2π; circles: crossings") << shading << "'\n"
    << "set ylabel '"
    << (d.frequency == CampbellFrequency::kNatural ? "natural frequency |λ|/2π"
                                                   : "damped frequency Im λ/2π")
    << "  [Hz]'\nset yrange [0:" << V(x.ytop) << "]\n";
  PerRevLabels(d, x.ytop, g);
  std::ostringstream plot;
  plot << "plot ";
  bool first = true;
  auto add = [&](const std::string& item) {
    plot << (first ? "" : ", \\\n     ") << item;
    first = false;
  };
  const int stride = 3 + 2 * in.sidebands;
  for (size_t k = 0; k < L; ++k)
    for (int s = 0; s < 2 * in.sidebands; ++s)
      add("$M using 1:" + std::to_string(2 + k * stride + 3 + s) +
          " with lines lw 0.6 lc rgb '#e6e6e6' notitle");
  for (size_t k = 0; k < d.per_rev.size(); ++k) {
    // Multiples of the blade count excite the fixed frame: drawn darker.
    const bool blade = d.blades > 1 && d.per_rev[k] % d.blades == 0;
    add("$R using 1:" + std::to_string(2 + k) + " with lines dt 2 lw " + (blade ? "1.6" : "1") +
        " lc rgb '" + (blade ? "#404040" : "#a0a0a0") + "' " +
        (k == 0 ? "title 'n·Ω/2π" +
                      std::string(d.blades > 1 ? " (dark: multiples of " +
                                                     std::to_string(d.blades) + " blades)"
                                               : "") +
                      "'"
                : "notitle"));
  }
  for (size_t k = 0; k < L; ++k)
    add("$M using 1:" + std::to_string(2 + k * stride) + " with linespoints lw 2 ps 0.7 " +
        LineStyle(k, d.parameter.size()) + " title \"" + LegendTitle(k, d.lines[k].description) +
        "\"");
  if (!d.crossings.empty())
    add("$X using 1:2 with points pt 6 ps 1.2 lw 1.5 lc rgb '#000000' title 'crossings'");
  if (x.lost)
    add("$L using 1:2 with points pt 2 ps 1.6 lw 2 lc rgb '#d00000' title 'line lost (see "
        "output)'");
  if (x.compare) {
    add("$S using 1:2 with points pt 7 ps 0.25 lc rgb '#444444' title 'snapshot A(0)'");
    add("$A using 1:2 with points pt 6 ps 0.35 lc rgb '#e08000' title 'averaged A_0'");
  }
  g << plot.str() << "\n";
  for (size_t k = 0; k < d.per_rev.size(); ++k) g << "unset label " << 100 + k << "\n";
}

// Bottom panel: the damping ratio ζ in % (MBC3) or Re λ (Floquet) of every line, in the
// frequency panel's styles.
void DampingPanel(const ChartPlotInput& in, const CampbellExtras& x, std::ostringstream& g) {
  const CampbellDiagram& d = *in.campbell;
  const int stride = 3 + 2 * in.sidebands;
  const bool zeta = in.damping_ratio_panel;
  if (zeta)
    g << "set title 'Damping diagram: damping ratio ζ = −Re λ/|λ| of the " << in.real_parts
      << " (below 0: unstable)'\nset ylabel 'ζ  [%]'\n";
  else
    g << "set title 'Damping diagram: " << in.real_parts << " (above 0: unstable)'\n"
      << "set ylabel 'Re λ  [1/s]'\n";
  g << "set autoscale y\nset yrange [*:*]\n"
    << "set arrow 100 from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#000000' lw 1\n";
  g << "plot ";
  for (size_t k = 0; k < d.lines.size(); ++k)
    g << (k == 0 ? "" : ", \\\n     ") << "$M using 1:" << 2 + k * stride + (zeta ? 2 : 1)
      << " with linespoints lw 2 ps 0.7 " << LineStyle(k, d.parameter.size()) << " notitle";
  if (x.lost && !zeta)
    g << ", \\\n     $L using 1:3 with points pt 2 ps 1.6 lw 2 lc rgb '#d00000' notitle";
  g << "\n";
}

std::string CampbellScript(const ChartPlotInput& in, const std::string& file) {
  std::ostringstream g;
  g << GnuplotTerminal(file, 1400, 950) << "set output '" << file << "'\n";
  const CampbellExtras x = CampbellData(in, g);
  g << "set multiplot layout 2,1 title \"" << TitleText(in.title, in.caption, 150)
    << "\" font ',13'\n"
    << "set grid\nset xlabel \"" << GnuplotEscape(in.axis_labels.at(0))
    << "\"\nset key outside right top font ',9'\n"
    << "set lmargin 12\nset rmargin " << LegendMargin(*in.campbell) << "\n";
  Bands(g, in);
  FrequencyPanel(in, x, g);
  DampingPanel(in, x, g);
  g << "unset multiplot\n";
  return g.str();
}

// The colour scale of a map: symmetric around 0 so stable (blue) and unstable (red) read at a
// glance; clipped at the 98th percentile of |max Re λ| so a few deep points do not wash it out.
double MapColourScale(const std::vector<SweepPoint>& points) {
  std::vector<double> mags;
  for (const SweepPoint& p : points)
    if (p.ok) mags.push_back(std::abs(p.max_real_exponent));
  double scale = 1;
  if (!mags.empty()) {
    std::sort(mags.begin(), mags.end());
    scale = mags[static_cast<size_t>(0.98 * double(mags.size() - 1))];
    if (!(scale > 0)) scale = mags.back() > 0 ? mags.back() : 1;
  }
  return scale;
}

// The data blocks of a map, horizontal axis `xa`: $G (the grid, x fastest), $P and $M (the
// curves following multipliers +1 and −1, one block per curve), $B (refined boundary points on
// no curve). Returns which of $P, $M, $B hold data.
std::array<bool, 3> MapData(const ChartPlotInput& in, size_t xa, std::ostringstream& g) {
  const SweepGrid& grid = *in.grid;
  const size_t ya = 1 - xa, n0 = grid.values[0].size();
  g << "$G << EOD\n";
  for (size_t iy = 0; iy < grid.values[ya].size(); ++iy) {
    for (size_t ix = 0; ix < grid.values[xa].size(); ++ix) {
      const size_t i0 = xa == 0 ? ix : iy, i1 = xa == 0 ? iy : ix;
      const SweepPoint& p = (*in.points)[i0 + n0 * i1];
      g << V(p.values[xa]) << " " << V(p.values[ya]) << " "
        << (p.ok ? V(p.max_real_exponent) : "NaN") << "\n";
    }
    g << "\n";
  }
  g << "EOD\n";
  std::array<bool, 3> have{false, false, false};
  for (int k = 0; k < 2 && in.curves; ++k) {
    const BoundaryKind kind = k == 0 ? BoundaryKind::kRealPlusOne : BoundaryKind::kRealMinusOne;
    std::ostringstream block;
    for (const BoundaryCurve& c : in.curves->curves) {
      if (c.kind != kind) continue;
      for (const auto& p : c.points) block << V(p[xa]) << " " << V(p[ya]) << "\n";
      block << "\n\n";
      have[static_cast<size_t>(k)] = true;
    }
    if (have[static_cast<size_t>(k)])
      g << (k == 0 ? "$P" : "$M") << " << EOD\n" << block.str() << "EOD\n";
  }
  std::ostringstream dots;
  if (in.boundary) {
    std::vector<char> traced(in.boundary->size(), in.curves != nullptr);
    if (in.curves)
      for (size_t i : in.curves->untraced) traced[i] = 0;
    for (size_t i = 0; i < in.boundary->size(); ++i) {
      const BoundaryPoint& b = (*in.boundary)[i];
      if (!b.estimate.refined || traced[i]) continue;
      dots << V(b.values[xa]) << " " << V(b.values[ya]) << "\n";
      have[2] = true;
    }
  }
  if (have[2]) g << "$B << EOD\n" << dots.str() << "EOD\n";
  return have;
}

std::string MapScript(const ChartPlotInput& in, const std::string& file) {
  const SweepGrid& grid = *in.grid;
  const size_t xa = in.x_axis == 1 ? 1 : 0, ya = 1 - xa;
  const double scale = MapColourScale(*in.points);
  std::ostringstream g;
  g << GnuplotTerminal(file, 1000, 900) << "set output '" << file << "'\n";
  const std::array<bool, 3> have = MapData(in, xa, g);
  g << "set title \"" << TitleText(in.title, in.caption, 110) << "\" font ',12'\n"
    << "set xlabel \"" << GnuplotEscape(in.axis_labels.at(xa)) << "\"\n"
    << "set ylabel \"" << GnuplotEscape(in.axis_labels.at(ya)) << "\"\n"
    << "set cblabel 'max Re λ  [1/s]   (blue: stable, white: marginal, red: unstable)'\n"
    << "set palette defined (-1 '#2166ac', -1e-4 '#a6cee3', 0 '#ffffff', 1e-4 '#fddbc7', 1 "
       "'#b2182b')\n"
    << "set cbrange [" << V(-scale) << ":" << V(scale) << "]\n"
    << "set xrange [" << V(grid.values[xa].front()) << ":" << V(grid.values[xa].back()) << "]\n"
    << "set yrange [" << V(grid.values[ya].front()) << ":" << V(grid.values[ya].back()) << "]\n"
    << "set key outside below center horizontal font ',10'\nset tics out\n";
  g << "plot $G using 1:2:3 with image notitle";
  if (have[0])
    g << ", \\\n     $P using 1:2 with lines lw 1.6 lc rgb '#000000' title 'transition curve: "
         "multiplier +1 (T-periodic solution)'";
  if (have[1])
    g << ", \\\n     $M using 1:2 with lines lw 1.6 dt 2 lc rgb '#000000' title 'transition curve: "
         "multiplier −1 (2T-periodic solution)'";
  if (have[2])
    g << ", \\\n     $B using 1:2 with points pt 7 ps 0.35 lc rgb '#404040' title '"
      << (in.curves ? "refined boundary points on no curve (complex multipliers)"
                    : "refined boundary points")
      << "'";
  g << "\n";
  return g.str();
}

}  // namespace

std::string ChartPlotScript(const ChartPlotInput& in, const std::string& file) {
  if (!in.grid || in.grid->axes.size() == 1) return CampbellScript(in, file);
  return MapScript(in, file);
}

std::string DrawChart(const ChartPlotInput& in, const std::string& file) {
  GnuplotTerminal(file, 1, 1);  // a bad extension is an error either way
  const std::string script = ChartPlotScript(in, file);
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    const std::string gp = file + ".gp";
    std::ofstream out(gp);
    out << script;
    if (!out) throw InputError("cannot write '" + gp + "'");
    return "gnuplot is not installed: wrote the plot script '" + gp +
           "' (data inline); render it with `gnuplot " + gp +
           "` after `apt-get install gnuplot-nox`";
  }
  RunGnuplot(file, script);
  return "";
}

}  // namespace ltp::cli
