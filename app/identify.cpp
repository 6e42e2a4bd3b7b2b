#include "app/identify.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/tables/calibration.hpp"
#include "nocdyn/text.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

using render::Figure;
using render::literalText;
using render::PlotPanel;
using render::PlotSeries;

namespace {

std::string exactNumber(double v) { return text::format("%.12g", v); }

/// The measurements of the CSV file: named columns, time increasing (errors name the line).
}  // namespace

Measurements readMeasurements(const std::string& path, int n) { return measurementsOf(io::readCsvFile(path), path, n); }

Measurements measurementsOf(const io::Table& table, const std::string& path, int n) {
    // where row k is: its line in the file, or its number from 1 in a table built in code
    const auto at = [&](Eigen::Index k) {
        const auto kk = static_cast<std::size_t>(k);
        return kk < table.lines.size() ? path + ":" + std::to_string(table.lines[kk])
                                       : path + ": row " + std::to_string(k + 1);
    };
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
        for (std::size_t c = 0; c < row.size() && c < table.columns.size(); ++c) {
            if (!std::isfinite(row[c])) throw Error(at(k) + ": column '" + table.columns[c] + "': not a finite number");
        }
        if (k > 0 && !(row[t_col] > m.t.back())) {
            throw Error(at(k) + ": column 't': " + exactNumber(row[t_col]) + " s is not after the previous sample's " +
                        exactNumber(m.t.back()) + " s (time must increase)");
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

namespace {

std::string fitText(const Model& model, const FitReport& fit) {
    std::string text = "# fit: " + std::to_string(fit.fit_samples) +
                       " samples, held out: " + std::to_string(fit.holdout_samples) +
                       ", condition number of the scaled regressor " + exactNumber(fit.condition) + "\n";
    for (int a = 0; a < model.actuators; ++a) {
        const auto aa = static_cast<std::size_t>(a);
        std::string line;
        line = text::format(
            "# actuator %d: rms residual %.4g (fit), %.4g held out, of rms force %.4g held out (%.3g %%)\n", a + 1,
            fit.rms_fit[aa], fit.rms_holdout[aa], fit.rms_measured[aa],
            fit.rms_measured[aa] > 0.0 ? 100.0 * fit.rms_holdout[aa] / fit.rms_measured[aa] : 0.0);
        text += line;
    }
    text += text::format(
        "# residuals correlated over %.3g samples (integrated autocorrelation): %.4g effective samples of %d; "
        "the standard deviations and covariance count it (batch means of %d samples)\n",
        fit.correlation_samples, fit.effective_samples, fit.fit_samples, fit.block_samples);
    return text;
}

/// A covariance matrix as a YAML flow sequence of rows, with the order of its entries.
std::string covarianceYaml(const Eigen::MatrixXd& covariance, const std::vector<std::string>& order) {
    std::string text = "covariance:\n  order: [";
    for (std::size_t i = 0; i < order.size(); ++i) text += (i == 0 ? "" : ", ") + io::yamlQuoted(order[i]);
    text += "]\n  matrix: [";
    for (Eigen::Index r = 0; r < covariance.rows(); ++r) {
        text += r == 0 ? "[" : ", [";
        for (Eigen::Index c = 0; c < covariance.cols(); ++c)
            text += (c == 0 ? "" : ", ") + text::format("%.6g", covariance(r, c));
        text += "]";
    }
    return text + "]\n";
}

Figure forcesFigure(const Model& model, const FitReport& fit) {
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
    return f;
}

}  // namespace

void validate(const IdentifyOptions& o) {
    if (o.data.empty() && !o.data_table) throw OptionError("data", "the measured CSV is required");
    if (o.cutoff != 0.0) requireIn(o.cutoff, kCutoffRange, "cutoff");
    requireIn(o.holdout, kHoldoutRange, "holdout");
    if (o.payload && o.base) throw OptionError("base", "give payload or base, not both");
    if (o.base && !o.calibration.empty())
        throw OptionError("calibration", "is for identifying a payload against the calibrated robot, not with base");
    if (o.base && (!o.prior.empty() || o.prior_bounds))
        throw OptionError("prior", "bounds a payload's parameters: not with base (base parameters have no bounds)");
}

IdentifyResult runIdentify(const IdentifyOptions& options, Observer& observer) {
    validate(options);
    // a two-DOF robot too: its payload is a point mass at the tool point (its mass only)
    const RobotDescription robot = loadRobot(options.robot);
    const Model model(robot);
    const bool point = model.task_dimension == 2;
    IdentificationOptions identification;
    static_cast<IdentificationSettings&>(identification) = options;
    if (!options.calibration.empty()) {
        identification.calibration = tables::loadCalibration(options.calibration, model);
        try {
            checkCalibration(model, *identification.calibration);
        } catch (const Error& e) {
            throw Error(options.calibration + ": " + e.what());
        }
    }
    if (options.prior_bounds)
        identification.prior = *options.prior_bounds;
    else if (!options.prior.empty())
        identification.prior = tables::loadPayloadPrior(options.prior);
    // a log of 10^6 samples or more takes seconds per step: say which step runs
    observer.step("reading " + io::terminalText(options.data), 1, 3);
    const Measurements measured = options.data_table
                                      ? measurementsOf(*options.data_table, options.data, model.actuators)
                                      : readMeasurements(options.data, model.actuators);
    stopIfRequested(observer);
    observer.step("reconstructing the motion", 2, 3);
    const Motion motion = reconstructMotion(model, measured, identification);
    stopIfRequested(observer);
    observer.step("least squares", 3, 3);
    IdentifyResult out;
    std::string text, file;
    FitReport fit;
    if (options.base) {
        const BaseResult result = identifyBase(model, motion, identification);
        text = "# " + io::terminalText(robot.name) + ": base parameters from " + io::terminalText(options.data) +
               " (see nocdyn regressor)\n";
        text += fitText(model, result.fit);
        text += "base_parameters:\n";
        for (const Estimate& e : result.beta) {
            text += "  - {name: " + io::yamlQuoted(e.name) + ", value: " + exactNumber(e.value) +
                    ", stddev: " + exactNumber(e.stddev) + ", robot_file: " + exactNumber(e.prior) +
                    ", unit: " + io::yamlQuoted(e.unit) + "}\n";
        }
        std::vector<std::string> order;
        order.reserve(result.beta.size());
        for (const Estimate& e : result.beta) order.push_back(e.name);
        text += covarianceYaml(result.covariance, order);
        std::string comment = "# " + io::terminalText(robot.name) + ": calibration (base parameters) identified from " +
                              io::terminalText(options.data) + "; use with nocdyn identify --payload --calibration\n";
        comment += fitText(model, result.fit);
        file = tables::calibrationToYaml(model, result, comment);
        fit = result.fit;
        out.base = result;
    } else {
        const PayloadResult r = identifyPayload(model, motion, identification);
        text =
            "# " + io::terminalText(robot.name) + ": payload from " + io::terminalText(options.data) +
            (options.calibration.empty() ? "" : ", against the calibration " + io::terminalText(options.calibration)) +
            "\n" + fitText(model, r.fit);
        if (r.inertia_constrained) {
            text += "# the unconstrained inertia about the c.o.m. came out negative (" +
                    exactNumber(r.inertia_unconstrained) + " kg m^2): the physically consistent solution has 0\n";
        }
        for (const ActiveBound& b : r.active_bounds) {
            if (r.inertia_constrained && b.parameter == "inertia" && !b.upper) continue;  // said above
            const std::string unit = b.parameter == "mass" ? " kg" : b.parameter == "inertia" ? " kg m^2" : " m";
            text += "# " + b.parameter + " is on its " + (b.upper ? "upper" : "lower") + " bound " +
                    exactNumber(b.bound) + unit +
                    (std::isnan(b.unbounded) ? std::string(" (the unbounded fit has no positive mass)")
                                             : " (the unbounded fit gives " + exactNumber(b.unbounded) + unit + ")") +
                    "\n";
        }
        if (!options.prior.empty() || options.prior_bounds || !r.active_bounds.empty()) {
            text += "active_bounds: [";
            for (std::size_t i = 0; i < r.active_bounds.size(); ++i) {
                const ActiveBound& b = r.active_bounds[i];
                text += std::string(i == 0 ? "" : ", ") + "{parameter: " + b.parameter +
                        ", side: " + (b.upper ? "upper" : "lower") + ", bound: " + exactNumber(b.bound) + "}";
            }
            text += "]\n";
        }
        if (point) {
            text +=
                "# a two-DOF robot: the payload is a point mass at the tool point, its mass only (no c.o.m. "
                "offset, no inertia: they have no effect on the forces)\n";
            text += "payload: {mass: " + exactNumber(r.mass) + "}\n";
            text += "standard_deviation: {mass: " + exactNumber(r.mass_sd) + "}\n";
        } else {
            text += "payload: {mass: " + exactNumber(r.mass) + ", com: [" + exactNumber(r.com.x()) + ", " +
                    exactNumber(r.com.y()) + "], inertia: " + exactNumber(r.inertia) + "}\n";
            text += "standard_deviation: {mass: " + exactNumber(r.mass_sd) + ", com: [" + exactNumber(r.com_sd.x()) +
                    ", " + exactNumber(r.com_sd.y()) + "], inertia: " + exactNumber(r.inertia_sd) + "}\n";
        }
        if (!r.friction.empty()) {
            text += "friction:\n";
            for (const Estimate& e : r.friction) {
                text += "  - {name: " + io::yamlQuoted(e.name) + ", value: " + exactNumber(e.value) +
                        ", stddev: " + exactNumber(e.stddev) + ", unit: " + io::yamlQuoted(e.unit) + "}\n";
            }
        }
        std::vector<std::string> order{"mass", "com_x", "com_y", "inertia"};
        if (point) order.resize(1);
        for (const Estimate& e : r.friction) order.push_back(e.name);
        text += covarianceYaml(r.covariance, order);
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
        file += point ? "# payload: {mass: " + exactNumber(r.mass) + "} (a point mass at the tool point)\n"
                      : "# payload: {mass: " + exactNumber(r.mass) + ", com: [" + exactNumber(r.com.x()) + ", " +
                            exactNumber(r.com.y()) + "], inertia: " + exactNumber(r.inertia) + "}\n";
        file += io::descriptionToYaml(merged);
        fit = r.fit;
        out.payload = r;
    }
    out.figure = forcesFigure(model, fit);
    out.text = std::move(text);
    out.yaml = std::move(file);
    return out;
}

}  // namespace nocdyn::app
