// Operating envelope of any robot (envelope.hpp): on the paper's 3-PRR it equals the
// hand-derived 3-PRR envelope's numbers (the P joints' range is the stroke, their effort the
// peak force); each kind of
// limit binds where it should (range flat in f, velocity ~ 1/f, effort ~ 1/f^2) and is reached
// at the envelope; every example robot has an envelope whose limits name their actuator; its
// points come in the order x, y, theta; a robot file that declares compliance bounds the band
// by the first natural frequency at home (stiffnessAndModes), where the limit is resonance.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/io/short_form.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"

namespace nocdyn::test {
namespace {

constexpr EnvelopeAxis kAxes[] = {EnvelopeAxis::x, EnvelopeAxis::y, EnvelopeAxis::theta};

/// First natural frequency [Hz] of robots/paper-3prr-compliant.yaml's lumped model at home
/// (`nocdyn pose 0 0 0 --robot robots/paper-3prr-compliant.yaml --json`).
constexpr double kCompliantFirstFrequency = 41.038352764818065;

RobotDescription example(const std::string& robot) {
    return io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml");
}

TEST(GeneralEnvelope, EqualsThe3PrrEnvelopeOnThePaperRobot) {
    // The hand-derived 3-PRR envelope's amplitudes [rad, m], its binding limit (0 stroke =
    // range, 1 force = effort) and limb (1-based), at 1, 10 and 100 Hz on each axis (theta, x, y).
    struct Reference {
        EnvelopeAxis axis;
        double frequency, amplitude;
        EnvelopeLimit limit;
        int limb;
    };
    const Reference references[] = {
        {EnvelopeAxis::theta, 1.0, 0.1879594326019287, EnvelopeLimit::range, 1},
        {EnvelopeAxis::theta, 10.0, 0.1879594326019287, EnvelopeLimit::range, 1},
        {EnvelopeAxis::theta, 100.0, 0.004086432151751751, EnvelopeLimit::effort, 1},
        {EnvelopeAxis::x, 1.0, 0.011507391947507859, EnvelopeLimit::range, 2},
        {EnvelopeAxis::x, 10.0, 0.011507391947507859, EnvelopeLimit::range, 2},
        {EnvelopeAxis::x, 100.0, 0.00021359545375760383, EnvelopeLimit::effort, 2},
        {EnvelopeAxis::y, 1.0, 0.010471151626110077, EnvelopeLimit::range, 3},
        {EnvelopeAxis::y, 10.0, 0.010471151626110077, EnvelopeLimit::range, 3},
        {EnvelopeAxis::y, 100.0, 0.00018826531854093477, EnvelopeLimit::effort, 3},
    };
    const Model model{io::expand(io::RobotParameters{})};
    for (const Reference& r : references) {
        const EnvelopePoint general = maximumAmplitude(model, r.axis, r.frequency);
        // both bisect to 1e-6 of the amplitude
        EXPECT_NEAR(general.amplitude, r.amplitude, 4e-6 * r.amplitude) << axisName(r.axis) << " at " << r.frequency;
        EXPECT_EQ(general.limit, r.limit) << axisName(r.axis) << " at " << r.frequency << " Hz";
        EXPECT_EQ(general.limb + 1, r.limb);
        EXPECT_EQ(general.joint, 0);
        EXPECT_EQ(general.actuator, general.limb);  // one slider per limb, in order
    }
}

/// Peak over one period (finely sampled, off the envelope's grid) of max_j |q_j| / range and
/// max_j |q'_j| / velocity limit over the limited joints, and of |tau_a| / effort.
struct Peaks {
    double range = 0.0, velocity = 0.0, effort = 0.0;
};
Peaks peaks(const Model& model, EnvelopeAxis axis, double f, double amplitude) {
    Data data(model);
    Peaks out;
    const double w = 2.0 * std::numbers::pi * f;
    const int index = static_cast<int>(axis);
    for (int k = 0; k < 4096; ++k) {
        const double phase = 2.0 * std::numbers::pi * (k + 0.37) / 4096;
        Pose p = model.home;
        Twist dp = Twist::Zero(), ddp = Twist::Zero();
        p(index) += amplitude * std::sin(phase);
        dp(index) = amplitude * w * std::cos(phase);
        ddp(index) = -amplitude * w * w * std::sin(phase);
        EXPECT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
        for (int j = 0; j < model.limbs; ++j) {
            const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
            for (std::size_t k2 = 0; k2 < 3; ++k2) {
                const JointLimits& lim = limb.limits[k2];
                const double q = data.limb[static_cast<std::size_t>(j)].q(static_cast<int>(k2));
                const double qd = data.limb[static_cast<std::size_t>(j)].gamma_dot(static_cast<int>(k2));
                if (std::isfinite(lim.upper)) out.range = std::max(out.range, q / lim.upper);
                if (std::isfinite(lim.lower)) out.range = std::max(out.range, q / lim.lower);
                if (std::isfinite(lim.velocity)) out.velocity = std::max(out.velocity, std::abs(qd) / lim.velocity);
                if (limb.actuator[k2] >= 0 && std::isfinite(lim.effort)) {
                    out.effort = std::max(out.effort, std::abs(data.tau(limb.actuator[k2])) / lim.effort);
                }
            }
        }
    }
    return out;
}

TEST(GeneralEnvelope, RangeVelocityAndEffortEachBindWithTheirSlopeAndAreReached) {
    // the paper's robot with a velocity limit on its sliders (symmetric ranges about home)
    RobotDescription robot = expand(io::RobotParameters{});
    for (auto& limb : robot.limbs) limb.joints[0].limits.velocity = 0.5;  // [m/s]
    const Model model(robot);
    const EnvelopeAxis axis = EnvelopeAxis::x;
    const EnvelopePoint low = maximumAmplitude(model, axis, 1.0);
    const EnvelopePoint mid1 = maximumAmplitude(model, axis, 12.0);
    const EnvelopePoint mid2 = maximumAmplitude(model, axis, 16.0);
    const EnvelopePoint high1 = maximumAmplitude(model, axis, 200.0);
    const EnvelopePoint high2 = maximumAmplitude(model, axis, 400.0);
    ASSERT_EQ(low.limit, EnvelopeLimit::range);
    ASSERT_EQ(mid1.limit, EnvelopeLimit::velocity);
    ASSERT_EQ(mid2.limit, EnvelopeLimit::velocity);
    ASSERT_EQ(high1.limit, EnvelopeLimit::effort);
    ASSERT_EQ(high2.limit, EnvelopeLimit::effort);
    // A ~ 1 / f, up to the change of the velocity gain du/dp with the amplitude itself
    EXPECT_NEAR(mid1.amplitude / mid2.amplitude, 16.0 / 12.0, 2e-3);
    EXPECT_NEAR(high1.amplitude / high2.amplitude, 4.0, 0.02);  // A ~ 1 / f^2 (gravity-free)
    for (const EnvelopePoint* p : {&low, &mid1, &high1}) {
        EXPECT_GE(p->actuator, 0);
        const Peaks at = peaks(model, axis, p->frequency, p->amplitude);
        const double reached = p->limit == EnvelopeLimit::range      ? at.range
                               : p->limit == EnvelopeLimit::velocity ? at.velocity
                                                                     : at.effort;
        // reached at the envelope, to the bisection tolerance and the 256-sample grid
        EXPECT_NEAR(reached, 1.0, 2e-3) << limitName(p->limit);
        EXPECT_LE(at.range, 1.0 + 1e-9);
        EXPECT_LE(at.velocity, 1.0 + 2e-3);
        EXPECT_LE(at.effort, 1.0 + 2e-3);
    }
    EXPECT_NEAR(high1.peak_effort_ratio, 1.0, 1e-5);
}

TEST(GeneralEnvelope, EveryExampleRobotHasAnEnvelopeNamingItsLimits) {
    EnvelopeOptions options;
    options.points = 3;
    options.min_frequency = 1.0;
    options.max_frequency = 100.0;
    for (const char* name : {"3-rrr", "3-rpr", "4-rrr"}) {
        const Model model(example(name));
        const auto points = operatingEnvelope(model, options);
        ASSERT_EQ(points.size(), 9u);
        for (const EnvelopePoint& p : points) {
            EXPECT_GT(p.amplitude, 0.0) << name << " " << axisName(p.axis) << " " << p.frequency;
            EXPECT_LE(p.amplitude, p.kinematic_amplitude);
            EXPECT_NE(p.limit, EnvelopeLimit::none) << name;
            EXPECT_GE(p.limb, 0) << name;
            if (p.limit == EnvelopeLimit::effort) {
                EXPECT_GE(p.actuator, 0) << name;
            }
        }
    }
}

TEST(GeneralEnvelope, APassiveJointsLimitsAreCheckedAndWideOnesChangeNothing) {
    // Limits on passive joints take the per-sample full path, the actuated joints' alone the
    // batch: wide passive limits give the same envelope, narrow ones bind at the passive joint.
    const RobotDescription robot = example("3-rrr");
    RobotDescription wide = robot, narrow = robot;
    for (std::size_t j = 0; j < robot.limbs.size(); ++j) {
        for (std::size_t k : {1u, 2u}) {
            wide.limbs[j].joints[k].limits.lower = -100.0;  // [rad]
            wide.limbs[j].joints[k].limits.upper = 100.0;
            wide.limbs[j].joints[k].limits.velocity = 1e6;  // [rad/s]
        }
        narrow.limbs[j].joints[1].limits.lower = -0.01;  // the elbow [rad]
        narrow.limbs[j].joints[1].limits.upper = 0.01;
    }
    const Model model(robot), model_wide(wide), model_narrow(narrow);
    for (const EnvelopeAxis axis : kAxes) {
        for (const double f : {1.0, 50.0}) {
            const EnvelopePoint a = maximumAmplitude(model, axis, f);
            const EnvelopePoint b = maximumAmplitude(model_wide, axis, f);
            EXPECT_NEAR(b.amplitude, a.amplitude, 1e-12 * a.amplitude) << axisName(axis) << " at " << f << " Hz";
            EXPECT_NEAR(b.kinematic_amplitude, a.kinematic_amplitude, 1e-12 * a.kinematic_amplitude);
            EXPECT_EQ(b.limit, a.limit);
            EXPECT_EQ(b.limb, a.limb);
            EXPECT_EQ(b.joint, a.joint);
            EXPECT_NEAR(b.peak_tau, a.peak_tau, 1e-9 * a.peak_tau);
        }
        const EnvelopePoint elbow = maximumAmplitude(model_narrow, axis, 1.0);
        EXPECT_EQ(elbow.limit, EnvelopeLimit::range) << axisName(axis);
        EXPECT_EQ(elbow.joint, 1);
        EXPECT_EQ(elbow.actuator, -1);
        EXPECT_LT(elbow.amplitude, maximumAmplitude(model, axis, 1.0).amplitude);
    }
}

TEST(GeneralEnvelope, PointsComeAxisAfterAxisInTheOrderXYTheta) {
    EnvelopeOptions options;
    options.points = 2;
    const auto points = operatingEnvelope(Model(example("3-rrr")), options);
    ASSERT_EQ(points.size(), 6u);
    const EnvelopeAxis expected[] = {EnvelopeAxis::x, EnvelopeAxis::x,     EnvelopeAxis::y,
                                     EnvelopeAxis::y, EnvelopeAxis::theta, EnvelopeAxis::theta};
    for (std::size_t k = 0; k < points.size(); ++k) EXPECT_EQ(points[k].axis, expected[k]) << k;
    const io::Table table = tables::toTable(points);
    EXPECT_EQ(table.categories[0][static_cast<std::size_t>(table.rows[0][0])], "x");
    EXPECT_EQ(table.categories[0][static_cast<std::size_t>(table.rows[5][0])], "theta");
}

TEST(GeneralEnvelope, TheFirstNaturalFrequencyAtHomeIsTheBandsThirdBound) {
    const Model model(example("paper-3prr-compliant"));
    const EnvelopeResonance resonance = envelopeResonance(model);
    ASSERT_TRUE(resonance.known) << resonance.reason;
    EXPECT_TRUE(resonance.declared);
    // the lumped model at home, as `nocdyn pose` reports it
    const StiffnessModel compliance(model);
    Data data(model);
    StiffnessData stiffness;
    LumpedModes modes;
    ASSERT_TRUE(stiffnessAndModes(model, compliance, data, model.home, stiffness, modes));
    EXPECT_EQ(resonance.frequency, modes.frequency(0));
    EXPECT_NEAR(resonance.frequency, kCompliantFirstFrequency, 1e-9 * kCompliantFirstFrequency);

    // f_1 / 2, f_1 and 2 f_1 (log-spaced: the middle one is f_1 to the last bit)
    EnvelopeOptions options;
    options.points = 3;
    options.min_frequency = 0.5 * resonance.frequency;
    options.max_frequency = 2.0 * resonance.frequency;
    const auto points = operatingEnvelope(model, options);
    ASSERT_EQ(points.size(), 9u);
    for (const EnvelopePoint& p : points) {
        const EnvelopePoint rigid = maximumAmplitude(model, p.axis, p.frequency);
        EXPECT_EQ(p.amplitude, rigid.amplitude);  // the rigid model's number, kept
        // the band of each axis ends where its dynamic amplification leaves [1 / 1.1, 1.1],
        // below f_1 (f_1 / 2 is beyond it already: 1 / (1 - 1/4) = 1.33)
        EXPECT_LT(resonance.band_end[static_cast<std::size_t>(p.axis)], resonance.frequency);
        if (p.frequency >= resonance.band_end[static_cast<std::size_t>(p.axis)]) {
            EXPECT_EQ(p.limit, EnvelopeLimit::resonance) << axisName(p.axis) << " at " << p.frequency;
            EXPECT_EQ(p.limb, -1);
            EXPECT_EQ(p.joint, -1);
            EXPECT_EQ(p.actuator, -1);
        } else {
            EXPECT_EQ(p.limit, rigid.limit) << axisName(p.axis) << " at " << p.frequency;
            EXPECT_NE(p.limit, EnvelopeLimit::resonance);
        }
    }
    EXPECT_EQ(points[1].frequency, resonance.frequency);
    EXPECT_STREQ(limitName(EnvelopeLimit::resonance), "resonance");

    // the CSV names it in its optional last column, in every row
    const io::Table table = tables::toTable(points, resonance);
    ASSERT_EQ(table.columns, io::columnNames(io::TableId::envelope, {.optional = true}));
    EXPECT_EQ(table.columns.back(), "first_natural_frequency");
    for (const auto& row : table.rows) EXPECT_EQ(row.back(), resonance.frequency);
    EXPECT_EQ(table.categories[3][static_cast<std::size_t>(table.rows[1][3])], "resonance");
}

/// |p_a| of the lumped model M ddp + C dp + K p = K e_a sin(w t) by a direct complex solve at
/// f [Hz] (C the modal damping of ratio zeta), independent of the modal sum envelope.cpp uses.
double amplificationBySolve(const LumpedModes& modes, const Matrix3& K, double zeta, int a, double f) {
    const double w = 2.0 * std::numbers::pi * f;
    const Matrix3 MPhi = modes.M * modes.shape;
    Vector3 two_zeta_w;
    for (int i = 0; i < 3; ++i) two_zeta_w(i) = 2.0 * zeta * 2.0 * std::numbers::pi * modes.frequency(i);
    const Matrix3 C = MPhi * two_zeta_w.asDiagonal() * MPhi.transpose();
    const Eigen::Matrix3cd Z = (K - w * w * modes.M).cast<std::complex<double>>() +
                               std::complex<double>(0.0, w) * C.cast<std::complex<double>>();
    const Eigen::Vector3cd p = Z.partialPivLu().solve((K * Vector3::Unit(a)).cast<std::complex<double>>());
    return std::abs(p(a));
}

TEST(GeneralEnvelope, NoFrequencyReportedUsableIsAmplifiedBeyondTheLimit) {
    const Model model(example("paper-3prr-compliant"));
    const StiffnessModel compliance(model);
    Data data(model);
    StiffnessData stiffness;
    LumpedModes modes;
    ASSERT_TRUE(stiffnessAndModes(model, compliance, data, model.home, stiffness, modes));
    const double zeta = model.description.damping_ratio;
    EXPECT_EQ(zeta, 0.02);  // the default: the file sets none
    for (const double limit : {1.1, 1.5, 3.0}) {
        EnvelopeOptions options;
        options.min_frequency = 1.0;
        options.max_frequency = 200.0;
        options.points = 41;
        options.amplification = limit;
        const EnvelopeResonance resonance = envelopeResonance(model, limit);
        ASSERT_TRUE(resonance.known);
        for (const EnvelopePoint& p : operatingEnvelope(model, options)) {
            const int a = static_cast<int>(p.axis);
            const double h = amplificationBySolve(modes, stiffness.K, zeta, a, p.frequency);
            EXPECT_NEAR(dynamicAmplification(resonance, p.axis, p.frequency), h, 1e-9 * h);
            if (p.limit == EnvelopeLimit::resonance) continue;
            EXPECT_LE(h, limit) << axisName(p.axis) << " at " << p.frequency << " Hz reported usable";
            EXPECT_GE(h, 1.0 / limit) << axisName(p.axis) << " at " << p.frequency << " Hz reported usable";
        }
        // each axis' band ends where the amplification reaches the limit
        for (const EnvelopeAxis axis : kEnvelopeAxes) {
            const double f = resonance.band_end[static_cast<std::size_t>(axis)];
            ASSERT_TRUE(std::isfinite(f)) << axisName(axis);
            EXPECT_NEAR(amplificationBySolve(modes, stiffness.K, zeta, static_cast<int>(axis), f), limit, 1e-6 * limit)
                << axisName(axis);
        }
    }
    // the translation's mode alone along x at home (symmetric machine): 1 / (1 - r^2) = 1.1 at
    // r^2 = 1 / 11, and 1 / (2 zeta) = 25 at resonance
    const EnvelopeResonance resonance = envelopeResonance(model);
    EXPECT_NEAR(resonance.band_end[static_cast<std::size_t>(EnvelopeAxis::x)], resonance.frequency / std::sqrt(11.0),
                1e-3 * resonance.frequency);
    EXPECT_NEAR(dynamicAmplification(resonance, EnvelopeAxis::x, resonance.frequency), 25.0, 0.1);
    EXPECT_THROW((void)envelopeResonance(model, 1.0), Error);
}

TEST(GeneralEnvelope, WithoutDeclaredComplianceTheEnvelopeIsUnchangedAndTheBoundUnknown) {
    const Model model(example("paper-3prr-general"));
    const EnvelopeResonance resonance = envelopeResonance(model);
    EXPECT_FALSE(resonance.known);
    EXPECT_FALSE(resonance.declared);
    EXPECT_EQ(resonance.reason, "the robot file declares no compliance");
    EnvelopeOptions options;
    options.points = 2;
    options.min_frequency = 10.0;
    options.max_frequency = 1000.0;
    const auto points = operatingEnvelope(model, options);
    for (const EnvelopePoint& p : points) {
        const EnvelopePoint rigid = maximumAmplitude(model, p.axis, p.frequency);
        EXPECT_EQ(p.limit, rigid.limit);
        EXPECT_EQ(p.limb, rigid.limb);
        EXPECT_EQ(p.amplitude, rigid.amplitude);
    }
    EXPECT_EQ(tables::toTable(points, resonance).columns, io::columnNames(io::TableId::envelope));
}

TEST(GeneralEnvelope, ComplianceThatLeavesALimbRigidGivesNoBoundAndSaysWhy) {
    // the compliant prototype with limbs 2 and 3 rigid again: K is not finite, f_1 unknown
    RobotDescription robot = example("paper-3prr-compliant");
    for (std::size_t j : {1u, 2u}) {
        for (auto& joint : robot.limbs[j].joints) joint.stiffness.reset();
        for (auto& body : robot.limbs[j].bodies) body.elastic.reset();
    }
    const Model model(robot);
    const EnvelopeResonance resonance = envelopeResonance(model);
    EXPECT_TRUE(resonance.declared);
    EXPECT_FALSE(resonance.known);
    EXPECT_EQ(resonance.reason.rfind("at home: ", 0), 0u) << resonance.reason;
    EXPECT_NE(resonance.reason.find("limb 2"), std::string::npos) << resonance.reason;
    EnvelopeOptions options;
    options.points = 1;
    options.min_frequency = options.max_frequency = 500.0;
    for (const EnvelopePoint& p : operatingEnvelope(model, options)) EXPECT_NE(p.limit, EnvelopeLimit::resonance);
}

TEST(GeneralEnvelope, RefusesFrequenciesOutOfRange) {
    const Model model{io::expand(io::RobotParameters{})};
    EXPECT_THROW((void)maximumAmplitude(model, EnvelopeAxis::x, 0.0), Error);
    EXPECT_THROW((void)maximumAmplitude(model, EnvelopeAxis::x, 1e5), Error);
    EnvelopeOptions options;
    options.points = 0;
    EXPECT_THROW((void)operatingEnvelope(model, options), Error);
}

}  // namespace
}  // namespace nocdyn::test
