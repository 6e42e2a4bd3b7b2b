#include "app/frequency_response.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/pose_order.hpp"
#include "nocdyn/sim/closed_loop.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

/// The axes in the user's order x, y, theta: their names and indices in the core's [theta, x, y].
constexpr const char* kAxisNames[3] = {"x", "y", "theta"};
constexpr int kCoreAxis[3] = {1, 2, 0};

Vector3 threeValues(const std::vector<double>& values) { return {values[0], values[1], values[2]}; }

std::string numberOrBeyond(double value) {
    if (std::isnan(value)) return "beyond the grid";
    return text::format("%.4f", value);
}

std::vector<double> column(const Eigen::MatrixXd& m, Eigen::Index c) {
    return {m.col(c).data(), m.col(c).data() + m.rows()};
}

/// The open-loop plant: from each actuator force (or commanded drive position) to each output.
FrequencyResponseResult plant(const FrequencyResponseOptions& options, const Model& model) {
    Data data(model);
    const Pose p = options.pose.empty() ? model.home : corePose(threeValues(options.pose));
    const Twist dp = options.rate.empty() ? Twist::Zero() : Twist(corePose(threeValues(options.rate)));
    // the operating point: the forces that hold the state without acceleration
    if (const Status status = inverseDynamics(model, data, p, dp, Twist::Zero()); !status) {
        throw Error("operating point: " + describe(status, model));
    }
    const ActuatorVector tau = data.tau;
    const bool acceleration = options.output_kind == "acceleration";
    const LinearOutput kind = acceleration ? LinearOutput::platform_acceleration : LinearOutput::actuator_variables;
    const analysis::StiffnessModel compliance(model);
    const bool lumped = options.compliance == "lumped" || (options.compliance == "auto" && compliance.any);
    if (lumped && !compliance.any) {
        throw OptionError("compliance", "the robot file declares no joint or drive stiffness and no elastic link");
    }
    StateSpace system;
    const Status status = lumped ? linearizeCompliant(model, compliance, data, p, dp, tau, kind, system)
                                 : linearize(model, data, p, dp, tau, kind, system);
    if (!status) throw Error("operating point: " + describe(status, model));
    const FrequencyResponse r = frequencyResponse(system, logGrid(options.f_min, options.f_max, options.points));
    FrequencyResponseResult out;
    out.robot = model.description.name;
    out.frequency = r.frequency;
    const auto rows = static_cast<Eigen::Index>(r.frequency.size());
    out.table.resize(rows, 1 + 2 * r.outputs * r.inputs);
    out.columns.push_back("f");
    for (Eigen::Index k = 0; k < rows; ++k) out.table(k, 0) = r.frequency[static_cast<std::size_t>(k)];
    const Vector3 pu = userPose(p), dpu = userPose(dp);
    std::string line;
    const auto positions = std::count(system.inputs.begin(), system.inputs.end(), LinearInput::commanded_position);
    const char* inputs = positions == 0                           ? "the actuator forces"
                         : positions == std::ssize(system.inputs) ? "the commanded drive positions"
                                                                  : "the drive inputs (uc: commanded "
                                                                    "position, tau: force)";
    out.summary = "# frequency response of " + io::terminalText(out.robot) + " from " + inputs + " to " +
                  (acceleration ? "the platform acceleration" : "the actuator variables") +
                  (lumped ? " (lumped compliant model)\n" : " (rigid model)\n");
    line = text::format("# operating point [x, y, theta] = [%.6g, %.6g, %.6g], its rate = [%.6g, %.6g, %.6g]%s\n",
                        pu(0), pu(1), pu(2), dpu(0), dpu(1), dpu(2),
                        options.payload > 0.0 ? text::format("; payload %g kg at C", options.payload).c_str() : "");
    out.summary += line;
    if (lumped) {
        analysis::StiffnessData stiffness;
        analysis::LumpedModes modes;
        Data at_rest(model);
        if (const Status s = analysis::stiffnessAndModes(model, compliance, at_rest, p, stiffness, modes); !s) {
            throw Error("operating point: " + describe(s, model));
        }
        line = text::format("# lumped natural frequencies at the pose [Hz]: %.4f %.4f %.4f\n", modes.frequency(0),
                            modes.frequency(1), modes.frequency(2));
        out.summary += line;
    }
    out.summary += "# channel  |H| at f_min [dB]  |H| at f_max [dB]  -3 dB bandwidth [Hz]\n";
    Eigen::Index c_out = 1;
    for (int k = 0; k < r.outputs; ++k) {
        // accelerations per axis in the order x, y, theta; actuator variables in theirs
        const int o = acceleration ? kCoreAxis[k] : k;
        std::string label = acceleration ? "dd" : "u";
        label += acceleration ? std::string(kAxisNames[k]) : std::to_string(k + 1);
        for (int i = 0; i < r.inputs; ++i) {
            const Eigen::Index c = o * r.inputs + i;
            const std::string input = name(system.inputs[static_cast<std::size_t>(i)]) + std::to_string(i + 1);
            const std::string channel = text::format("%s_%s", label.c_str(), input.c_str());
            out.columns.push_back(channel + "_db");
            out.columns.push_back(channel + "_deg");
            out.table.col(c_out++) = r.magnitude_db.col(c);
            out.table.col(c_out++) = r.phase_deg.col(c);
            const double bw = bandwidth3dB(r, o, i);
            line = text::format("%s/%s  %.4f  %.4f  %s\n", label.c_str(), input.c_str(), r.magnitude_db(0, c),
                                r.magnitude_db(rows - 1, c),
                                std::isnan(bw) ? "beyond the grid" : text::format("%f", bw).c_str());
            out.summary += line;
            out.curves.push_back({text::format("%s/%s", label.c_str(), input.c_str()), column(r.magnitude_db, c),
                                  column(r.phase_deg, c)});
        }
    }
    return out;
}

/// The shake-table loop linearised at rest at the pose (see sim/closed_loop.hpp).
FrequencyResponseResult closedLoop(const FrequencyResponseOptions& options, const RobotDescription& robot,
                                   const Model& model) {
    const Model plant_model(withPayload(robot, Payload{options.payload, 0.0, Vector2::Zero()}));
    const Pose p = options.pose.empty() ? model.home : corePose(threeValues(options.pose));
    ShakeLoopOptions loop_options;
    loop_options.rate = options.controller_rate;
    loop_options.natural_frequency = options.natural_frequency;
    const ShakeLoopLinearization loop = linearizeShakeLoop(model, plant_model, p, loop_options);
    // a response is a steady state only of a stable loop: every eigenvalue of the one-tick map
    // inside the unit circle
    if (const double radius = shakeLoopSpectralRadius(loop); !(radius < 1.0)) {
        throw OptionError("closed_loop",
                          text::format("unstable closed loop (spectral radius max |eig F| = %.6g >= 1 at a tick of "
                                       "%g Hz with f_n = %g Hz): it has no frequency response; lower "
                                       "`natural_frequency`, raise `controller_rate` or lighten `payload`",
                                       radius, options.controller_rate, options.natural_frequency));
    }
    const ShakeLoopFrequencyResponse r =
        shakeLoopFrequencyResponse(loop, logGrid(options.f_min, options.f_max, options.points));
    FrequencyResponseResult out;
    out.robot = model.description.name;
    out.closed_loop = true;
    out.frequency = r.frequency;
    const auto rows = static_cast<Eigen::Index>(r.frequency.size());
    out.table.resize(rows, 1 + 4 * 3);
    out.columns.push_back("f");
    for (Eigen::Index k = 0; k < rows; ++k) out.table(k, 0) = r.frequency[static_cast<std::size_t>(k)];
    const Vector3 pu = userPose(p);
    std::string line;
    line = text::format(
        "# (linearised at rest at [x, y, theta] = [%.6g, %.6g, %.6g]; tick %g Hz, f_n = %g Hz, payload "
        "unknown to the controller %g kg)\n",
        pu(0), pu(1), pu(2), options.controller_rate, options.natural_frequency, options.payload);
    out.summary = "# closed-loop frequency response of " + io::terminalText(out.robot) +
                  " under the shake-table controller, from the reference to the achieved platform acceleration\n" +
                  line;
    if (analysis::StiffnessModel(model).any) {
        out.summary +=
            "# rigid plant: the compliance the robot file declares (joint or drive stiffness, elastic links) is not "
            "modelled in the closed loop (the open-loop plant models it: frequency-response without --closed-loop)\n";
    }
    out.summary +=
        "# axis  |H| at f_min [dB]  |H| at f_max [dB]  -3 dB bandwidth [Hz]  crossover [Hz]  phase margin [deg]\n";
    Eigen::Index c_out = 1;
    for (int k = 0; k < 3; ++k) {
        const int i = kCoreAxis[k];
        for (const char* suffix : {"_db", "_deg", "_loop_db", "_loop_deg"})
            out.columns.push_back(kAxisNames[k] + std::string(suffix));
        out.table.col(c_out++) = r.magnitude_db.col(i);
        out.table.col(c_out++) = r.phase_deg.col(i);
        out.table.col(c_out++) = r.loop_magnitude_db.col(i);
        out.table.col(c_out++) = r.loop_phase_deg.col(i);
        line = text::format("%s  %.4f  %.4f  %s  %s  %s\n", kAxisNames[k], r.magnitude_db(0, i),
                            r.magnitude_db(rows - 1, i), numberOrBeyond(r.bandwidth(i)).c_str(),
                            numberOrBeyond(r.crossover(i)).c_str(), numberOrBeyond(r.phase_margin(i)).c_str());
        out.summary += line;
        out.curves.push_back({std::string("H ") + kAxisNames[k], column(r.magnitude_db, i), column(r.phase_deg, i)});
        out.curves.push_back(
            {std::string("L ") + kAxisNames[k], column(r.loop_magnitude_db, i), column(r.loop_phase_deg, i)});
    }
    return out;
}

}  // namespace

void validate(const FrequencyResponseOptions& options) {
    if (!options.pose.empty() && options.pose.size() != 3) throw OptionError("pose", "expected 3 values x, y, theta");
    if (!options.rate.empty() && options.rate.size() != 3)
        throw OptionError("rate", "expected 3 values dx, dy, dtheta");
    for (const double v : options.pose) requireIn(v, kLengthRange, "pose");
    for (const double v : options.rate) requireIn(v, Range{-1e6, 1e6, "m/s or rad/s"}, "rate");
    if (options.output_kind != "acceleration" && options.output_kind != "actuators") {
        throw OptionError("output_kind", "'" + options.output_kind + "' is not one of acceleration, actuators");
    }
    requireIn(options.f_min, kResponseFrequencyRange, "f_min");
    requireIn(options.f_max, kResponseFrequencyRange, "f_max");
    if (!(options.f_max > options.f_min)) throw OptionError("f_max", "must be above f_min");
    if (options.points < kMinPoints || options.points > kMaxPoints) {
        throw OptionError("points", std::to_string(options.points) + " is outside [2, 100000]");
    }
    requireIn(options.payload, kPayloadMassRange, "payload");
    requireIn(options.controller_rate, kShakeRateRange, "controller_rate");
    requireIn(options.natural_frequency, kShakeNaturalFrequencyRange, "natural_frequency");
    if (options.compliance != "auto" && options.compliance != "rigid" && options.compliance != "lumped") {
        throw OptionError("compliance", "'" + options.compliance + "' is not one of auto, rigid, lumped");
    }
    // the controller's settings do nothing to the open-loop plant: set, they are refused
    const FrequencyResponseOptions defaults;
    if (!options.closed_loop) {
        if (options.controller_rate != defaults.controller_rate)
            throw OptionError("controller_rate", "does not apply to the plant: it goes with `closed_loop`");
        if (options.natural_frequency != defaults.natural_frequency)
            throw OptionError("natural_frequency", "does not apply to the plant: it goes with `closed_loop`");
    }
    if (options.closed_loop) {
        if (options.output_kind != defaults.output_kind)
            throw OptionError("output_kind",
                              "does not apply to the closed loop (its output is the achieved platform acceleration): "
                              "it goes with the plant (without `closed_loop`)");
        if (options.compliance == "lumped")
            throw OptionError("compliance", "the closed loop is the rigid model: lumped does not apply");
        if (!options.rate.empty())
            throw OptionError("rate", "the closed loop is linearised at rest: rate does not apply");
        if (!(options.f_max < 0.5 * options.controller_rate)) {
            throw OptionError("f_max", "must be below half the `controller_rate` (the Nyquist frequency)");
        }
        // the loop's reference position is a / w^2: its rounding, amplified by the gains
        // (about w_n^2), costs eps (f_n / f)^2 of the response (2e-6 at f = 1e-5 f_n)
        if (!(options.f_min >= kClosedLoopLowestFraction * options.natural_frequency)) {
            throw OptionError(
                "f_min", text::format("must be at least %g Hz with the closed loop (1e-5 times natural_frequency): "
                                      "below it the rounding of the reference position a / w^2 costs more than "
                                      "a millionth of the response",
                                      kClosedLoopLowestFraction * options.natural_frequency));
        }
    }
}

FrequencyResponseResult runFrequencyResponse(const FrequencyResponseOptions& options, Observer& /*observer*/) {
    validate(options);
    const RobotDescription robot = loadRobot(options.robot);
    // the open-loop plant carries the payload (a point mass at C) itself
    FrequencyResponseResult out =
        options.closed_loop
            ? closedLoop(options, robot, Model(robot))
            : plant(options,
                    Model(options.payload > 0.0 ? withPayload(robot, Payload{options.payload, 0.0, Vector2::Zero()})
                                                : robot));
    // a grid the options accept may still reach beyond a double (|H| of 1 / w^2 at extreme w):
    // said at once, naming the end of the grid, not when the table is written
    for (Eigen::Index k = 0; k < out.table.rows(); ++k) {
        for (Eigen::Index c = 1; c < out.table.cols(); ++c) {
            if (std::isfinite(out.table(k, c))) continue;
            const double f = out.table(k, 0);
            const bool low = f < std::sqrt(options.f_min) * std::sqrt(options.f_max);
            throw OptionError(low ? "f_min" : "f_max",
                              text::format("the response at %g Hz (%s) is beyond the range of a double; choose a "
                                           "narrower grid",
                                           f, out.columns[static_cast<std::size_t>(c)].c_str()));
        }
    }
    return out;
}

report::Figure bodeFigure(const FrequencyResponseResult& result) {
    report::Figure figure;
    figure.title = result.closed_loop
                       ? "Closed loop of " + report::literalText(result.robot) + " (shake-table controller)"
                       : "Frequency response of " + report::literalText(result.robot);
    report::PlotPanel magnitude{"", "frequency [Hz]", "magnitude [dB]", {}, true, false, false};
    report::PlotPanel phase{"", "frequency [Hz]", "phase [deg]", {}, true, false, false};
    for (const BodeCurve& curve : result.curves) {
        magnitude.series.push_back({report::literalText(curve.label), result.frequency, curve.magnitude_db});
        phase.series.push_back({report::literalText(curve.label), result.frequency, curve.phase_deg});
    }
    figure.panels = {magnitude, phase};
    return figure;
}

}  // namespace nocdyn::app
