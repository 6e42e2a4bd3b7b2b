// The operating envelope as a figure (see envelope_figure.hpp).
#include "render/envelope_figure.hpp"

#include <algorithm>
#include <limits>
#include <numbers>

#include "nocdyn/text.hpp"

namespace nocdyn::render {

namespace {

/// The band's third bound on a panel: a vertical line at f_1 over the panel's amplitudes, and
/// the frequencies from the band's end (where the panel's axes' dynamic amplification leaves
/// [1 / A, A]) to the last point shaded as beyond the band.
void drawResonance(PlotPanel& panel, double f1, double band_end, double amplification, double last_frequency) {
    double low = std::numeric_limits<double>::infinity(), high = 0.0;
    for (const PlotSeries& s : panel.series) {
        for (const double y : s.y) {
            if (y > 0.0) low = std::min(low, y), high = std::max(high, y);
        }
    }
    if (!(high > 0.0)) return;  // nothing on a log axis to span
    if (band_end < last_frequency) {
        panel.series.push_back({text::format("beyond the band (amplification beyond %.3g)", amplification),
                                {band_end, last_frequency},
                                {low, low},
                                "filledcurves fs transparent solid 0.15 noborder lc rgb '#d62728'",
                                {{high, high}}});
    }
    std::string label;
    label = text::format("first natural frequency %.4g Hz", f1);
    panel.series.push_back({label, {f1, f1}, {low, high}, "lines dt 2 lw 2 lc rgb '#d62728'"});
}

}  // namespace

Figure envelopeFigure(const std::vector<EnvelopePoint>& points, const std::string& robot, const std::string& reading,
                      const EnvelopeResonance& resonance) {
    PlotPanel translation{"Translation along x and y", "frequency [Hz]", "largest amplitude [mm]", {}, true, true};
    PlotPanel rotation{"Rotation theta", "frequency [Hz]", "largest amplitude [deg]", {}, true, true};
    for (const EnvelopeAxis axis : kEnvelopeAxes) {
        PlotSeries line;
        line.label = axisName(axis);
        line.style = "linespoints lw 2 pt 7 ps 0.6";
        for (const auto& p : points) {
            if (p.axis != axis) continue;
            line.x.push_back(p.frequency);
            line.y.push_back(axis == EnvelopeAxis::theta ? p.amplitude * 180.0 / std::numbers::pi : p.amplitude * 1e3);
        }
        (axis == EnvelopeAxis::theta ? rotation : translation).series.push_back(std::move(line));
    }
    if (resonance.known) {
        double last = 0.0;
        for (const auto& p : points) last = std::max(last, p.frequency);
        const auto end = [&](EnvelopeAxis axis) { return resonance.band_end[static_cast<std::size_t>(axis)]; };
        drawResonance(translation, resonance.frequency, std::min(end(EnvelopeAxis::x), end(EnvelopeAxis::y)),
                      resonance.amplification, last);
        drawResonance(rotation, resonance.frequency, end(EnvelopeAxis::theta), resonance.amplification, last);
    }
    Figure figure;
    figure.title = "Operating envelope of " + literalText(robot) + ": " + reading;
    // a two-DOF robot's envelope has no theta points: no rotation panel
    const bool rotates =
        std::any_of(points.begin(), points.end(), [](const EnvelopePoint& p) { return p.axis == EnvelopeAxis::theta; });
    figure.panels = {translation};
    if (rotates) figure.panels.push_back(rotation);
    return figure;
}

}  // namespace nocdyn::render
