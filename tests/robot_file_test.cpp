// Robot files of the general form: the shipped examples, the short form's expansion, the
// exact round trip of `convert`, and one-line errors naming the file, line, limb and field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

std::string robotPath(const std::string& name) { return std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name; }

const std::vector<std::string> kExamples{"paper-3prr.yaml", "paper-3prr-general.yaml", "3-rrr.yaml", "3-rpr.yaml",
                                         "4-rrr.yaml"};

TEST(RobotFile, GeneralFormOfThePaperRobotIsTheShortFormExactly) {
    const Model short_form(io::loadRobotDescription(robotPath("paper-3prr.yaml")));
    const Model general(io::loadRobotDescription(robotPath("paper-3prr-general.yaml")));
    Data a(short_form), b(general);
    for (int k = 0; k < 200; ++k) {
        Pose p, dp, ddp;
        paperTrajectory1().evaluate(k * 1e-3, p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(short_form, a, p, dp, ddp).ok());
        ASSERT_TRUE(inverseDynamics(general, b, p, dp, ddp).ok());
        for (int j = 0; j < 3; ++j) EXPECT_EQ(a.tau(j), b.tau(j)) << "t = " << k * 1e-3;
    }
}

TEST(RobotFile, ConvertRoundTripsEveryExampleExactly) {
    for (const std::string& name : kExamples) {
        const RobotDescription robot = io::loadRobotDescription(robotPath(name));
        const std::string once = io::descriptionToYaml(robot);
        const std::string twice = io::descriptionToYaml(io::parseRobotDescription(once, name));
        EXPECT_EQ(once, twice) << name;
    }
}

TEST(RobotFile, ExampleRobotsFollowThePaperTrajectoriesWithinTheirLimits) {
    for (const std::string& name : kExamples) {
        const Model model(io::loadRobotDescription(robotPath(name)));
        Data data(model);
        for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
            for (int k = 0; k < 2000; ++k) {
                Pose p, dp, ddp;
                trajectory.evaluate(k * 1e-4, p, dp, ddp);
                const Status status = inverseDynamics(model, data, p, dp, ddp);
                ASSERT_TRUE(status.ok()) << name << " " << trajectory.name << " t = " << k * 1e-4 << ": "
                                         << describe(status, model);
                const Status joints = checkJointLimits(model, data);
                ASSERT_TRUE(joints.ok()) << name << ": " << describe(joints, model);
                const Status effort = checkEffort(model, data);
                ASSERT_TRUE(effort.ok()) << name << ": " << describe(effort, model);
            }
        }
    }
}

TEST(RobotFile, CompiledInExamplesAreTheShippedFiles) {
    ASSERT_EQ(io::exampleRobotNames().size(), kExamples.size());
    for (const std::string& name : io::exampleRobotNames()) {
        std::ifstream in(robotPath(name + ".yaml"));
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        EXPECT_EQ(io::exampleRobotText(name), text) << name;
        EXPECT_EQ(io::exampleRobot(name).limbs.size(), name == "4-rrr" ? 4u : 3u);
    }
    EXPECT_THROW((void)io::exampleRobot("5-rrr"), Error);
}

/// The error message of a robot text, or "" when it loads.
std::string errorOf(const std::string& text) {
    try {
        const Model model(io::parseRobotDescription(text, "bad.yaml"));
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

/// A valid 3-RRR in the general form with one line replaced.
std::string rrr(const std::string& joint1 = "{type: R, point: [0.0, -0.2], actuated: true}",
                const std::string& body1 = "{mass: 0.3, inertia: 2.7e-4, com: [0.04, -0.166]}",
                const std::string& extra = "") {
    std::string limbs;
    const char* points[3][3] = {{"[0.0, -0.2]", "[0.08, -0.13175]", "[0.0, -0.0635]"},
                                {"[0.173205, 0.1]", "[0.0740988, 0.135157]", "[0.0549926, 0.03175]"},
                                {"[-0.173205, 0.1]", "[-0.154099, -0.00340703]", "[-0.0549926, 0.03175]"}};
    for (int j = 0; j < 3; ++j) {
        limbs += "  - joints:\n";
        limbs += "      - " +
                 (j == 0 ? joint1 : "{type: R, point: " + std::string(points[j][0]) + ", actuated: true}") + "\n";
        limbs += "      - {type: R, point: " + std::string(points[j][1]) + "}\n";
        limbs += "      - {type: R, point: " + std::string(points[j][2]) + "}\n";
        limbs += "    bodies:\n      - " +
                 (j == 0 ? body1 : std::string("{mass: 0.3, inertia: 2.7e-4, com: [0.1, 0.1]}")) +
                 "\n      - {mass: 0.25, inertia: 2.3e-4, com: [0.05, 0.05]}\n";
    }
    return "name: test\n" + extra + "platform: {mass: 1.75, inertia: 6.2e-3}\nlimbs:\n" + limbs;
}

TEST(RobotFile, AValidGeneralFileLoads) { EXPECT_EQ(errorOf(rrr()), ""); }

TEST(RobotFile, BadInputNamesFileLineLimbJointAndField) {
    struct Case {
        std::string text;
        std::vector<std::string> expected;
    };
    const std::vector<Case> cases{
        {rrr("{type: X, point: [0.0, -0.2], actuated: true}"),
         {"bad.yaml:5:", "limbs[0].joints[0].type", "unknown joint type"}},
        {rrr("{type: P, direction: [0.0, 0.0], actuated: true}"),
         {"bad.yaml:5:", "limbs[0]", "joints[0].direction", "non-zero"}},
        {rrr("{type: R, point: [0.0, -0.2], actuated: true}", "{mass: -1.0, inertia: 2.7e-4, com: [0.04, -0.166]}"),
         {"bad.yaml:9:", "limbs[0]", "bodies[0].mass"}},
        {rrr("{type: R, point: [0.0, -0.2], actuated: true, colour: red}"), {"bad.yaml:5:", "colour", "unknown key"}},
        {rrr("{type: R, point: [0.0, -0.2]}"), {"bad.yaml", "at least 3 actuated joints", "got 2"}},
        {rrr("{type: R, point: [0.0, .nan], actuated: true}"), {"bad.yaml:5:", "joints[0].point", "finite"}},
        {rrr("{type: R, point: [0.0, -0.2], actuated: true, limits: {lower: 0.1, upper: 0.5}}"),
         {"bad.yaml:5:", "joints[0].limits", "home value 0"}},
        {rrr("{type: R, point: [0.0, -0.2], actuated: true}", "{mass: 0.3, inertia: 2.7e-4, com: [0.04, -0.166]}",
             "home: [0.0, 0.0]\n"),
         {"bad.yaml:2:", "home", "[x, y, theta]"}},
        {"platform: {mass: 1.0, inertia: 1.0}\nlimbs:\n  - joints: []\n    bodies: []\n  - joints: []\n    bodies: "
         "[]\n",
         {"bad.yaml:3:", "limbs[0].joints", "exactly 3 joints"}},
        // found by fuzzing: a limb without `joints` (an invalid yaml-cpp node, not an exception of ours)
        {"platform: {mass: 1.0, inertia: 1.0}\nlimbs:\n  - name: a\n  - name: b\n",
         {"bad.yaml:3:", "limbs[0].joints", "exactly 3 joints"}},
        {"platform: {mass: 1.0, inertia: 1.0}\nname: x\nlimbs: 3\n", {"bad.yaml", "limbs", "list of limbs"}},
    };
    for (const Case& c : cases) {
        const std::string message = errorOf(c.text);
        ASSERT_FALSE(message.empty()) << c.text;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        for (const std::string& part : c.expected)
            EXPECT_NE(message.find(part), std::string::npos) << message << "\n  lacks: " << part;
    }
}

TEST(RobotFile, ALimbAtTheEdgeOfItsReachAtHomeIsRejected) {
    // limb 1 stretched straight: base, elbow and platform pivot on one line
    std::string text = rrr();
    text.replace(text.find("[0.08, -0.13175]"), 16, "[0.0, -0.13175]");
    const std::string message = errorOf(text);
    EXPECT_NE(message.find("limbs[0]"), std::string::npos) << message;
    EXPECT_NE(message.find("singular at home"), std::string::npos) << message;
}

}  // namespace
}  // namespace nocdyn::test
