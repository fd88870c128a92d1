#include "chart_plot.h"

#include <algorithm>
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
const char* kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                         "#17becf", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22"};

std::string V(double x) { return std::isfinite(x) ? Num(x, 9) : std::string("NaN"); }

// Light red bands over the unstable intervals, in both panels.
void IntervalRects(std::ostringstream& g, const std::vector<UnstableInterval>& intervals) {
  int id = 1;
  for (const auto& in : intervals)
    g << "set object " << id++ << " rect from " << V(in.lo.value) << ", graph 0 to "
      << V(in.hi.value) << ", graph 1 behind fillcolor rgb '#f6c6c6' fillstyle solid 0.6 noborder\n";
}

std::string CampbellScript(const ChartPlotInput& in, const std::string& file) {
  const auto& points = *in.points;
  const auto& labels = in.tracking->labels;
  const int n = points.empty() ? 0 : static_cast<int>(labels.front().size());
  std::ostringstream g;
  g << GnuplotTerminal(file, 1000, 900) << "set output '" << file << "'\n";
  // $M: x, then per label: frequency (Hz, NaN when negative), Re λ, and the sideband
  // frequencies f ± kΩp/2π.
  g << "$M << EOD\n";
  double fmax = 0;
  for (size_t p = 0; p < points.size(); ++p) {
    const SweepPoint& pt = points[p];
    g << V(pt.values[0]);
    const double fp = pt.period > 0 ? 1.0 / pt.period : NAN;  // Ωp/2π in Hz
    for (int k = 0; k < n; ++k) {
      const int j = p < labels.size() && k < static_cast<int>(labels[p].size()) ? labels[p][k] : -1;
      double f = NAN, re = NAN;
      if (pt.ok && j >= 0 && j < static_cast<int>(pt.modes.size())) {
        f = in.tracking->frequency_hz[p][k];
        re = pt.modes[j].exponent.real();
      }
      if (f < -1e-9) f = NAN;  // the negative half of a conjugate pair says nothing new
      if (std::isfinite(f)) fmax = std::max(fmax, f);
      g << " " << V(f) << " " << V(re);
      for (int s = 1; s <= in.sidebands; ++s) g << " " << V(f + s * fp) << " " << V(f - s * fp);
    }
    g << "\n";
  }
  g << "EOD\n";
  const bool compare = in.compare && !points.empty() && !points.front().snapshot_eigenvalues.empty();
  if (compare) {
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
  const int cols = 1 + n * (2 + 2 * in.sidebands);
  (void)cols;
  const std::string xlabel = GnuplotEscape(in.axis_labels.at(0));
  g << "set multiplot layout 2,1 title \"" << GnuplotEscape(in.title) << "\" font ',13'\n"
    << "set grid\nset xlabel \"" << xlabel << "\"\nset key outside right top\n"
    << "set lmargin 12\nset rmargin 28\n";
  if (in.intervals) IntervalRects(g, *in.intervals);
  g << "set title 'Floquet frequencies (tracked by MAC, branch kept continuous); faint: sidebands f ± kΩp/2π"
    << (in.intervals && !in.intervals->empty() ? "; red bands: unstable" : "") << "'\n"
    << "set ylabel 'frequency  [Hz]'\nset yrange [0:" << V(fmax > 0 ? 1.15 * fmax : 1.0) << "]\n";
  std::ostringstream plot;
  plot << "plot ";
  bool first = true;
  auto add = [&](const std::string& item) {
    plot << (first ? "" : ", \\\n     ") << item;
    first = false;
  };
  const int stride = 2 + 2 * in.sidebands;
  for (int k = 0; k < n; ++k) {
    const int fcol = 2 + k * stride;
    for (int s = 0; s < 2 * in.sidebands; ++s)
      add("$M using 1:" + std::to_string(fcol + 2 + s) + " with lines lw 0.8 lc rgb '#c8c8c8' notitle");
  }
  for (int k = 0; k < n; ++k) {
    const int fcol = 2 + k * stride;
    add("$M using 1:" + std::to_string(fcol) + " with lines lw 2 lc rgb '" + kColors[k % 10] +
        "' title 'mode " + std::to_string(k + 1) + "'");
  }
  if (compare) {
    add("$S using 1:2 with points pt 7 ps 0.25 lc rgb '#444444' title 'snapshot A(0)'");
    add("$A using 1:2 with points pt 6 ps 0.35 lc rgb '#e08000' title 'averaged A_0'");
  }
  g << plot.str() << "\n";
  g << "set title 'Damping diagram: real parts of the Floquet exponents (above 0: unstable)'\n"
    << "set ylabel 'Re λ  [1/s]'\nset autoscale y\nset yrange [*:*]\n"
    << "set arrow 100 from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#000000' lw 1\n";
  std::ostringstream damp;
  damp << "plot ";
  first = true;
  for (int k = 0; k < n; ++k) {
    const int fcol = 2 + k * stride;
    damp << (first ? "" : ", \\\n     ") << "$M using 1:" << fcol + 1 << " with lines lw 2 lc rgb '"
         << kColors[k % 10] << "' title 'mode " << k + 1 << "'";
    first = false;
  }
  g << damp.str() << "\nunset multiplot\n";
  return g.str();
}

std::string MapScript(const ChartPlotInput& in, const std::string& file) {
  const SweepGrid& grid = *in.grid;
  const auto& points = *in.points;
  const size_t n0 = grid.values[0].size(), n1 = grid.values[1].size();
  // Colour scale: symmetric around 0 so stable (blue) and unstable (red) read at a glance;
  // clipped at the 98th percentile of |max Re λ| so a few deep points do not wash it out.
  std::vector<double> mags;
  for (const SweepPoint& p : points)
    if (p.ok) mags.push_back(std::abs(p.max_real_exponent));
  double scale = 1;
  if (!mags.empty()) {
    std::sort(mags.begin(), mags.end());
    scale = mags[static_cast<size_t>(0.98 * double(mags.size() - 1))];
    if (!(scale > 0)) scale = mags.back() > 0 ? mags.back() : 1;
  }
  std::ostringstream g;
  g << GnuplotTerminal(file, 1000, 820) << "set output '" << file << "'\n$G << EOD\n";
  for (size_t i1 = 0; i1 < n1; ++i1) {
    for (size_t i0 = 0; i0 < n0; ++i0) {
      const SweepPoint& p = points[i0 + n0 * i1];
      g << V(p.values[0]) << " " << V(p.values[1]) << " " << (p.ok ? V(p.max_real_exponent) : "NaN") << "\n";
    }
    g << "\n";
  }
  g << "EOD\n";
  const bool boundary = in.boundary && !in.boundary->empty();
  if (boundary) {
    g << "$B << EOD\n";
    for (const auto& b : *in.boundary)
      if (b.estimate.refined) g << V(b.values[0]) << " " << V(b.values[1]) << "\n";
    g << "EOD\n";
  }
  g << "set title \"" << GnuplotEscape(in.title) << "\" font ',13'\n"
    << "set xlabel \"" << GnuplotEscape(in.axis_labels.at(0)) << "\"\n"
    << "set ylabel \"" << GnuplotEscape(in.axis_labels.at(1)) << "\"\n"
    << "set cblabel 'max Re λ  [1/s]   (blue: stable, white: marginal, red: unstable)'\n"
    << "set palette defined (-1 '#2166ac', -1e-4 '#a6cee3', 0 '#ffffff', 1e-4 '#fddbc7', 1 '#b2182b')\n"
    << "set cbrange [" << V(-scale) << ":" << V(scale) << "]\n"
    << "set xrange [" << V(grid.values[0].front()) << ":" << V(grid.values[0].back()) << "]\n"
    << "set yrange [" << V(grid.values[1].front()) << ":" << V(grid.values[1].back()) << "]\n"
    << "set key top left opaque box\nset tics out\n";
  g << "plot $G using 1:2:3 with image notitle";
  if (boundary) g << ", $B using 1:2 with points pt 7 ps 0.35 lc rgb '#000000' title 'refined boundary points'";
  g << "\n";
  return g.str();
}

}  // namespace

std::string ChartPlotScript(const ChartPlotInput& in, const std::string& file) {
  if (in.grid->axes.size() == 1) return CampbellScript(in, file);
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
           "' (data inline); render it with `gnuplot " + gp + "` after `apt-get install gnuplot-nox`";
  }
  RunGnuplot(file, script);
  return "";
}

}  // namespace ltp::cli
