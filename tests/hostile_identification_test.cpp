// Identifiability judged against the data: a motion that leaves payload parameters without
// effect on the forces (a translation along x alone: no rotation, so neither the inertia nor
// the c.o.m.'s x acts) is an error naming them and what the motion does determine, never a
// confident payload; a motion that excites every parameter still identifies them exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "identification_support.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/examples.hpp"

namespace nocdyn::test {
namespace {

const Payload kPayload{0.5, 8e-4, Vector2(0.012, -0.007)};

std::string identifyError(const Model& nominal, const Motion& motion) {
    try {
        const PayloadResult r = identifyPayload(nominal, motion);
        return "a payload was reported: mass " + std::to_string(r.mass) + ", com [" + std::to_string(r.com.x()) + ", " +
               std::to_string(r.com.y()) + "], inertia " + std::to_string(r.inertia);
    } catch (const Error& e) {
        return e.what();
    }
}

TEST(HostileIdentifiability, TranslationAlongXAloneNamesTheInertiaAndComXAsNotIdentifiable) {
    const Model nominal(io::exampleRobot("paper-3prr-general"));
    const Model loaded(withPayload(io::exampleRobot("paper-3prr-general"), kPayload));
    PoseTrajectory trajectory;
    trajectory.x.harmonics = {{0.002, 5.0, 0.0}};
    const Motion motion = exactMotion(loaded, trajectory, 1000, 0.001);
    ASSERT_EQ(motion.t.size(), 1000U);
    const std::string what = identifyError(nominal, motion);
    EXPECT_NE(what.find("not identifiable"), std::string::npos) << what;
    EXPECT_NE(what.find("payload inertia"), std::string::npos) << what;
    EXPECT_NE(what.find("payload c.o.m. x"), std::string::npos) << what;
    // what the translation does determine: the mass, and m c_y (0.5 kg * -7 mm), fitted alone
    EXPECT_NE(what.find("payload mass 0.5 kg"), std::string::npos) << what;
    EXPECT_NE(what.find("payload c.o.m. y (mass times) -0.0035 kg m"), std::string::npos) << what;
}

TEST(HostileIdentifiability, AFilteredLogOfATranslationAlongXAloneIsNoConfidentPayloadEither) {
    // u and tau only: the rates come from filtering and differentiating u, whose rounding
    // gives the rotation a little noise (the combination is excited 5e-5 times the best)
    const Model nominal(io::exampleRobot("paper-3prr-general"));
    const Model loaded(withPayload(io::exampleRobot("paper-3prr-general"), kPayload));
    Data data(loaded);
    Measurements m;
    m.u.resize(1000, 3);
    m.tau.resize(1000, 3);
    for (int k = 0; k < 1000; ++k) {
        const double t = 0.001 * k, w = 2.0 * 3.141592653589793 * 5.0;
        ASSERT_TRUE(inverseDynamics(loaded, data, Pose(0.0, 0.002 * std::sin(w * t), 0.0),
                                    Twist(0.0, 0.002 * w * std::cos(w * t), 0.0),
                                    Twist(0.0, -0.002 * w * w * std::sin(w * t), 0.0))
                        .ok());
        m.t.push_back(t);
        m.u.row(k) = data.u.transpose();
        m.tau.row(k) = data.tau.transpose();
    }
    const std::string what = identifyError(nominal, reconstructMotion(nominal, m));
    EXPECT_NE(what.find("not identifiable"), std::string::npos) << what;
    EXPECT_NE(what.find("payload inertia"), std::string::npos) << what;
    EXPECT_NE(what.find("payload c.o.m. x"), std::string::npos) << what;
}

TEST(HostileIdentifiability, TranslationAlongYAloneNamesTheInertiaAndComY) {
    const Model nominal(io::exampleRobot("paper-3prr-general"));
    const Model loaded(withPayload(io::exampleRobot("paper-3prr-general"), kPayload));
    PoseTrajectory trajectory;
    trajectory.y.harmonics = {{0.002, 5.0, 0.0}};
    const std::string what = identifyError(nominal, exactMotion(loaded, trajectory, 1000, 0.001));
    EXPECT_NE(what.find("payload inertia"), std::string::npos) << what;
    EXPECT_NE(what.find("payload c.o.m. y"), std::string::npos) << what;
    EXPECT_EQ(what.find("payload c.o.m. x (mass times),"), std::string::npos) << what;
    EXPECT_NE(what.find("payload mass 0.5 kg"), std::string::npos) << what;
}

TEST(HostileIdentifiability, RotationWithTranslationStillIdentifiesEveryParameterExactly) {
    const Model nominal(io::exampleRobot("paper-3prr-general"));
    const Model loaded(withPayload(io::exampleRobot("paper-3prr-general"), kPayload));
    PoseTrajectory trajectory;
    trajectory.x.harmonics = {{0.002, 5.0, 0.0}};
    trajectory.y.harmonics = {{0.002, 7.0, 0.5}};
    trajectory.theta.harmonics = {{0.05, 3.0, 0.0}};
    const PayloadResult r = identifyPayload(nominal, exactMotion(loaded, trajectory, 1000, 0.001));
    EXPECT_NEAR(r.mass, 0.5, 1e-9);
    EXPECT_NEAR(r.com.x(), 0.012, 1e-9);
    EXPECT_NEAR(r.com.y(), -0.007, 1e-9);
    EXPECT_NEAR(r.inertia, 8e-4, 1e-9);
}

}  // namespace
}  // namespace nocdyn::test
