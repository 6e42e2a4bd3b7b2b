#include "app/excite.hpp"

#include <cstdio>

#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/excitation.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

std::string percent(double v) { return text::format("%.1f", 100.0 * v); }

std::string useText(const ExcitationLimitUse& use) {
    return "{range: " + percent(use.range) + ", velocity: " + percent(use.velocity) +
           ", effort: " + percent(use.effort) + ", condition: " + percent(use.condition) + ", binding: '" +
           use.binding + "'}";
}

/// One baseline line: the paper's trajectory about home, its condition number and limit use.
std::string baseline(const Model& model, const char* key, const PoseTrajectory& paper,
                     const ExcitationOptions& options) {
    if (!paper.duration) throw Error(std::string("excite: ") + key + " has no duration");
    PoseTrajectory about = aboutHome(model, paper);
    if (model.task_dimension == 2) about.theta = AxisMotion{model.home(0), {}};  // x, y only: no theta
    const ExcitationAssessment a = assessExcitation(model, about, *paper.duration, options.check_samples, options);
    std::string text = key + std::string(": {condition_number: ") + text::number(a.condition) +
                       ", limit_use_percent: " + useText(a.use) + "}";
    if (!a.feasible) text += "   # outside the limits: " + a.failure;
    return text + "\n";
}

void requireCount(int value, int lo, int hi, const char* field) {
    if (value < lo || value > hi) {
        throw OptionError(
            field, std::to_string(value) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
}

}  // namespace

void validate(const ExciteOptions& o) {
    if (!o.payload_guess.empty() && o.payload_guess.size() != 4)
        throw OptionError("payload_guess", "expected 4 numbers: mass, com x, com y, inertia");
    for (double v : o.payload_guess) requireIn(v, kPayloadGuessRange, "payload_guess");
    if (o.payload_guess.size() == 4) {
        // each value in its own quantity's range (the range of a payload anywhere else)
        requireIn(o.payload_guess[0], kPayloadMassRange, "payload_guess");
        requireIn(o.payload_guess[1], kLengthRange, "payload_guess");
        requireIn(o.payload_guess[2], kLengthRange, "payload_guess");
        requireIn(o.payload_guess[3], kPayloadInertiaRange, "payload_guess");
    }
    if (!o.payload_guess.empty() && o.parameters == ExcitedParameters::base)
        throw OptionError("payload_guess", "is for a payload; base designs for the robot without one");
    requireIn(o.duration, kExciteDurationRange, "duration");
    requireIn(o.base_frequency, kExciteFrequencyRange, "base_frequency");
    requireCount(o.harmonics, 3, 20, "harmonics");
    requireIn(o.margin, kExciteMarginRange, "margin");
    requireIn(o.max_condition, kMaxConditionRange, "max_condition");
    requireCount(o.evaluations, 1, 1000000, "evaluations");
    requireCount(o.random_shapes, 1, 1000000, "random_shapes");
    requireCount(o.samples, 0, 100000, "samples");
    requireCount(o.check_samples, 24, 1000000, "check_samples");
}

ExciteResult runExcite(const ExciteOptions& options, Observer& observer) {
    validate(options);
    // a two-DOF robot too: the excitation moves x, y (theta stays at home)
    RobotDescription robot = loadRobot(options.robot);
    Payload payload;
    if (!options.payload_guess.empty()) {
        const std::vector<double>& g = options.payload_guess;
        if (robot.motion == PlatformMotion::translation && (g[1] != 0.0 || g[2] != 0.0 || g[3] != 0.0)) {
            throw OptionError("payload_guess",
                              "a two-DOF robot's payload is a point mass at the tool point: give its mass with com "
                              "0 0 and inertia 0");
        }
        payload = Payload{g[0], g[3], Vector2(g[1], g[2])};
        robot = withPayload(robot, payload);
    }
    // the design's own part of the options, with the progress added
    ExcitationOptions o = static_cast<const ExcitationOptions&>(options);
    const auto total = static_cast<double>(options.evaluations);
    o.progress = [&observer, total](int done) {
        observer.progress(static_cast<double>(done), total, "evaluations");
        stopIfRequested(observer);
    };
    const Model model(robot);
    const ExcitationResult result = designExcitation(model, options.duration, o);
    o.progress = {};
    // a two-DOF robot's payload: a point mass at the tool point, its mass the one unknown
    const std::string payload_text =
        model.task_dimension == 2 ? "the payload mass (a point mass at the tool point)" : "the payload";
    const std::string what = o.parameters == ExcitedParameters::base
                                 ? "the base parameters"
                                 : (o.friction ? payload_text + " and the actuators' friction" : payload_text);
    std::string report = "# " + io::terminalText(robot.name) + ": excitation for " + what + ", " +
                         std::to_string(o.harmonics) + " harmonics of " + text::number(o.base_frequency) +
                         (model.task_dimension == 2 ? " Hz per axis (x, y), " : " Hz per axis, ") +
                         text::number(options.duration) + " s, margin " + percent(o.margin) +
                         " %, condition numbers of J_j and A at most " + text::number(o.max_condition) + "\n";
    if (!options.payload_guess.empty()) {
        report += "# payload guess: " + text::number(payload.mass) + " kg at [" + text::number(payload.com.x()) + ", " +
                  text::number(payload.com.y()) + "] m, " + text::number(payload.inertia) +
                  " kg m^2 about its c.o.m.\n";
    }
    report += "# " + std::to_string(result.evaluations) + " evaluations (" + std::to_string(o.random_shapes) +
              " random shapes, then " +
              (o.optimizer == ExcitationOptimizer::gradient
                   ? "BFGS on the exact gradient, " + std::to_string(result.gradients) + " gradients, then Nelder-Mead"
                   : std::string("Nelder-Mead")) +
              "), seed " + std::to_string(o.seed) +
              "; condition number of the column-scaled stacked regressor (as identify reports it)\n";
    report += "designed: {condition_number: " + text::number(result.assessment.condition) +
              ", limit_use_percent: " + useText(result.assessment.use) + "}\n";
    report += baseline(model, "paper_trajectory_1", paperTrajectory1(), o);
    report += baseline(model, "paper_trajectory_2", paperTrajectory2(), o);

    std::string file = "# Excitation trajectory by `nocdyn excite` for " + what + " of " +
                       io::terminalText(robot.name) + ": condition number " +
                       text::number(result.assessment.condition) + "; starts and ends each period at home, at rest.\n";
    for (std::size_t start = 0; start < report.size();) {
        const std::size_t end = report.find('\n', start);
        const std::string line = report.substr(start, end - start);
        file += (line.rfind('#', 0) == 0 ? line : "# " + line) + "\n";
        start = end == std::string::npos ? report.size() : end + 1;
    }
    file += io::trajectoryToYaml(result.trajectory);
    ExciteResult out;
    out.text = std::move(report);
    out.yaml = std::move(file);
    out.trajectory = result.trajectory;
    out.condition = result.assessment.condition;
    out.evaluations = result.evaluations;
    out.gradients = result.gradients;
    return out;
}

}  // namespace nocdyn::app
