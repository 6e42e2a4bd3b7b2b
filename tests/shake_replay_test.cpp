// The earthquake replay's steps (sim/shake_replay.hpp): every choice named once in its table,
// a replay too long to hold refused by the fit before any plant is built, and the pose
// controller on a plant it knows exactly (no payload, no sensor noise) following a fitted tone.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "nocdyn/error.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/shake_replay.hpp"

namespace nocdyn::test {
namespace {

template <class E>
void expectOneNameEach(std::size_t count) {
    std::set<std::string> names;
    std::set<int> values;
    for (const Choice<E>& choice : choices(E{})) {
        names.emplace(choice.name);
        values.insert(static_cast<int>(choice.value));
        ASSERT_TRUE(choiceNamed<E>(choice.name).has_value()) << choice.name;
        EXPECT_EQ(*choiceNamed<E>(choice.name), choice.value) << choice.name;
        EXPECT_EQ(nameOf(choice.value), choice.name);
    }
    EXPECT_EQ(names.size(), count);
    EXPECT_EQ(values.size(), count);
    EXPECT_FALSE(choiceNamed<E>("none of them").has_value());
}

TEST(ShakeReplayChoices, EveryValueHasOneNameAndEveryNameOneValue) {
    expectOneNameEach<PlantKind>(3);
    expectOneNameEach<ShakeController>(2);
    expectOneNameEach<DriveModel>(3);
    EXPECT_EQ(nameOf(PlantKind::nocdyn_rk4), "nocdyn-rk4");
    EXPECT_EQ(choiceList<ShakeController>(), "table or pose");
    EXPECT_EQ(choiceList<PlantKind>(), "simbody, nocdyn or nocdyn-rk4");
}

/// A tone of `amplitude` [m/s^2] at `frequency` [Hz], `seconds` long, sampled every dt.
GroundRecord tone(double amplitude, double frequency, double seconds, double dt) {
    GroundRecord record;
    record.dt = dt;
    for (int i = 0; i * dt <= seconds; ++i)
        record.ax.push_back(amplitude * std::sin(2.0 * std::numbers::pi * frequency * i * dt));
    return record;
}

TEST(ShakeReplay, AReplayTooLongToHoldIsRefusedByTheFitBeforeAnyPlantIsBuilt) {
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    ShakeReplayOptions options;
    options.rate = 1e6;                                        // 1e6 ticks per second of replay
    const GroundRecord record = tone(1.0, 1.0, 2000.0, 0.05);  // 2000 s of record
    bool built = false;
    const PlantFactory factory = [&](const RobotDescription& r) -> std::unique_ptr<RobotPlant> {
        built = true;
        return std::make_unique<RungeKuttaRobotPlant>(Model(r));
    };
    try {
        (void)runShakeReplay(robot, record, options, factory);
        FAIL() << "a replay of 2000 s at 1 MHz was played";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("too long to hold"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(built);
}

TEST(ShakeReplay, PoseControllerOnAPlantItKnowsFollowsAFittedToneWithinOnePercent) {
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    ShakeReplayOptions options;
    options.controller = ShakeController::pose;
    options.plant = PlantKind::nocdyn_rk4;
    options.payload_mass = 0.0;  // the plant is the controller's model
    options.noise_pose = 0.0;
    options.noise_rate = 0.0;
    options.rate = 5000.0;
    const GroundRecord record = tone(0.5, 2.0, 2.0, 0.01);
    const ShakeOutcome out = runShakeReplay(robot, record, options, [](const RobotDescription& r) {
        return std::make_unique<RungeKuttaRobotPlant>(Model(r));
    });
    EXPECT_EQ(out.driven, (std::array<bool, 3>{false, true, false}));
    ASSERT_EQ(out.pass_rms.size(), 1u);
    EXPECT_LT(out.pass_rms[0], 0.01);
    // the pass's error and the score's RMS error are one measure on the same samples
    EXPECT_NEAR(out.pass_rms[0], out.score[1].rms_error, 1e-9);
    EXPECT_LT(std::abs(out.score[1].peak_error), 0.01);
    EXPECT_EQ(out.sensing, "pose sensor: noise 0 (m, rad); rate sensor: noise 0 (m/s, rad/s)");
    EXPECT_GT(out.fit.time_scale, 0.0);
}

}  // namespace
}  // namespace nocdyn::test
