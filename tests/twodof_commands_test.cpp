// Two-DOF planar robots (motion: translation, pose [x, y] of a point tool) through `envelope`,
// `frequency-response` and `control`, on the shipped five-bar (horizontal) and biglide (vertical,
// under gravity).
//   - envelope: x and y only; at each point's amplitude A no limit is violated over the period
//     (checked here sample by sample on the full inverse dynamics), at A (1 + 2e-6) (the
//     bisection's tolerance) the limit the point names is: an effort-bound point's peak
//     |tau| / effort crosses 1 there. theta is refused.
//     With springs at the motors the band's third bound is the task's lumped model: f_1 and
//     |H_aa| = 1.1 at each band end from K_t = k A_t^T A_t and M_t by differences.
//   - frequency-response: the linearised plant over [x, y] (4 states) against central
//     differences of the forward dynamics in x, y, dx, dy and tau; the command's flat response at
//     rest (no gravity: H = M_t^-1 A_t^T) against the same differences, the actuator output's
//     |H| = |A_t M_t^-1 A_t^T| / w^2; a theta value and the shake-table loop refused.
//   - control: computed torque on the nocdyn plant tracks a smooth circle with errors of
//     micrometres, PD with errors larger; the table has no theta columns; a theta trajectory and
//     the Simbody plant refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "app/control.hpp"
#include "app/envelope.hpp"
#include "app/frequency_response.hpp"
#include "cli_support.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"

namespace nocdyn::test {
namespace {

constexpr double kPi = std::numbers::pi;

std::string shippedPath(const std::string& name) {
    return std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml";
}

app::RobotSource source(const std::string& name) {
    app::RobotSource s;
    s.path = shippedPath(name);
    return s;
}

/// The first violation over one period of A sin(2 pi f t) along `axis` about home, on the full
/// path (inverse dynamics, joint limits, efforts), and the period's peak |tau_a| / effort_a.
Status periodCheck(const Model& model, EnvelopeAxis axis, double f, double A, int samples, double& peak_ratio) {
    Data data(model);
    const auto i = static_cast<Eigen::Index>(axis);
    const double w = 2.0 * kPi * f;
    peak_ratio = 0.0;
    for (int k = 0; k < samples; ++k) {
        const double phase = 2.0 * kPi * k / samples;
        Pose p = model.home;
        Twist dp = Twist::Zero(), ddp = Twist::Zero();
        p(i) += A * std::sin(phase);
        dp(i) = A * w * std::cos(phase);
        ddp(i) = -A * w * w * std::sin(phase);
        if (const Status s = inverseDynamics(model, data, p, dp, ddp); !s) return s;
        if (const Status s = checkJointLimits(model, data); !s) return s;
        for (int a = 0; a < model.actuators; ++a) {
            const auto j = static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)]);
            const auto q = static_cast<std::size_t>(model.actuator_joint[static_cast<std::size_t>(a)]);
            peak_ratio = std::max(peak_ratio, std::abs(data.tau(a)) / model.limb[j].limits[q].effort);
        }
        if (const Status s = checkEffort(model, data); !s) return s;
    }
    return {};
}

EnvelopeLimit limitOfStatus(const Status& s) {
    switch (s.code) {
        case StatusCode::joint_limit_exceeded:
            return EnvelopeLimit::range;
        case StatusCode::velocity_exceeded:
            return EnvelopeLimit::velocity;
        case StatusCode::effort_exceeded:
            return EnvelopeLimit::effort;
        default:
            return EnvelopeLimit::workspace;
    }
}

TEST(TwoDofCommands, EnvelopeAmplitudesSitOnTheirLimits) {
    for (const std::string name : {"five-bar", "biglide"}) {
        SCOPED_TRACE(name);
        app::EnvelopeOptions options;
        options.robot = source(name);
        options.min_frequency = 1.0;
        options.max_frequency = 100.0;
        options.points = 3;
        const app::EnvelopeResult result = app::runEnvelope(options, app::silent());
        const Model model(io::loadRobotDescription(shippedPath(name)));
        ASSERT_EQ(result.points.size(), 6U);  // x and y, three frequencies each: no theta
        int effort_bound = 0;
        for (const EnvelopePoint& p : result.points) {
            SCOPED_TRACE(std::string(axisName(p.axis)) + " at " + std::to_string(p.frequency) + " Hz");
            EXPECT_NE(p.axis, EnvelopeAxis::theta);
            ASSERT_NE(p.limit, EnvelopeLimit::none);
            ASSERT_GT(p.amplitude, 0.0);
            double ratio = 0.0, over_ratio = 0.0;
            const Status at = periodCheck(model, p.axis, p.frequency, p.amplitude, options.samples_per_period, ratio);
            EXPECT_TRUE(at.ok()) << describe(at, model);
            // the bisection stops with hi - lo <= 1e-6 hi: the limit is violated within 2e-6 of A
            const Status over = periodCheck(model, p.axis, p.frequency, p.amplitude * (1.0 + 2e-6),
                                            options.samples_per_period, over_ratio);
            ASSERT_FALSE(over.ok()) << "nothing binds just above the envelope";
            EXPECT_EQ(limitOfStatus(over), p.limit) << describe(over, model);
            EXPECT_NEAR(ratio, p.peak_effort_ratio, 1e-12);
            std::printf("%s %s %g Hz: %.6g m, %s, peak |tau|/effort %.6f (%.6f at +2e-6)\n", name.c_str(),
                        axisName(p.axis), p.frequency, p.amplitude, limitName(p.limit), ratio, over_ratio);
            if (p.limit == EnvelopeLimit::effort) {
                ++effort_bound;
                EXPECT_LE(ratio, 1.0);
                EXPECT_GT(over_ratio, 1.0);
            }
        }
        // at 100 Hz the inertia forces bind on both robots
        EXPECT_GE(effort_bound, 2);
        EXPECT_EQ(result.table.rows.size(), 6U);
    }
    const Model five_bar(io::loadRobotDescription(shippedPath("five-bar")));
    try {
        (void)maximumAmplitude(five_bar, EnvelopeAxis::theta, 1.0);
        ADD_FAILURE() << "theta accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("has no theta axis"), std::string::npos) << e.what();
    }
}

/// ddp_t of the forward dynamics at (p, dp, tau) (two-DOF: [x, y] of the pose's acceleration).
Vector2 acceleration(const Model& model, const Pose& p, const Twist& dp, const ActuatorVector& tau) {
    Data data(model);
    const Status s = forwardDynamics(model, data, p, dp, tau);
    EXPECT_TRUE(s.ok()) << describe(s, model);
    return data.t_M_dot.tail<2>();
}

TEST(TwoDofCommands, LinearisedPlantMatchesFiniteDifferences) {
    for (const std::string name : {"five-bar", "biglide"}) {
        SCOPED_TRACE(name);
        const Model model(io::loadRobotDescription(shippedPath(name)));
        Data data(model);
        // a moving state off home, forces that do not hold it (every term of A and B nonzero)
        Pose p = model.home;
        p(1) += 0.01;
        p(2) -= 0.02;
        const Twist dp(0.0, 0.3, -0.2);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, Twist::Zero()).ok());
        ActuatorVector tau = data.tau;
        tau(0) += 0.1;
        StateSpace system;
        ASSERT_TRUE(linearize(model, data, p, dp, tau, LinearOutput::platform_acceleration, system).ok());
        ASSERT_EQ(system.A.rows(), 4);
        ASSERT_EQ(system.B.rows(), 4);
        ASSERT_EQ(system.C.rows(), 2);
        // columns x, y, dx, dy, then tau_1, tau_2, by central differences
        const double h = 1e-6;
        Eigen::MatrixXd fd(2, 6);
        for (int c = 0; c < 6; ++c) {
            Pose pp = p, pm = p;
            Twist dpp = dp, dpm = dp;
            ActuatorVector tp = tau, tm = tau;
            if (c < 2) {
                pp(1 + c) += h, pm(1 + c) -= h;
            } else if (c < 4) {
                dpp(c - 1) += h, dpm(c - 1) -= h;
            } else {
                tp(c - 4) += h, tm(c - 4) -= h;
            }
            fd.col(c) = (acceleration(model, pp, dpp, tp) - acceleration(model, pm, dpm, tm)) / (2.0 * h);
        }
        Eigen::MatrixXd exact(2, 6);
        exact << system.A.bottomRows(2), system.B.bottomRows(2);
        // measured: within 3e-8 of the largest entry on both robots
        EXPECT_LT((exact - fd).cwiseAbs().maxCoeff(), 1e-6 * exact.cwiseAbs().maxCoeff()) << "exact\n"
                                                                                          << exact << "\ndifferences\n"
                                                                                          << fd;
        EXPECT_TRUE(system.A.topLeftCorner(2, 2).isZero());
        EXPECT_TRUE(system.A.topRightCorner(2, 2).isIdentity());
    }
}

/// d(ddp_t)/d tau = M_t^-1 A_t^T at home at rest (no gravity), by central differences of the
/// forward dynamics.
Eigen::Matrix2d accelerationPerForce(const Model& model) {
    Eigen::Matrix2d D;
    const double h = 1e-4;
    for (int i = 0; i < 2; ++i) {
        ActuatorVector tp = ActuatorVector::Zero(2), tm = ActuatorVector::Zero(2);
        tp(i) = h, tm(i) = -h;
        D.col(i) =
            (acceleration(model, model.home, Twist::Zero(), tp) - acceleration(model, model.home, Twist::Zero(), tm)) /
            (2.0 * h);
    }
    return D;
}

/// du/dp_t = A_t at home, by central differences of the inverse kinematics.
Eigen::Matrix2d actuationJacobian(const Model& model) {
    Eigen::Matrix2d J;
    for (int c = 0; c < 2; ++c) {
        Data data(model);
        Pose pp = model.home, pm = model.home;
        pp(1 + c) += 1e-6, pm(1 + c) -= 1e-6;
        EXPECT_TRUE(inverseDisplacement(model, data, pp).ok());
        const Eigen::Vector2d up = data.u.head<2>();
        EXPECT_TRUE(inverseDisplacement(model, data, pm).ok());
        J.col(c) = (up - data.u.head<2>()) / 2e-6;
    }
    return J;
}

TEST(TwoDofCommands, EnvelopeBandEndsAreTheTasksLumpedModel) {
    // springs k at both motors: K_t = k A_t^T A_t, M_t = A_t^T D^-1 (D = M_t^-1 A_t^T), modal
    // damping C = M Phi diag(2 zeta w) Phi^T M; |H_aa| = |((K - w^2 M + j w C)^-1 K)_aa| leaves
    // [1/1.1, 1.1] at each axis' band end
    const std::filesystem::path dir = freshScratchDirectory("twodof_commands");
    std::string text = readWhole(shippedPath("five-bar"));
    const std::string limits = "effort: 8.0, velocity: 30.0}}";
    for (std::size_t at = text.find(limits); at != std::string::npos; at = text.find(limits, at + 1))
        text.replace(at, limits.size(), "effort: 8.0, velocity: 30.0}, stiffness: 5000.0}");
    const std::filesystem::path stiff = dir / "stiff-five-bar.yaml";
    std::ofstream(stiff) << text;
    app::EnvelopeOptions options;
    options.robot.path = stiff.string();
    options.min_frequency = options.max_frequency = 1.0;
    options.points = 1;
    const app::EnvelopeResult result = app::runEnvelope(options, app::silent());
    ASSERT_TRUE(result.resonance.known) << result.resonance.reason;
    const Model model(io::loadRobotDescription(stiff.string()));
    const Eigen::Matrix2d J = actuationJacobian(model);
    const Eigen::Matrix2d K = 5000.0 * J.transpose() * J;
    const Eigen::Matrix2d Mu = J.transpose() * accelerationPerForce(model).inverse();
    const Eigen::Matrix2d M = 0.5 * (Mu + Mu.transpose());
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> modes(K, M);
    const Eigen::Vector2d w = modes.eigenvalues().cwiseSqrt();
    EXPECT_NEAR(result.resonance.frequency, w(0) / (2.0 * kPi), 1e-6 * w(0));
    const double zeta = model.description.damping_ratio;
    const Eigen::Matrix2d MPhi = M * modes.eigenvectors();
    const Eigen::Matrix2d C = MPhi * (2.0 * zeta * w).asDiagonal() * MPhi.transpose();
    for (const EnvelopeAxis axis : {EnvelopeAxis::x, EnvelopeAxis::y}) {
        const double f = result.resonance.band_end[static_cast<std::size_t>(axis)];
        ASSERT_TRUE(std::isfinite(f));
        const double W = 2.0 * kPi * f;
        const Eigen::Matrix2cd Z = (K - W * W * M).cast<std::complex<double>>() +
                                   std::complex<double>(0.0, W) * C.cast<std::complex<double>>();
        const Eigen::Matrix2cd H = Z.inverse() * K.cast<std::complex<double>>();
        const int a = axis == EnvelopeAxis::x ? 0 : 1;
        std::printf("band end %s %.6g Hz: |H| %.9f (f_1 %.6g Hz)\n", axisName(axis), f, std::abs(H(a, a)),
                    result.resonance.frequency);
        EXPECT_NEAR(std::abs(H(a, a)), 1.1, 1e-5);
    }
    EXPECT_EQ(result.summary.find("theta"), std::string::npos) << result.summary;
}

TEST(TwoDofCommands, FrequencyResponseOverXYAtRest) {
    const Model model(io::loadRobotDescription(shippedPath("five-bar")));
    // at rest, no gravity: A's lower blocks vanish and ddp_t = M_t^-1 A_t^T tau at every frequency
    const Eigen::Matrix2d D = accelerationPerForce(model);
    const Eigen::Matrix2d J = actuationJacobian(model);
    app::FrequencyResponseOptions options;
    options.robot = source("five-bar");
    options.min_frequency = 1.0;
    options.max_frequency = 100.0;
    options.points = 3;
    const app::FrequencyResponseResult acc = app::runFrequencyResponse(options, app::silent());
    const std::vector<std::string> columns{"f",           "ddx_tau1_db",  "ddx_tau1_deg", "ddx_tau2_db", "ddx_tau2_deg",
                                           "ddy_tau1_db", "ddy_tau1_deg", "ddy_tau2_db",  "ddy_tau2_deg"};
    EXPECT_EQ(acc.columns, columns);
    ASSERT_EQ(acc.table.rows(), 3);
    for (Eigen::Index k = 0; k < 3; ++k) {
        for (int o = 0; o < 2; ++o) {
            for (int i = 0; i < 2; ++i) {
                // measured: 1e-9 dB from the differences
                EXPECT_NEAR(acc.table(k, 1 + 2 * (2 * o + i)), 20.0 * std::log10(std::abs(D(o, i))), 1e-6)
                    << "ddp_" << o << "/tau" << i;
            }
        }
    }
    EXPECT_NE(acc.summary.find("# operating point [x, y] = [0, 0.35]"), std::string::npos) << acc.summary;
    options.output_kind = LinearOutput::actuator_variables;
    const app::FrequencyResponseResult u = app::runFrequencyResponse(options, app::silent());
    const Eigen::Matrix2d G = J * D;  // u = A_t ddp_t / s^2
    for (Eigen::Index k = 0; k < 3; ++k) {
        const double w = 2.0 * kPi * u.table(k, 0);
        for (int a = 0; a < 2; ++a) {
            for (int i = 0; i < 2; ++i) {
                EXPECT_NEAR(u.table(k, 1 + 2 * (2 * a + i)), 20.0 * std::log10(std::abs(G(a, i)) / (w * w)), 1e-5);
            }
        }
    }
    // theta is no coordinate; the shake-table loop is not built for a two-DOF robot
    options.output_kind = LinearOutput::platform_acceleration;
    options.pose = {0.0, 0.3, 0.0};
    EXPECT_THROW((void)app::runFrequencyResponse(options, app::silent()), app::OptionError);
    options.pose = {0.02, 0.3};
    EXPECT_NO_THROW((void)app::runFrequencyResponse(options, app::silent()));
    options.pose.clear();
    options.closed_loop = true;
    try {
        (void)app::runFrequencyResponse(options, app::silent());
        ADD_FAILURE() << "closed loop accepted";
    } catch (const app::OptionError& e) {
        EXPECT_NE(std::string(e.what()).find("two-DOF"), std::string::npos) << e.what();
    }
}

TEST(TwoDofCommands, FrequencyResponseCommandLine) {
    const std::filesystem::path dir = freshScratchDirectory("twodof_commands");
    const std::string csv = (dir / "plant.csv").string();
    const CliResult ok = runCli("frequency-response --robot " + shippedPath("biglide") +
                                " --points 3 --pose 0.01 0.2 --quiet -o " + csv);
    ASSERT_EQ(ok.exit_code, 0) << ok.err;
    const std::string text = readWhole(csv);
    EXPECT_EQ(text.substr(0, text.find('\n')),
              "f,ddx_tau1_db,ddx_tau1_deg,ddx_tau2_db,ddx_tau2_deg,ddy_tau1_db,ddy_tau1_deg,ddy_tau2_db,ddy_tau2_deg");
    const CliResult theta = runCli("frequency-response --robot " + shippedPath("biglide") + " --pose 0 0.2 0.1");
    EXPECT_NE(theta.exit_code, 0);
    EXPECT_NE(theta.err.find("takes 2 values x, y: it has no theta"), std::string::npos) << theta.err;
}

/// A circle of radius r about the home point at f Hz, x = r cos, y = y0 + r sin, as a trajectory
/// file keyed x, y.
std::string circleFile(const std::filesystem::path& dir, double y0, double r, double f, bool theta = false) {
    const std::filesystem::path path = dir / "circle.yaml";
    std::ofstream out(path);
    out << "duration: 0.5\n"
        << "x: {offset: 0.0, harmonics: [{amplitude: " << r << ", frequency: " << f << ", phase: " << kPi / 2 << "}]}\n"
        << "y: {offset: " << y0 << ", harmonics: [{amplitude: " << r << ", frequency: " << f << "}]}\n";
    if (theta) out << "theta: {offset: 0.01}\n";
    return path.string();
}

TEST(TwoDofCommands, ControlTracksACircle) {
    const std::filesystem::path dir = freshScratchDirectory("twodof_commands");
    struct Case {
        std::string robot;
        double y0;
        double ct_rms, pd_rms;  ///< bounds on the RMS position error [m] (measured values below)
    };
    // measured RMS errors: computed torque 9.1e-9 m (five-bar), 4.1e-8 m (biglide); PD 9.7e-5 m, 1.3e-4 m
    for (const Case& c : {Case{"five-bar", 0.35, 5e-8, 3e-4}, Case{"biglide", 0.2, 2e-7, 3e-4}}) {
        SCOPED_TRACE(c.robot);
        app::ControlOptions options;
        options.robot = source(c.robot);
        options.trajectory = circleFile(dir, c.y0, 0.01, 2.0);
        options.plant = PlantKind::nocdyn;
        options.rate = 2000.0;
        options.natural_frequency = 20.0;
        const app::ControlResult ct = app::runControl(options, app::silent());
        const double ct_rms = std::hypot(ct.loop.pose_rms_error(1), ct.loop.pose_rms_error(2));
        options.controller = ControlLaw::pd;
        const app::ControlResult pd = app::runControl(options, app::silent());
        const double pd_rms = std::hypot(pd.loop.pose_rms_error(1), pd.loop.pose_rms_error(2));
        std::printf("%s: RMS position error computed torque %.4g m, PD %.4g m; theta's %.3g\n", c.robot.c_str(), ct_rms,
                    pd_rms, ct.loop.pose_peak_error(0));
        EXPECT_LT(ct_rms, c.ct_rms);
        EXPECT_LT(pd_rms, c.pd_rms);
        EXPECT_GT(pd_rms, 10.0 * ct_rms);            // the model-based law tracks far better
        EXPECT_EQ(ct.loop.pose_peak_error(0), 0.0);  // theta is no coordinate
        const std::vector<std::string> head(ct.table.columns.begin(), ct.table.columns.begin() + 7);
        EXPECT_EQ(head, (std::vector<std::string>{"t", "x_d", "y_d", "x", "y", "e_x", "e_y"}));
        EXPECT_EQ(ct.table.rows.front().size(), ct.table.columns.size());
        EXPECT_EQ(ct.text.find("theta"), std::string::npos) << ct.text;
        // through the encoders: the direct kinematics of the two-DOF robot tracks the pose
        options.controller = ControlLaw::computed_torque;
        options.measure = app::ControlMeasure::encoders;
        const app::ControlResult enc = app::runControl(options, app::silent());
        EXPECT_LT(std::hypot(enc.loop.pose_rms_error(1), enc.loop.pose_rms_error(2)), c.ct_rms);
        EXPECT_LT(enc.loop.measurement_peak_error.tail<2>().maxCoeff(), 1e-12);  // measured: 2e-16 m
        EXPECT_EQ(enc.text.find("theta"), std::string::npos) << enc.text;
    }
    app::ControlOptions options;
    options.robot = source("five-bar");
    options.trajectory = circleFile(dir, 0.35, 0.01, 2.0, true);
    options.plant = PlantKind::nocdyn;
    options.rate = 2000.0;
    try {
        (void)app::runControl(options, app::silent());
        ADD_FAILURE() << "a theta trajectory accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("theta: a two-DOF robot"), std::string::npos) << e.what();
    }
    options.trajectory = circleFile(dir, 0.35, 0.01, 2.0);
    // the build's default plant, not chosen: nocdyn's for a two-DOF robot
    options.plant = PlantKind::simbody;
    options.plant_given = false;
    const app::ControlResult by_default = app::runControl(options, app::silent());
    EXPECT_EQ(by_default.loop.plant, "nocdyn forward dynamics");
    EXPECT_LT(by_default.loop.pose_rms_error.tail<2>().norm(), 5e-8);
    options.plant_given = true;
    try {
        (void)app::runControl(options, app::silent());
        ADD_FAILURE() << "the Simbody plant accepted";
    } catch (const app::OptionError& e) {
        EXPECT_NE(std::string(e.what()).find("give plant nocdyn"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace nocdyn::test
