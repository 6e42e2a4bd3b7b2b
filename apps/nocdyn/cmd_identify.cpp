// nocdyn identify: a payload's mass, c.o.m. and inertia (or the robot's base parameters) from
// a log of actuator positions and forces (t,u1..un,tau1..taun[,du1..dun,ddu1..ddun]).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/tables/calibration.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "plot.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

namespace {

struct IdentifyOptions {
    std::string robot, data, output, figure, calibration, prior;
    bool payload = false, base = false;
    IdentificationOptions identification;
};

std::string number(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.12g", v);
    return buffer;
}

/// The measurements of the CSV file: named columns, time increasing (errors name the line).
Measurements readMeasurements(const std::string& path, int n) {
    const io::Table table = io::readCsvFile(path);
    const auto need = [&](const std::string& name) {
        if (!table.has(name)) {
            throw Error(path + ": no column '" + name + "' (the log needs t, u1..u" + std::to_string(n) +
                        ", tau1..tau" + std::to_string(n) + " for this robot's " + std::to_string(n) + " actuators)");
        }
        return table.column(name);
    };
    const std::size_t t_col = need("t");
    // the forces' name says what they are: tau1 at the sample's instant (a force sensor),
    // tau1_held the command held from the sample to the next (`nocdyn control --log`)
    const bool held = table.has("tau1_held");
    if (held && table.has("tau1")) {
        throw Error(path + ": both tau1 and tau1_held: give the forces once, as tau1..tau" + std::to_string(n) +
                    " (measured at each sample) or tau1_held..tau" + std::to_string(n) +
                    "_held (commands held until the next sample)");
    }
    if (!held && !table.has("tau1")) {
        throw Error(path + ": no column 'tau1' or 'tau1_held' (the log needs t, u1..u" + std::to_string(n) +
                    " and the forces tau1..tau" + std::to_string(n) + " as measured at each sample, or tau1_held..tau" +
                    std::to_string(n) +
                    "_held when they are commands held until the next sample, as `nocdyn control "
                    "--log` writes them)");
    }
    std::vector<std::size_t> u_col, tau_col, du_col, ddu_col;
    for (int a = 1; a <= n; ++a) {
        u_col.push_back(need("u" + std::to_string(a)));
        tau_col.push_back(need("tau" + std::to_string(a) + (held ? "_held" : "")));
    }
    const bool has_du = table.has("du1"), has_ddu = table.has("ddu1");
    if (has_du != has_ddu)
        throw Error(path + ": give both du1..du" + std::to_string(n) + " and ddu1..ddu" + std::to_string(n) +
                    ", or neither");
    if (has_du) {
        for (int a = 1; a <= n; ++a) {
            du_col.push_back(need("du" + std::to_string(a)));
            ddu_col.push_back(need("ddu" + std::to_string(a)));
        }
    }
    const auto N = static_cast<Eigen::Index>(table.rows.size());
    Measurements m;
    m.held_forces = held;
    m.u.resize(N, n);
    m.tau.resize(N, n);
    if (has_du) {
        m.du.resize(N, n);
        m.ddu.resize(N, n);
    }
    for (Eigen::Index k = 0; k < N; ++k) {
        const std::vector<double>& row = table.rows[static_cast<std::size_t>(k)];
        if (k > 0 && !(row[t_col] > m.t.back())) {
            throw Error(path + ":" + std::to_string(table.lines[static_cast<std::size_t>(k)]) +
                        ": column 't': " + number(row[t_col]) + " s is not after the previous sample's " +
                        number(m.t.back()) + " s (time must increase)");
        }
        m.t.push_back(row[t_col]);
        for (int a = 0; a < n; ++a) {
            const auto aa = static_cast<std::size_t>(a);
            m.u(k, a) = row[u_col[aa]];
            m.tau(k, a) = row[tau_col[aa]];
            if (has_du) {
                m.du(k, a) = row[du_col[aa]];
                m.ddu(k, a) = row[ddu_col[aa]];
            }
        }
    }
    return m;
}

std::string fitText(const Model& model, const FitReport& fit) {
    std::string text = "# fit: " + std::to_string(fit.fit_samples) +
                       " samples, held out: " + std::to_string(fit.holdout_samples) +
                       ", condition number of the scaled regressor " + number(fit.condition) + "\n";
    for (int a = 0; a < model.actuators; ++a) {
        const auto aa = static_cast<std::size_t>(a);
        char line[200];
        std::snprintf(line, sizeof line,
                      "# actuator %d: rms residual %.4g (fit), %.4g held out, of rms force %.4g held out (%.3g %%)\n",
                      a + 1, fit.rms_fit[aa], fit.rms_holdout[aa], fit.rms_measured[aa],
                      fit.rms_measured[aa] > 0.0 ? 100.0 * fit.rms_holdout[aa] / fit.rms_measured[aa] : 0.0);
        text += line;
    }
    return text;
}

void figure(const Model& model, const FitReport& fit, const std::string& stem) {
    Figure f;
    f.title = literalText(model.description.name) + ": measured and predicted actuator forces (held-out data)";
    for (int a = 0; a < model.actuators; ++a) {
        PlotPanel panel;
        panel.title = "actuator " + std::to_string(a + 1);
        panel.xlabel = "t [s]";
        const auto ia = static_cast<std::size_t>(a);
        const bool revolute = model.limb[static_cast<std::size_t>(model.actuator_limb[ia])]
                                  .type[static_cast<std::size_t>(model.actuator_joint[ia])] == JointType::revolute;
        panel.ylabel = revolute ? "tau [N m]" : "tau [N]";
        PlotSeries measured{"measured", fit.t, {}, "lines lw 1"};
        PlotSeries predicted{"predicted", fit.t, {}, "lines dt 2 lw 2"};
        for (Eigen::Index k = 0; k < fit.measured.rows(); ++k) {
            measured.y.push_back(fit.measured(k, a));
            predicted.y.push_back(fit.predicted(k, a));
        }
        panel.series = {measured, predicted};
        f.panels.push_back(panel);
    }
    renderFigure(f, stem);
}

void run(const IdentifyOptions& options) {
    if (options.payload && options.base) throw Error("give --payload or --base, not both");
    if (options.base && !options.calibration.empty())
        throw Error("--calibration is for identifying a payload against the calibrated robot, not with --base");
    if (options.base && !options.prior.empty())
        throw Error("--prior bounds a payload's parameters: not with --base (base parameters have no bounds)");
    const RobotDescription robot = loadRobotDescriptionOrDefault(options.robot);
    const Model model(robot);
    IdentificationOptions identification = options.identification;
    if (!options.calibration.empty()) {
        identification.calibration = io::loadCalibration(options.calibration, model);
        try {
            checkCalibration(model, *identification.calibration);
        } catch (const Error& e) {
            throw Error(options.calibration + ": " + e.what());
        }
    }
    if (!options.prior.empty()) identification.prior = io::loadPayloadPrior(options.prior);
    // a log of 10^6 samples or more takes seconds per step: say which step runs (terminal only)
    Steps steps("nocdyn identify", 3);
    steps.next("reading " + io::terminalText(options.data));
    const Measurements measured = readMeasurements(options.data, model.actuators);
    steps.next("reconstructing the motion");
    const Motion motion = reconstructMotion(model, measured, identification);
    steps.next("least squares");
    std::string text, file;
    FitReport fit;
    if (options.base) {
        const BaseResult result = identifyBase(model, motion, identification);
        text = "# " + io::terminalText(robot.name) + ": base parameters from " + io::terminalText(options.data) +
               " (see nocdyn regressor)\n";
        text += fitText(model, result.fit);
        text += "base_parameters:\n";
        for (const Estimate& e : result.beta) {
            text += "  - {name: " + io::yamlQuoted(e.name) + ", value: " + number(e.value) +
                    ", stddev: " + number(e.stddev) + ", robot_file: " + number(e.prior) +
                    ", unit: " + io::yamlQuoted(e.unit) + "}\n";
        }
        std::string comment = "# " + io::terminalText(robot.name) + ": calibration (base parameters) identified from " +
                              io::terminalText(options.data) + "; use with nocdyn identify --payload --calibration\n";
        comment += fitText(model, result.fit);
        file = io::calibrationToYaml(model, result, comment);
        fit = result.fit;
    } else {
        const PayloadResult r = identifyPayload(model, motion, identification);
        text =
            "# " + io::terminalText(robot.name) + ": payload from " + io::terminalText(options.data) +
            (options.calibration.empty() ? "" : ", against the calibration " + io::terminalText(options.calibration)) +
            "\n" + fitText(model, r.fit);
        if (r.inertia_constrained) {
            text += "# the unconstrained inertia about the c.o.m. came out negative (" +
                    number(r.inertia_unconstrained) + " kg m^2): the physically consistent solution has 0\n";
        }
        for (const ActiveBound& b : r.active_bounds) {
            if (r.inertia_constrained && b.parameter == "inertia" && !b.upper) continue;  // said above
            const std::string unit = b.parameter == "mass" ? " kg" : b.parameter == "inertia" ? " kg m^2" : " m";
            text += "# " + b.parameter + " is on its " + (b.upper ? "upper" : "lower") + " bound " + number(b.bound) +
                    unit +
                    (std::isnan(b.unbounded) ? std::string(" (the unbounded fit has no positive mass)")
                                             : " (the unbounded fit gives " + number(b.unbounded) + unit + ")") +
                    "\n";
        }
        if (!options.prior.empty() || !r.active_bounds.empty()) {
            text += "active_bounds: [";
            for (std::size_t i = 0; i < r.active_bounds.size(); ++i) {
                const ActiveBound& b = r.active_bounds[i];
                text += std::string(i == 0 ? "" : ", ") + "{parameter: " + b.parameter +
                        ", side: " + (b.upper ? "upper" : "lower") + ", bound: " + number(b.bound) + "}";
            }
            text += "]\n";
        }
        text += "payload: {mass: " + number(r.mass) + ", com: [" + number(r.com.x()) + ", " + number(r.com.y()) +
                "], inertia: " + number(r.inertia) + "}\n";
        text += "standard_deviation: {mass: " + number(r.mass_sd) + ", com: [" + number(r.com_sd.x()) + ", " +
                number(r.com_sd.y()) + "], inertia: " + number(r.inertia_sd) + "}\n";
        if (!r.friction.empty()) {
            text += "friction:\n";
            for (const Estimate& e : r.friction) {
                text += "  - {name: " + io::yamlQuoted(e.name) + ", value: " + number(e.value) +
                        ", stddev: " + number(e.stddev) + ", unit: " + io::yamlQuoted(e.unit) + "}\n";
            }
        }
        RobotDescription merged = withPayload(robot, Payload{r.mass, r.inertia, r.com});
        for (const Estimate& e : r.friction) {
            // "limbJ.jointK.damping": write the identified value into the robot file
            for (LimbDescription& limb : merged.limbs) {
                for (std::size_t k = 0; k < 3; ++k) {
                    const std::string prefix = limb.name + ".joint" + std::to_string(k + 1) + ".";
                    if (e.name == prefix + "damping") limb.joints[k].damping = std::max(e.value, 0.0);
                    if (e.name == prefix + "friction") limb.joints[k].friction = std::max(e.value, 0.0);
                }
            }
        }
        file = "# " + io::terminalText(robot.name) + " with the payload identified from " +
               io::terminalText(options.data) + " merged into the platform\n";
        file += "# payload: {mass: " + number(r.mass) + ", com: [" + number(r.com.x()) + ", " + number(r.com.y()) +
                "], inertia: " + number(r.inertia) + "}\n";
        file += io::descriptionToYaml(merged);
        fit = r.fit;
    }
    steps.finish();
    std::cout << text;
    std::cout.flush();
    if (!std::cout) throw Error("cannot write to standard output");
    if (!options.output.empty()) io::writeTextFile(options.output, file);
    if (!options.figure.empty()) {
        figure(model, fit, options.figure);
    }
}

}  // namespace

void addIdentifyCommand(CLI::App& app) {
    auto options = std::make_shared<IdentifyOptions>();
    CLI::App* command = app.add_subcommand(
        "identify",
        "Identify a payload fixed to the platform (mass, c.o.m. [x, y] in the platform frame, moment of inertia\n"
        "about its own c.o.m.; the robot's own parameters from the robot file) or the robot's base parameters\n"
        "(--base; see `nocdyn regressor`) from a log of actuator positions and forces. The CSV holds\n"
        "t,u1..un and the forces: tau1..taun measured at each sample, or tau1_held..taun_held, commands held until\n"
        "the next sample (as `nocdyn control --log` writes them; other columns ignored); with du1..dun,ddu1..ddun\n"
        "they are used as given, else u and\n"
        "tau are low-pass filtered (zero phase) and u differentiated. The platform pose comes from the\n"
        "direct-kinematics tracker; weighted least squares (weights from each actuator's residual), then the\n"
        "physically consistent solution (mass > 0, inertia about the c.o.m. >= 0, and the bounds of --prior: the\n"
        "bounded least-squares solution, the bounds it lies on reported as active_bounds); standard deviations\n"
        "from the residuals; the last --holdout of the samples is held out to check the fit. Prints YAML.\n"
        "Example: nocdyn control --trajectory paper2 --payload-mass 0.5 --log log.csv && nocdyn identify --data "
        "log.csv");
    addRobotOption(*command, options->robot);
    command->add_option("--data", options->data, "Measured CSV: " + io::columnList(io::TableId::measurements))
        ->required()
        ->check(CLI::ExistingFile);
    command->add_flag("--payload", options->payload, "Identify a payload (the default)");
    command->add_flag("--base", options->base, "Identify the robot's base parameters (calibration, no payload)");
    command->add_flag("--friction", options->identification.friction,
                      "With --payload: identify the actuated joints' damping and Coulomb friction alongside");
    command->add_flag("--held-forces", options->identification.held_forces,
                      "The logged tau1..taun are commands held until the next sample (zero-order hold): each "
                      "sample's force is taken as the mean of the holds around it. Not needed for columns named "
                      "tau1_held..taun_held (as `nocdyn control --log` writes them), which are taken so anyway");
    command
        ->add_option("--cutoff", options->identification.cutoff,
                     "Low-pass cut-off when du, ddu are not given [Hz] (default: rate/10, at most 50)")
        ->check(finiteIn(1e-3, 1e6, "Hz"));
    command->add_option("--holdout", options->identification.holdout, "Fraction of the samples (the last) held out")
        ->check(finiteIn(0.0, 0.9, ""))
        ->capture_default_str();
    command
        ->add_option("--output,-o", options->output,
                     "YAML to write: the robot file with the payload merged into the platform (--payload), or "
                     "the calibration file of the base parameters (--base)")
        ->check(nonEmptyPath());
    command
        ->add_option("--calibration", options->calibration,
                     "With --payload: a calibration file (identify --base --output on data without payload) whose "
                     "base parameters replace the robot file's own parameters (the robot file still gives the "
                     "geometry)")
        ->check(CLI::ExistingFile);
    command
        ->add_option("--prior", options->prior,
                     "With --payload: a YAML file of bounds on the payload's parameters, e.g. 'payload: {mass: [0.4, "
                     "0.6], com_x: [-0.02, 0.02], com_y: [-0.02, 0.02], inertia: [0, 2e-3]}' (kg, m in the platform "
                     "frame, kg m^2 about the payload's c.o.m.; every key optional, ~ for an open side, equal bounds "
                     "fix a parameter). The estimate is the weighted least-squares solution within them. Not with "
                     "--base: base parameters are combinations of the robot's parameters, which have no such bounds")
        ->check(CLI::ExistingFile);
    command->add_option("--figure", options->figure,
                        "Measured against predicted forces on the held-out samples: writes STEM.png and STEM.svg");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
