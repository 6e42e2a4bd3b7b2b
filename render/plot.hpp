// Figures drawn by gnuplot (from Debian's gnuplot-nox): the CLI builds a gnuplot script with
// the data inline and pipes it to gnuplot, once for PNG (pngcairo) and once for SVG. Texts
// (titles, labels) reach gnuplot only as data: printable characters in single-quoted strings.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace nocdyn::render {

struct PlotSeries {
    std::string label;
    std::vector<double> x, y;
    std::string style = "lines";  ///< gnuplot style, e.g. "lines dt 2 lw 2"
    /// Further columns (3, 4, ...) for the styles that read them: "filledcurves" (a band
    /// from y to extra[0]), "vectors" (arrows from (x, y) by (extra[0], extra[1])).
    std::vector<std::vector<double>> extra{};
};

struct PlotPanel {
    std::string title, xlabel, ylabel;
    std::vector<PlotSeries> series;
    bool log_x = false, log_y = false;
    bool equal_axes = false;  ///< one unit as long on both axes (a map)
    bool key_below = false;   ///< the legend in rows under the plot, not in a column at its right
};

struct Figure {
    std::string title;
    std::vector<PlotPanel> panels;  ///< stacked top to bottom
    int width = 1000, height = 0;   ///< pixels; height 0 = 380 per panel
};

/// The unit an axis is labelled in: values in the base unit times `factor` are numbers in `unit`.
struct AxisUnit {
    double factor = 1.0;
    std::string unit;  ///< gnuplot enhanced text, e.g. "mN", "{/Symbol m}m", "10^{-13} N"
};

/// The unit for values whose largest magnitude is `peak`, in the base unit `base` ("N" or
/// "m"): the prefix (none, m, u, and n for metres) that puts the peak in [1, 1000), the base
/// unit for larger values, and a power of ten of the base unit below the smallest prefix (a
/// difference of 1e-13 N is drawn as 1.5 on an axis in 10^{-13} N, not 1.5x10^{-7} uN).
[[nodiscard]] AxisUnit axisUnit(double peak, const std::string& base);

/// `text` (e.g. a robot or trajectory name from a file) marked up to be shown as it is by the
/// enhanced-text terminals: `\ @ _ ^ { } & ~` are escaped.
[[nodiscard]] std::string literalText(const std::string& text);

/// gnuplot's SVG made well-formed XML: gnuplot writes a title's '&' and "]]>" as they are;
/// every '&' that does not begin an entity becomes "&amp;", the '>' of "]]>" "&gt;".
[[nodiscard]] std::string wellFormedSvg(std::string_view svg);

/// Writes `stem`.png and `stem`.svg, each safely (io::OutputFile: all or nothing). Throws
/// nocdyn::Error when gnuplot is missing or fails.
void renderFigure(const Figure& figure, const std::string& stem);
/// The same to the paths given (an empty path: that format is not written).
void renderFigureFiles(const Figure& figure, const std::string& png, const std::string& svg);

}  // namespace nocdyn::render
