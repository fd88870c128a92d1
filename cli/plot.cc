#include "plot.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "format.h"
#include "ltp/core/error.h"

namespace ltp::cli {

std::string GnuplotEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '_' || c == '^' || c == '{' || c == '}' || c == '@') out += "\\\\";
    out += c;
  }
  return out;
}

std::string GnuplotTerminal(const std::string& file, int width, int height) {
  const std::string ext = std::filesystem::path(file).extension().string();
  std::ostringstream s;
  if (ext == ".svg") {
    s << "set terminal svg size " << width << "," << height
      << " dynamic enhanced font 'DejaVu Sans,12' background rgb 'white'\n";
  } else if (ext == ".png") {
    s << "set terminal pngcairo size " << width << "," << height
      << " enhanced font 'DejaVu Sans,11' background rgb 'white'\n";
  } else if (ext == ".pdf") {
    // Vector output for papers: pdfcairo, sized in inches (100 pixels to the inch).
    s << "set terminal pdfcairo size " << width / 100.0 << "in," << height / 100.0
      << "in enhanced font 'DejaVu Sans,10' background rgb 'white'\n";
  } else {
    throw InputError("plot file '" + file + "' must end in .svg, .png or .pdf");
  }
  return s.str();
}

void RunGnuplot(const std::string& output_file, const std::string& script) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw InputError("cannot draw '" + output_file +
                     "': gnuplot is not installed (apt-get install gnuplot-nox)");
  if (std::filesystem::path(output_file).extension() == ".pdf" &&
      std::system("gnuplot -e 'set terminal pdfcairo' >/dev/null 2>&1") != 0)
    throw InputError("cannot draw '" + output_file +
                     "': this gnuplot has no pdfcairo terminal (Debian's gnuplot-nox, -qt and "
                     "-x11 have it); use .svg or .png, or convert the SVG");
  char path[] = "/tmp/ltp-plot-XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) throw InputError("cannot create a temporary file for gnuplot");
  close(fd);
  {
    std::ofstream f(path);
    f << script;
  }
  const std::string cmd = "gnuplot '" + std::string(path) + "' 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string messages;
  if (pipe) {
    char buf[512];
    while (fgets(buf, sizeof buf, pipe)) messages += buf;
  }
  const int status = pipe ? pclose(pipe) : -1;
  std::remove(path);
  if (status != 0)
    throw InputError("gnuplot failed to draw '" + output_file + "': " + messages.substr(0, 300));
}

void PlotFloquet(const FloquetResult& r, const std::string& title, const std::string& file) {
  std::ostringstream s;
  s << GnuplotTerminal(file, 1100, 520) << "set output '" << file << "'\n"
    << "set multiplot layout 1,2 title \"Floquet analysis: " << title << "  (K = " << r.segments
    << ", " << ToString(r.integrator) << ")\"\n";
  // Exponents.
  s << "$EXP << EOD\n";
  for (const auto& m : r.modes) s << m.exponent.real() << " " << m.frequency_hz << "\n";
  s << "EOD\n"
    << "set title 'Floquet exponents (physical branch)'\nset xlabel 'Re λ  [1/s]'\n"
    << "set ylabel 'frequency Im λ/2π  [Hz]'\nset grid\nset key below\n"
    << "set arrow 1 from 0, graph 0 to 0, graph 1 nohead dt 2 lc rgb '#aa0000'\n"
    << "set offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1\n"
    << "plot $EXP using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'λ_k', "
       "NaN with lines dt 2 lc rgb '#aa0000' title 'stability boundary Re λ = 0'\n"
    << "unset arrow 1\nset offsets 0,0,0,0\n";
  // Harmonic energy of each mode shape.
  const int H = r.mode_harmonics;
  if (!r.mode_fourier.empty()) {
    s << "$HARM << EOD\n";
    for (int v = -H; v <= H; ++v) {
      s << v;
      for (int k = 0; k < r.states; ++k) {
        double total = 0;
        for (int w = -H; w <= H; ++w) total += r.mode_fourier[w + H].col(k).squaredNorm();
        const double e = total > 0 ? r.mode_fourier[v + H].col(k).squaredNorm() / total : 0;
        s << " " << std::max(e, 1e-300);
      }
      s << "\n";
    }
    s << "EOD\n"
      << "set title 'Fourier energy of the periodic mode shapes ξ_k(t)'\n"
      << "set xlabel 'harmonic v  (ξ_k(t) = Σ ξ_{k,v} e^{j v Ωp t})'\nset ylabel 'energy "
         "fraction'\n"
      << "set logscale y\nset format y '10^{%L}'\nset yrange [1e-16:2]\nset key below maxrows 3\n"
      << "set xrange [" << -std::min(H, 12) << ":" << std::min(H, 12) << "]\n"
      << "plot ";
    const int shown = std::min(r.states, 10);
    for (int k = 0; k < shown; ++k)
      s << (k ? ", " : "") << "$HARM using 1:" << k + 2
        << " with linespoints pt 7 ps 0.6 title 'mode " << k + 1 << " ("
        << Num(r.modes[k].frequency_hz, 4) << " Hz)'";
    s << "\n";
  }
  s << "unset multiplot\n";
  RunGnuplot(file, s.str());
}

}  // namespace ltp::cli
