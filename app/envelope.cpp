#include "app/envelope.hpp"

#include <cstdio>

#include "nocdyn/tables/tables.hpp"
#include "nocdyn/text.hpp"
#include "plot.hpp"
#include "reproduce_dynamics.hpp"

namespace nocdyn::app {

void validate(const EnvelopeOptions& options) {
    requireIn(options.min_frequency, kEnvelopeFrequencyRange, "min_frequency");
    requireIn(options.max_frequency, kEnvelopeFrequencyRange, "max_frequency");
    requireIn(options.points, kEnvelopePointsRange, "points");
    if (options.max_frequency < options.min_frequency)
        throw OptionError("max_frequency", "must be at least min_frequency");
}

EnvelopeResult runEnvelope(const EnvelopeOptions& options, Observer& observer) {
    validate(options);
    const Model model(loadRobot(options.robot));
    nocdyn::EnvelopeOptions envelope;
    envelope.min_frequency = options.min_frequency;
    envelope.max_frequency = options.max_frequency;
    envelope.frequencies = options.points;
    // called between points, from this thread
    envelope.progress = [&observer](int done, int total) {
        observer.progress(done, total, "points");
        stopIfRequested(observer);
    };
    envelope.poll = [&observer] { stopIfRequested(observer); };
    EnvelopeResult out;
    out.robot = model.description.name;
    out.points = operatingEnvelope(model, envelope);
    out.resonance = envelopeResonance(model);
    out.table = io::toTable(out.points, out.resonance);
    out.summary = resonanceSummary(out.resonance);
    return out;
}

std::string resonanceSummary(const EnvelopeResonance& resonance) {
    if (resonance.known) {
        std::string text;
        text = text::format(
            "third bound: first natural frequency %.6g Hz (lumped model at home); the limit at and above "
            "it is resonance",
            resonance.frequency);
        return text;
    }
    std::string text = "third bound (first natural frequency): unknown, " + resonance.reason;
    if (!resonance.declared) {
        text += " (joint stiffness, body elastic: docs/robot-files.md, Compliance)";
    }
    return text;
}

void writeEnvelopeFigure(const EnvelopeResult& result, const std::string& stem) {
    report::renderFigure(
        report::envelopeFigure(result.points, result.robot,
                               "flat = range-bound, slope -1 = velocity-bound, slope -2 = effort-bound",
                               result.resonance),
        stem);
}

}  // namespace nocdyn::app
