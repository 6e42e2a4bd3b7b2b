// Operating envelope of any robot (envelope.hpp): on the paper's 3-PRR it equals the
// hand-derived 3-PRR envelope's numbers (the P joints' range is the stroke, their effort the
// peak force); each kind of
// limit binds where it should (range flat in f, velocity ~ 1/f, effort ~ 1/f^2) and is reached
// at the envelope; every example robot has an envelope whose limits name their actuator.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "nocdyn/io/short_form.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"

namespace nocdyn::test {
namespace {

constexpr EnvelopeAxis kAxes[] = {EnvelopeAxis::theta, EnvelopeAxis::x, EnvelopeAxis::y};

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
    options.frequencies = 3;
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

TEST(GeneralEnvelope, RefusesFrequenciesOutOfRange) {
    const Model model{io::expand(io::RobotParameters{})};
    EXPECT_THROW((void)maximumAmplitude(model, EnvelopeAxis::x, 0.0), Error);
    EXPECT_THROW((void)maximumAmplitude(model, EnvelopeAxis::x, 1e5), Error);
    EnvelopeOptions options;
    options.frequencies = 0;
    EXPECT_THROW((void)operatingEnvelope(model, options), Error);
}

}  // namespace
}  // namespace nocdyn::test
