#pragma once
// Pictures through gnuplot (PNG, SVG or PDF, chosen by the file name's extension).
#include <string>

#include "ltp/floquet/floquet.h"

namespace ltp::cli {

/// Runs a gnuplot script with the given inline data blocks. @throws InputError if the file
/// extension is not .svg/.png/.pdf, gnuplot is missing or fails, or (.pdf) it has no pdfcairo.
void RunGnuplot(const std::string& output_file, const std::string& script);

/// Text for a double-quoted gnuplot title in enhanced mode: '_', '^', '{', '}' and '@' are
/// taken literally (names like z_tip otherwise turn into subscripts).
std::string GnuplotEscape(const std::string& text);

/// Terminal line for the extension of `file` ("set terminal svg ..." / "pngcairo" / "pdfcairo").
std::string GnuplotTerminal(const std::string& file, int width, int height);

/// Left: Floquet exponents (Re λ vs frequency, the stability boundary Re λ = 0).
/// Right: Fourier energy of each periodic mode shape per harmonic (the branch choice).
void PlotFloquet(const FloquetResult& result, const std::string& title, const std::string& file);

}  // namespace ltp::cli
