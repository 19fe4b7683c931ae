// Charts drawn by gnuplot (Debian's gnuplot-nox), run as a subprocess on a script that carries its
// own data (inline data blocks): no shell, no temporary data files beside the script, the output
// read back as SVG text.
#pragma once

#include <cstddef>
#include <string>

namespace vstcal {

// Runs `gnuplot SCRIPT` with the script in a private temporary file and returns what it writes on
// stdout (the script sets `set terminal svg` and `set output`). The script is at most
// kMaxGnuplotScriptBytes and the output at most kMaxGnuplotOutputBytes (more is a bug: the
// callers bound their data). Throws InputError when gnuplot is not installed ("install
// gnuplot-nox"), InternalError when it fails (with its first error line).
std::string RunGnuplot(const std::string& script);

inline constexpr size_t kMaxGnuplotScriptBytes = size_t{16} << 20;
inline constexpr size_t kMaxGnuplotOutputBytes = size_t{64} << 20;

// A string as a gnuplot double-quoted literal: backslashes, quotes, control characters escaped,
// so that a view or file name cannot end the string and inject commands.
std::string GnuplotQuoted(const std::string& text);

// The first lines of every vstcal chart script: an SVG of `width`×`height` px on white, a light
// grid, the key below the plot.
std::string SvgChartHeader(int width, int height);
// The k-th colour of the charts' palette (cycling), as "#rrggbb".
const char* ChartColour(size_t k);

}  // namespace vstcal
