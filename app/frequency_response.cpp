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

/// True when actuator a drives a prismatic joint (its force in N, its position in m).
bool prismatic(const Model& model, int a) {
    const auto j = static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)]);
    const auto q = static_cast<std::size_t>(model.actuator_joint[static_cast<std::size_t>(a)]);
    return model.description.limbs[j].joints[q].type == JointType::prismatic;
}

/// A quotient of units, the compound ones in parentheses: "(m/s^2)/N", "m/(N m)".
std::string perUnit(const std::string& output, const std::string& input) {
    const auto wrap = [](const std::string& u) {
        return u.find_first_of("/ ") == std::string::npos ? u : "(" + u + ")";
    };
    return wrap(output) + "/" + wrap(input);
}

/// The bandwidth column: a number, or why there is none.
std::string bandwidthText(double bandwidth, double slope) {
    if (!std::isnan(bandwidth)) return text::format("%.4f", bandwidth);
    if (std::abs(slope - std::round(slope)) <= kSlopeTolerance) return "beyond the grid";
    return "no asymptote at f_min";
}

/// The open-loop plant: from each actuator force (or commanded drive position) to each output.
/// Whether the plant is the lumped compliant model: asked for, or (auto) wherever the robot file
/// declares compliance.
bool lumpedPlant(const FrequencyResponseOptions& options, const StiffnessModel& compliance) {
    const bool lumped = options.compliance == PlantCompliance::lumped ||
                        (options.compliance == PlantCompliance::automatic && compliance.any);
    if (lumped && !compliance.any) {
        throw OptionError("compliance", "the robot file declares no joint or drive stiffness and no elastic link");
    }
    return lumped;
}

/// The lumped model's modes at the pose p, at rest (the natural frequencies the summaries print).
LumpedModes lumpedModesAt(const Model& model, const StiffnessModel& compliance, const Pose& p) {
    StiffnessData stiffness;
    LumpedModes modes;
    Data at_rest(model);
    if (const Status s = stiffnessAndModes(model, compliance, at_rest, p, stiffness, modes); !s) {
        throw Error("operating point: " + describe(s, model));
    }
    return modes;
}

/// The operating pose (or rate) of the options' values: x, y, theta in the user's order, or x, y
/// of a two-DOF robot (theta at home, its rate 0).
Vector3 operatingValues(const Model& model, const std::vector<double>& values, const char* option) {
    const auto n = static_cast<std::size_t>(model.task_dimension);
    if (values.size() != n) {
        throw OptionError(option, model.task_dimension == 2
                                      ? "a two-DOF robot (motion: translation) takes 2 values x, y: it has no theta"
                                      : "expected 3 values x, y, theta");
    }
    return n == 3 ? threeValues(values) : Vector3(values[0], values[1], 0.0);
}

FrequencyResponseResult plant(const FrequencyResponseOptions& options, const Model& model) {
    Data data(model);
    const bool task = model.task_dimension == 2;
    Pose p = options.pose.empty() ? model.home : corePose(operatingValues(model, options.pose, "pose"));
    if (task) p(0) = model.home(0);
    const Twist dp =
        options.rate.empty() ? Twist::Zero() : Twist(corePose(operatingValues(model, options.rate, "rate")));
    // the operating point: the forces that hold the state without acceleration
    if (const Status status = inverseDynamics(model, data, p, dp, Twist::Zero()); !status) {
        throw Error("operating point: " + describe(status, model));
    }
    const ActuatorVector tau = data.tau;
    const bool acceleration = options.output_kind == LinearOutput::platform_acceleration;
    const LinearOutput kind = options.output_kind;
    const StiffnessModel compliance(model);
    const bool lumped = lumpedPlant(options, compliance);
    StateSpace system;
    const Status status = lumped ? linearizeCompliant(model, compliance, data, p, dp, tau, kind, system)
                                 : linearize(model, data, p, dp, tau, kind, system);
    if (!status) throw Error("operating point: " + describe(status, model));
    const FrequencyResponse r =
        frequencyResponse(system, logGrid(options.min_frequency, options.max_frequency, options.points));
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
    const std::string payload =
        options.payload_mass > 0.0 ? text::format("; payload %g kg at C", options.payload_mass) : std::string();
    line = task ? text::format("# operating point [x, y] = [%.6g, %.6g], its rate = [%.6g, %.6g]%s\n", pu(0), pu(1),
                               dpu(0), dpu(1), payload.c_str())
                : text::format(
                      "# operating point [x, y, theta] = [%.6g, %.6g, %.6g], its rate = [%.6g, %.6g, "
                      "%.6g]%s\n",
                      pu(0), pu(1), pu(2), dpu(0), dpu(1), dpu(2), payload.c_str());
    out.summary += line;
    if (lumped) {
        const LumpedModes modes = lumpedModesAt(model, compliance, p);
        line = text::format("# lumped natural frequencies at the pose [Hz]: %.4f %.4f %.4f\n", modes.frequency(0),
                            modes.frequency(1), modes.frequency(2));
        out.summary += line;
    }
    out.summary +=
        "# -3 dB bandwidth: the lowest frequency where |H| falls 3 dB below its low-frequency asymptote |H(f_min)| "
        "(f/f_min)^k, k the slope at f_min in 20 dB/decade (k = 2: an acceleration per commanded position, the "
        "motion 3 dB below the commanded one); beyond the grid: not within [f_min, f_max]\n";
    out.summary +=
        "# channel  |H| at f_min [dB]  |H| at f_max [dB]  low-frequency slope [dB/decade]  -3 dB bandwidth [Hz]  unit "
        "of |H|\n";
    Eigen::Index c_out = 1;
    for (int k = 0; k < r.outputs; ++k) {
        // accelerations per axis in the order x, y, theta (a two-DOF robot's x, y: its outputs'
        // own order); actuator variables in theirs
        const int o = acceleration && !task ? kCoreAxis[k] : k;
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
            const double slope = lowFrequencySlope(r, o, i);
            const bool force = system.inputs[static_cast<std::size_t>(i)] == LinearInput::force;
            const bool linear_input = prismatic(model, i);
            const std::string input_unit = force ? (linear_input ? "N" : "N m") : (linear_input ? "m" : "rad");
            const bool linear_output = acceleration ? kCoreAxis[k] != 0 : prismatic(model, k);  // k < 2: x, y
            const std::string output_unit =
                acceleration ? (linear_output ? "m/s^2" : "rad/s^2") : (linear_output ? "m" : "rad");
            const std::string unit = perUnit(output_unit, input_unit);
            line = text::format("%s/%s  %.4f  %.4f  %.1f  %s  %s\n", label.c_str(), input.c_str(), r.magnitude_db(0, c),
                                r.magnitude_db(rows - 1, c), std::abs(slope) < 0.0025 ? 0.0 : 20.0 * slope,
                                bandwidthText(bw, slope).c_str(), unit.c_str());
            out.summary += line;
            out.curves.push_back({text::format("%s/%s", label.c_str(), input.c_str()), column(r.magnitude_db, c),
                                  column(r.phase_deg, c), unit});
        }
    }
    return out;
}

/// "12.3456", "beyond the grid" (NaN) or "none (outside at f_min)" (0): a usable band's end.
std::string bandEndText(double end) {
    if (std::isnan(end)) return "beyond the grid";
    if (end == 0.0) return "none (outside at f_min)";
    return text::format("%.4f", end);
}

/// The shake-table loop linearised at rest at the pose (see sim/closed_loop.hpp), on the rigid
/// plant or the lumped compliant one.
FrequencyResponseResult closedLoop(const FrequencyResponseOptions& options, const RobotDescription& robot,
                                   const Model& model) {
    const Model plant_model(withPayload(robot, Payload{options.payload_mass, 0.0, Vector2::Zero()}));
    const Pose p = options.pose.empty() ? model.home : corePose(operatingValues(model, options.pose, "pose"));
    const StiffnessModel compliance(plant_model);
    const bool lumped = lumpedPlant(options, compliance);
    ShakeLoopOptions loop_options;
    loop_options.rate = options.controller_rate;
    loop_options.natural_frequency = options.natural_frequency;
    const ShakeLoopLinearization loop = linearizeShakeLoop(model, plant_model, p, loop_options, LoopDerivatives::exact,
                                                           1e-6, lumped ? LoopPlant::lumped : LoopPlant::rigid);
    // a response is a steady state only of a stable loop: every eigenvalue of the one-tick map
    // inside the unit circle
    if (const double radius = shakeLoopSpectralRadius(loop); !(radius < 1.0)) {
        throw OptionError("closed_loop",
                          text::format("unstable closed loop (spectral radius max |eig F| = %.6g >= 1 at a tick of "
                                       "%g Hz with f_n = %g Hz%s): it has no frequency response; lower "
                                       "`natural_frequency`, raise `controller_rate` or lighten `payload_mass`",
                                       radius, options.controller_rate, options.natural_frequency,
                                       lumped ? ", lumped compliant plant" : ""));
    }
    const ShakeLoopFrequencyResponse r =
        shakeLoopFrequencyResponse(loop, logGrid(options.min_frequency, options.max_frequency, options.points));
    const ShakeLoopBand band = shakeLoopBand(loop, r, options.amplification);
    FrequencyResponseResult out;
    out.robot = model.description.name;
    out.closed_loop = true;
    out.lumped = lumped;
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
        pu(0), pu(1), pu(2), options.controller_rate, options.natural_frequency, options.payload_mass);
    out.summary = "# closed-loop frequency response of " + io::terminalText(out.robot) +
                  " under the shake-table controller, from the reference to the achieved platform acceleration\n" +
                  line;
    if (lumped) {
        const LumpedModes modes = lumpedModesAt(plant_model, compliance, p);
        line = text::format(
            "# plant: the lumped compliant model (natural frequencies at the pose %.4f %.4f %.4f Hz, damping ratio "
            "%g): the drives' set points follow the rigid image of the motion the forces give the rigid machine, "
            "the platform follows them through the lumped modes; the sensors see the platform\n",
            modes.frequency(0), modes.frequency(1), modes.frequency(2), plant_model.description.damping_ratio);
        out.summary += line;
    } else if (compliance.any) {
        out.summary +=
            "# rigid plant: the compliance the robot file declares (joint or drive stiffness, elastic links) is not "
            "modelled in the closed loop (--compliance rigid; auto, the default, models it)\n";
    }
    out.summary +=
        "# H: the closed loop, achieved / reference platform acceleration of the axis (columns <axis>_db, _deg; 0 dB "
        "is a perfect table); L: the loop transfer, the loop broken at the axis' acceleration demand, the other "
        "axes closed (columns <axis>_loop_db, _loop_deg; it crosses 0 dB at the crossover)\n";
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
        out.curves.push_back(
            {std::string("H ") + kAxisNames[k], column(r.magnitude_db, i), column(r.phase_deg, i), "1"});
        out.curves.push_back(
            {std::string("L ") + kAxisNames[k], column(r.loop_magnitude_db, i), column(r.loop_phase_deg, i), "1"});
    }
    line = text::format(
        "# usable band: from f_min up to the lowest frequency where |H| leaves [1/A, A] = [%.4f, %.4f] "
        "(--amplification A = %g, as the envelope's band; beyond the grid: |H| stays within over [f_min, f_max]); "
        "|H|'s peak on the grid\n",
        1.0 / options.amplification, options.amplification, options.amplification);
    out.summary += line;
    out.summary += "# band  axis  usable up to [Hz]  peak |H| [dB]  at [Hz]\n";
    for (int k = 0; k < 3; ++k) {
        const int i = kCoreAxis[k];
        out.band_end.push_back(band.end(i));
        out.peak_db.push_back(band.peak_db(i));
        out.peak_frequency.push_back(band.peak_frequency(i));
        line = text::format("band  %s  %s  %.4f  %.4f\n", kAxisNames[k], bandEndText(band.end(i)).c_str(),
                            band.peak_db(i), band.peak_frequency(i));
        out.summary += line;
    }
    return out;
}

}  // namespace

void validate(const FrequencyResponseOptions& options) {
    // 3 values x, y, theta, or 2 of a two-DOF robot (checked against the robot when it is loaded)
    if (!options.pose.empty() && options.pose.size() != 3 && options.pose.size() != 2)
        throw OptionError("pose", "expected 3 values x, y, theta (2, x, y, for a two-DOF robot)");
    if (!options.rate.empty() && options.rate.size() != 3 && options.rate.size() != 2)
        throw OptionError("rate", "expected 3 values dx, dy, dtheta (2, dx, dy, for a two-DOF robot)");
    for (const double v : options.pose) requireIn(v, kLengthRange, "pose");
    for (const double v : options.rate) requireIn(v, Range{-1e6, 1e6, "m/s or rad/s"}, "rate");
    requireIn(options.min_frequency, kResponseFrequencyRange, "min_frequency");
    requireIn(options.max_frequency, kResponseFrequencyRange, "max_frequency");
    if (!(options.max_frequency > options.min_frequency))
        throw OptionError("max_frequency", "must be above min_frequency");
    if (options.points < kMinPoints || options.points > kMaxPoints) {
        throw OptionError("points", std::to_string(options.points) + " is outside [2, 100000]");
    }
    requireIn(options.payload_mass, kPayloadMassRange, "payload_mass");
    requireIn(options.controller_rate, kShakeRateRange, "controller_rate");
    requireIn(options.natural_frequency, kShakeNaturalFrequencyRange, "natural_frequency");
    requireIn(options.amplification, kAmplificationRange, "amplification");
    // the controller's settings do nothing to the open-loop plant: set, they are refused
    const FrequencyResponseOptions defaults;
    if (!options.closed_loop) {
        if (options.controller_rate != defaults.controller_rate)
            throw OptionError("controller_rate", "does not apply to the plant: it goes with `closed_loop`");
        if (options.natural_frequency != defaults.natural_frequency)
            throw OptionError("natural_frequency", "does not apply to the plant: it goes with `closed_loop`");
        if (options.amplification != defaults.amplification)
            throw OptionError("amplification", "does not apply to the plant: it goes with `closed_loop`");
    }
    if (options.closed_loop) {
        if (options.output_kind != defaults.output_kind)
            throw OptionError("output_kind",
                              "does not apply to the closed loop (its output is the achieved platform acceleration): "
                              "it goes with the plant (without `closed_loop`)");
        if (!options.rate.empty())
            throw OptionError("rate", "the closed loop is linearised at rest: rate does not apply");
        if (!(options.max_frequency < 0.5 * options.controller_rate)) {
            throw OptionError("max_frequency", "must be below half the `controller_rate` (the Nyquist frequency)");
        }
        // the loop's reference position is a / w^2: its rounding, amplified by the gains
        // (about w_n^2), costs eps (f_n / f)^2 of the response (2e-6 at f = 1e-5 f_n)
        if (!(options.min_frequency >= kClosedLoopLowestFraction * options.natural_frequency)) {
            throw OptionError(
                "min_frequency",
                text::format("must be at least %g Hz with the closed loop (1e-5 times natural_frequency): "
                             "below it the rounding of the reference position a / w^2 costs more than "
                             "a millionth of the response",
                             kClosedLoopLowestFraction * options.natural_frequency));
        }
    }
}

FrequencyResponseResult runFrequencyResponse(const FrequencyResponseOptions& options, Observer& /*observer*/) {
    validate(options);
    const RobotDescription robot = loadRobot(options.robot);
    if (robot.motion == PlatformMotion::translation) {
        // the open-loop rigid plant over x, y; the shake-table loop and the lumped compliant
        // model are built for three-DOF robots only
        if (options.closed_loop)
            throw OptionError("closed_loop",
                              "the shake-table loop of a two-DOF robot (motion: translation) is not built; its "
                              "open-loop plant is (without `closed_loop`)");
        if (options.compliance == PlantCompliance::lumped ||
            (options.compliance == PlantCompliance::automatic && StiffnessModel(Model(robot)).any))
            throw OptionError("compliance",
                              "the lumped compliant model of a two-DOF robot (motion: translation) is not built: "
                              "give `compliance` rigid for its rigid plant");
    }
    // the open-loop plant carries the payload (a point mass at C) itself
    FrequencyResponseResult out =
        options.closed_loop
            ? closedLoop(options, robot, Model(robot))
            : plant(options, Model(options.payload_mass > 0.0
                                       ? withPayload(robot, Payload{options.payload_mass, 0.0, Vector2::Zero()})
                                       : robot));
    // a grid the options accept may still reach beyond a double (|H| of 1 / w^2 at extreme w):
    // said at once, naming the end of the grid, not when the table is written
    for (Eigen::Index k = 0; k < out.table.rows(); ++k) {
        for (Eigen::Index c = 1; c < out.table.cols(); ++c) {
            if (std::isfinite(out.table(k, c))) continue;
            const double f = out.table(k, 0);
            const bool low = f < std::sqrt(options.min_frequency) * std::sqrt(options.max_frequency);
            throw OptionError(low ? "min_frequency" : "max_frequency",
                              text::format("the response at %g Hz (%s) is beyond the range of a double; choose a "
                                           "narrower grid",
                                           f, out.columns[static_cast<std::size_t>(c)].c_str()));
        }
    }
    return out;
}

namespace {

/// Distinct colours, one per curve (gnuplot's own cycle repeats after eight); past them the
/// cycle goes on dashed.
constexpr const char* kCurveColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b",
                                         "#e377c2", "#17becf", "#7f7f7f", "#bcbd22", "#000000", "#aec7e8"};

std::string curveStyle(std::size_t index, bool dashed) {
    constexpr std::size_t colours = std::size(kCurveColours);
    const bool cycled = index >= colours;
    return text::format("lines lw 2 lc rgb '%s'%s", kCurveColours[index % colours], dashed || cycled ? " dt 2" : "");
}

}  // namespace

render::Figure bodeFigure(const FrequencyResponseResult& result) {
    render::Figure figure;
    figure.title = result.closed_loop
                       ? "Closed loop of " + render::literalText(result.robot) + " (shake-table controller" +
                             (result.lumped ? ", lumped compliant plant)" : ")")
                       : "Frequency response of " + render::literalText(result.robot);
    // one magnitude panel per unit of |H| (in the order the channels first use it), one phase
    // panel; each curve one colour in both
    std::vector<std::string> units;
    for (const BodeCurve& curve : result.curves) {
        if (std::find(units.begin(), units.end(), curve.unit) == units.end()) units.push_back(curve.unit);
    }
    std::vector<render::PlotPanel> magnitude;
    for (const std::string& unit : units) {
        const std::string title =
            result.closed_loop
                ? "H: closed loop, achieved / reference acceleration; L (dashed): loop transfer, broken at the "
                  "axis' demand"
                : "channels in " + render::literalText(unit);
        const std::string ylabel = unit == "1" ? "magnitude [dB] (a ratio of like quantities)"
                                               : "|H| [dB re 1 " + render::literalText(unit) + "]";
        magnitude.push_back({title, "frequency [Hz]", ylabel, {}, true, false, false});
    }
    render::PlotPanel phase{"phase of every channel: in (-180, 180] at the lowest frequency, continuous above",
                            "frequency [Hz]",
                            "phase [deg]",
                            {},
                            true,
                            false,
                            false};
    for (std::size_t k = 0; k < result.curves.size(); ++k) {
        const BodeCurve& curve = result.curves[k];
        const bool loop_transfer = result.closed_loop && curve.label.starts_with("L ");
        const std::string style = curveStyle(k, loop_transfer);
        const auto u = static_cast<std::size_t>(std::find(units.begin(), units.end(), curve.unit) - units.begin());
        magnitude[u].series.push_back({render::literalText(curve.label), result.frequency, curve.magnitude_db, style});
        phase.series.push_back({render::literalText(curve.label), result.frequency, curve.phase_deg, style});
    }
    figure.panels = magnitude;
    figure.panels.push_back(phase);
    return figure;
}

}  // namespace nocdyn::app
