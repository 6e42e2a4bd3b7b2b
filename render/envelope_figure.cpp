// The operating envelope as a figure (see envelope_figure.hpp).
#include "render/envelope_figure.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
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

/// One axis' curve: amplitude versus frequency.
PlotSeries amplitudeLine(const std::string& label) { return {label, {}, {}, "linespoints lw 2 pt 7 ps 0.6"}; }

/// The two panels of an envelope, translations [mm] and rotations [deg].
PlotPanel translationPanel(const std::string& axes) {
    return {"Translation along " + axes, "frequency [Hz]", "largest amplitude [mm]", {}, true, true};
}
PlotPanel rotationPanel(const std::string& axes) {
    return {"Rotation " + axes, "frequency [Hz]", "largest amplitude [deg]", {}, true, true};
}

/// The amplitude as drawn: mm for a length, degrees for an angle.
double drawn(double amplitude, bool angle) { return angle ? amplitude * 180.0 / std::numbers::pi : amplitude * 1e3; }

}  // namespace

Figure envelopeFigure(const std::vector<EnvelopePoint>& points, const std::string& robot, const std::string& reading,
                      const EnvelopeResonance& resonance) {
    PlotPanel translation = translationPanel("x and y"), rotation = rotationPanel("theta");
    for (const EnvelopeAxis axis : kEnvelopeAxes) {
        PlotSeries line = amplitudeLine(axisName(axis));
        for (const auto& p : points) {
            if (p.axis != axis) continue;
            line.x.push_back(p.frequency);
            line.y.push_back(drawn(p.amplitude, axis == EnvelopeAxis::theta));
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

Figure spatialEnvelopeFigure(const std::vector<spatial::EnvelopePoint>& points,
                             const std::vector<std::string>& coordinates, const std::string& robot) {
    PlotPanel translation = translationPanel("x, y and z"), rotation = rotationPanel("roll, pitch and yaw");
    // the binding limits as markers over the curves, one series per limit over both panels' axes
    constexpr std::array<EnvelopeLimit, 4> kMarked{EnvelopeLimit::range, EnvelopeLimit::velocity, EnvelopeLimit::effort,
                                                   EnvelopeLimit::workspace};
    constexpr std::array<const char*, 4> kMarker{
        "pt 4 ps 1.6 lw 2 lc rgb '#2ca02c'", "pt 8 ps 1.6 lw 2 lc rgb '#ff7f0e'", "pt 6 ps 1.6 lw 2 lc rgb '#d62728'",
        "pt 2 ps 1.6 lw 2 lc rgb '#7f7f7f'"};
    std::array<PlotSeries, 4> translation_marks, rotation_marks;
    for (std::size_t m = 0; m < kMarked.size(); ++m) {
        translation_marks[m] = rotation_marks[m] = {
            std::string(limitName(kMarked[m])) + "-bound", {}, {}, std::string("points ") + kMarker[m]};
    }
    for (std::size_t axis = 0; axis < coordinates.size(); ++axis) {
        const bool angle = axis >= 3;
        PlotSeries line = amplitudeLine(coordinates[axis]);
        for (const auto& p : points) {
            if (static_cast<std::size_t>(p.axis) != axis) continue;
            line.x.push_back(p.frequency);
            line.y.push_back(drawn(p.amplitude, angle));
            const auto m = std::find(kMarked.begin(), kMarked.end(), p.limit);
            if (m == kMarked.end()) continue;
            PlotSeries& mark =
                (angle ? rotation_marks : translation_marks)[static_cast<std::size_t>(m - kMarked.begin())];
            mark.x.push_back(p.frequency);
            mark.y.push_back(line.y.back());
        }
        (angle ? rotation : translation).series.push_back(std::move(line));
    }
    for (std::size_t m = 0; m < kMarked.size(); ++m) {
        if (!translation_marks[m].x.empty()) translation.series.push_back(std::move(translation_marks[m]));
        if (!rotation_marks[m].x.empty()) rotation.series.push_back(std::move(rotation_marks[m]));
    }
    Figure figure;
    figure.title = "Operating envelope of " + literalText(robot) +
                   ": flat = range-bound, slope -1 = velocity-bound, slope -2 = effort-bound";
    figure.panels = {translation};
    if (coordinates.size() > 3) figure.panels.push_back(rotation);
    return figure;
}

}  // namespace nocdyn::render
