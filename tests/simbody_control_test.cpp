// Task-space computed torque (control.hpp) designed on the NOC model, run on the
// independent Simbody model of the robot file (SimbodyMechanism as a plant): the redundant
// 4-RRR and the 3-RRR track the paper's trajectory 1, also with a payload the controller does
// not know.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "nocdyn/sim/control.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/validation/simbody_plant.hpp"

namespace nocdyn::test {
namespace {

PoseLoopResult trackOnSimbody(const RobotDescription& robot, const RobotDescription& plant_robot) {
    const Model model(robot);
    PoseController controller(model, ControlLaw::computed_torque, taskCriticallyDamped(50.0));
    validation::SimbodyPlant plant(plant_robot, 1e-8);
    PoseLoopOptions options;
    options.rate = 5000.0;
    options.duration = 0.1;
    return runPoseLoop(controller, plant, paperTrajectory1(), options);
}

double largest(const Vector3& e) { return e.cwiseAbs().maxCoeff(); }

class SimbodyExample : public ::testing::TestWithParam<std::string> {};

// The two models agree to integration accuracy, so the only error is the zero-order hold
// over one 200 us tick and Simbody's 1e-8 integration: well under 1 um (1 urad).
TEST_P(SimbodyExample, ComputedTorqueTracksTrajectory1OnTheSimbodyPlant) {
    const RobotDescription robot = io::exampleRobot(GetParam());
    const PoseLoopResult result = trackOnSimbody(robot, robot);
    ASSERT_EQ(result.t.size(), 500U);
    EXPECT_EQ(result.plant, "Simbody");
    EXPECT_LT(largest(result.pose_peak_error), 1e-6);
    for (const double e : result.peak_error) EXPECT_LT(e, 1e-5);
    EXPECT_EQ(result.saturated_ticks, 0U);
}

TEST_P(SimbodyExample, UnknownPayloadOnTheSimbodyPlantStaysBounded) {
    const RobotDescription robot = io::exampleRobot(GetParam());
    const PoseLoopResult result = trackOnSimbody(robot, withPayload(robot, {0.3, 2e-4, Vector2(0.01, -0.005)}));
    EXPECT_GT(largest(result.pose_peak_error), 1e-6);
    EXPECT_LT(largest(result.pose_peak_error), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(SimbodyControlRobots, SimbodyExample, ::testing::Values("4-rrr", "3-rrr"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace nocdyn::test
