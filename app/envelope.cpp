#include "app/envelope.hpp"

#include <cmath>
#include <cstdio>

#include "app/pose_spatial.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/text.hpp"
#include "render/envelope_figure.hpp"

namespace nocdyn::app {

void validate(const EnvelopeOptions& options) {
    requireIn(options.min_frequency, kEnvelopeFrequencyRange, "min_frequency");
    requireIn(options.max_frequency, kEnvelopeFrequencyRange, "max_frequency");
    requireIn(options.points, kEnvelopePointsRange, "points");
    requireIn(options.samples_per_period, kSamplesPerPeriodRange, "samples_per_period");
    requireIn(options.relative_tolerance, kEnvelopeToleranceRange, "relative_tolerance");
    requireIn(options.amplification, kAmplificationRange, "amplification");
    if (options.max_frequency < options.min_frequency)
        throw OptionError("max_frequency", "must be at least min_frequency");
}

nocdyn::EnvelopeOptions libraryEnvelopeOptions(const EnvelopeOptions& options, Observer& observer) {
    nocdyn::EnvelopeOptions envelope = static_cast<const nocdyn::EnvelopeOptions&>(options);
    // called between points, from this thread
    envelope.progress = [&observer](int done, int total) {
        observer.progress(done, total, "points");
        stopIfRequested(observer);
    };
    envelope.poll = [&observer] { stopIfRequested(observer); };
    return envelope;
}

EnvelopeResult runEnvelope(const EnvelopeOptions& options, Observer& observer) {
    validate(options);
    if (isSpatialRobot(options.robot)) return runSpatialEnvelope(options, observer);
    const Model model(loadRobot(options.robot));
    const nocdyn::EnvelopeOptions envelope = libraryEnvelopeOptions(options, observer);
    EnvelopeResult out;
    out.robot = model.description.name;
    out.points = operatingEnvelope(model, envelope);
    out.resonance = envelopeResonance(model, options.amplification);
    out.table = tables::toTable(out.points, out.resonance);
    out.summary = resonanceSummary(out.resonance);
    return out;
}

std::string resonanceSummary(const EnvelopeResonance& resonance) {
    if (resonance.known) {
        std::string text = text::format(
            "third bound: the dynamic amplification of the %s model at home (damping ratio %.3g, first natural "
            "frequency %.6g Hz) leaves [1/%.4g, %.4g] at",
            std::string(nameOf(resonance.model)).c_str(), resonance.damping_ratio, resonance.frequency,
            resonance.amplification, resonance.amplification);
        for (const EnvelopeAxis axis : kEnvelopeAxes) {
            if (!hasAxis(resonance.task_dimension, axis)) continue;
            const double f = resonance.band_end[static_cast<std::size_t>(axis)];
            text += std::string(axis == kEnvelopeAxes.front() ? " " : ", ") + axisName(axis) + " " +
                    (std::isfinite(f) ? text::format("%.4g Hz", f) : std::string("no frequency"));
        }
        text += "; the limit at and above it is resonance";
        if (!resonance.warning.empty()) text += " (" + resonance.warning + ")";
        return text;
    }
    std::string text = "third bound (first natural frequency): unknown, " + resonance.reason;
    if (!resonance.declared) {
        text += " (joint stiffness, body elastic: docs/robot-files.md, Compliance)";
    }
    return text;
}

render::Figure envelopeResultFigure(const EnvelopeResult& result) {
    if (!result.spatial_points.empty()) {
        return render::spatialEnvelopeFigure(result.spatial_points, result.coordinates, result.robot);
    }
    return render::envelopeFigure(result.points, result.robot,
                                  "flat = range-bound, slope -1 = velocity-bound, slope -2 = effort-bound",
                                  result.resonance);
}

}  // namespace nocdyn::app
