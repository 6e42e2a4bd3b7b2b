// Spatial direct kinematics (nocdyn/spatial_direct_kinematics.hpp): round trips p -> u -> every
// mode found -> u on the shipped Delta, 6-UPS and 6-RUS and at random poses, each mode checked
// by the limbs' own distance constraints (no inverse kinematics); the Delta's two modes
// mirrored about the plane of the spheres' centres; the tracker along a 1 kHz trajectory
// without allocating; the command's JSON and its one-line refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "allocation_counter.hpp"
#include "cli_support.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_direct_kinematics.hpp"

namespace nocdyn::spatial {
namespace {

std::string shippedPath(const std::string& name) {
    return std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml";
}

Model shipped(const std::string& name) { return Model(io::loadSpatialRobotDescription(shippedPath(name))); }

/// u at p by inverse kinematics from home.
ActuatorVector actuatorsAt(const Model& model, const TaskVector& p) {
    Data data(model);
    const Status status = inverseKinematics(model, data, p);
    EXPECT_TRUE(status) << describe(status, model);
    return data.u;
}

/// A platform point (at home q0) carried to pose p.
Eigen::Vector3d carried(const Model& model, const TaskVector& p, const Eigen::Vector3d& q0) {
    const Eigen::Matrix3d R = model.task_dimension == 6 ? rotation(p(3), p(4), p(5)) : Eigen::Matrix3d::Identity();
    return p.head<3>() + R * model.home_rotation.transpose() * (q0 - model.home.head<3>());
}

/// The largest violation of the limbs' distance constraints at (p, u), from the file's geometry
/// alone: a U-P-S leg's length |S(p) - B| = |S_0 - B| + u; an R-U-S or R-U-U limb's rod
/// |P(p) - U(u)| = |P_0 - U_0|, U(u) the crank's or arm's end turned by u about the motor.
double constraintGap(const Model& model, const ActuatorVector& u, const TaskVector& p) {
    double gap = 0.0;
    for (int a = 0; a < model.actuators; ++a) {
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a)];
        const std::vector<Freedom>& f = model.limb[static_cast<std::size_t>(j)].freedoms;
        const Eigen::Vector3d top = f.back().point, top_now = carried(model, p, top);
        if (!f[static_cast<std::size_t>(k)].revolute) {  // U P S
            const Eigen::Vector3d base = f.front().point;
            gap = std::max(gap, std::abs((top_now - base).norm() - ((top - base).norm() + u(a))));
        } else {  // R U S, R U U
            const Eigen::Vector3d B = f[0].point, U0 = f[1].point;
            const Eigen::Vector3d U = B + Eigen::AngleAxisd(u(a), f[0].axis) * (U0 - B);
            gap = std::max(gap, std::abs((top_now - U).norm() - (top - U0).norm()));
        }
    }
    return gap;
}

/// A number as the command line reads it back exactly.
std::string number(double x) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

double poseGap(const Model& model, const TaskVector& a, const TaskVector& b) {
    double gap = (a.head<3>() - b.head<3>()).cwiseAbs().maxCoeff();
    if (model.task_dimension == 6) {
        gap = std::max(gap, (rotation(a(3), a(4), a(5)) - rotation(b(3), b(4), b(5))).cwiseAbs().maxCoeff());
    }
    return gap;
}

/// p -> u -> every mode -> u: each mode closes the limbs to 1e-10 (their distances, and its own
/// inverse-kinematics round trip), and p is among them, marked working. Returns the modes.
std::vector<AssemblyMode> expectRoundTrip(const Model& model, const TaskVector& p, const ManyStarts& bounds = {}) {
    const ActuatorVector u = actuatorsAt(model, p);
    const AssemblyModes modes = assemblyModes(model, u, bounds);
    EXPECT_FALSE(modes.modes.empty()) << model.name;
    int found = 0;
    for (const AssemblyMode& mode : modes.modes) {
        EXPECT_LE(mode.u_error, 1e-10) << model.name;
        EXPECT_LE(constraintGap(model, u, mode.p), 1e-10) << model.name << " mode " << mode.p.transpose();
        EXPECT_TRUE(std::isfinite(mode.condition));
        if (poseGap(model, mode.p, p) <= 1e-9) {
            ++found;
            EXPECT_TRUE(mode.working) << model.name;
        }
    }
    EXPECT_EQ(found, 1) << model.name << " at " << p.transpose();
    // modes are distinct
    for (std::size_t i = 0; i < modes.modes.size(); ++i) {
        for (std::size_t k = i + 1; k < modes.modes.size(); ++k) {
            EXPECT_GT(poseGap(model, modes.modes[i].p, modes.modes[k].p), 1e-7);
        }
    }
    return modes.modes;
}

TaskVector nearHome(const Model& model) {
    TaskVector p = model.home;
    p(0) += 0.02, p(1) -= 0.01, p(2) += 0.03;
    if (p.size() == 6) p(3) += 0.05, p(4) -= 0.04, p(5) += 0.1;
    return p;
}

TEST(SpatialDirectKinematics, RoundTripsOnTheShippedDeltaAnd6Rus) {
    for (const char* name : {"delta", "hexa-6rus"}) {
        const Model model = shipped(name);
        EXPECT_GE(expectRoundTrip(model, nearHome(model)).size(), 2u) << name;
        EXPECT_GE(expectRoundTrip(model, model.home).size(), 2u) << name;
    }
}

TEST(SpatialDirectKinematics, TheStewartPlatformsModesComeInPairsMirroredAboutItsBase) {
    // base joints at z = 0, platform joints in the platform frame's plane z = 0: reflecting the
    // whole robot in the base plane keeps every leg's length, so (x, y, -z, M R M), M =
    // diag(1, 1, -1), is a mode whenever (x, y, z, R) is
    const Model model = shipped("stewart");
    const std::vector<AssemblyMode> modes = expectRoundTrip(model, nearHome(model));
    ASSERT_GE(modes.size(), 4u);
    const Eigen::Matrix3d M = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
    for (const AssemblyMode& mode : modes) {
        const Eigen::Matrix3d R = M * rotation(mode.p(3), mode.p(4), mode.p(5)) * M;
        const Eigen::Vector3d c(mode.p(0), mode.p(1), -mode.p(2));
        const bool paired = std::any_of(modes.begin(), modes.end(), [&](const AssemblyMode& other) {
            return (other.p.head<3>() - c).cwiseAbs().maxCoeff() < 1e-9 &&
                   (rotation(other.p(3), other.p(4), other.p(5)) - R).cwiseAbs().maxCoeff() < 1e-9;
        });
        EXPECT_TRUE(paired) << mode.p.transpose();
        EXPECT_EQ(mode.home_branches, mode.p(2) > 0.0);  // the legs point up on their home branches
    }
}

TEST(SpatialDirectKinematics, RoundTripsAtRandomPoses) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> offset(-1.0, 1.0);
    const ManyStarts few{8, 11u};
    for (const char* name : {"delta", "stewart", "hexa-6rus"}) {
        const Model model = shipped(name);
        const double reach = std::string(name) == "hexa-6rus" ? 0.03 : 0.1;  // the RUS's workspace is small
        for (int trial = 0; trial < 4; ++trial) {
            TaskVector p = model.home;
            for (int i = 0; i < 3; ++i) p(i) += reach * offset(rng);
            for (int i = 3; i < p.size(); ++i) p(i) += 0.15 * offset(rng);
            expectRoundTrip(model, p, few);
        }
    }
}

TEST(SpatialDirectKinematics, TheDeltasTwoModesAreMirroredAboutThePlaneOfTheSpheresCentres) {
    const Model model = shipped("delta");
    std::string why;
    const std::optional<ThreeSpheres> spheres = threeSpheres(model, why);
    ASSERT_TRUE(spheres) << why;
    for (const ActuatorVector& u :
         {ActuatorVector(ActuatorVector::Constant(3, 0.3)), ActuatorVector(Eigen::Vector3d(0.1, -0.4, 0.6))}) {
        const AssemblyModes modes = assemblyModes(model, u);
        EXPECT_EQ(modes.method, DirectMethod::three_spheres);
        EXPECT_TRUE(modes.complete);
        ASSERT_EQ(modes.modes.size(), 2u);
        const Eigen::Vector3d p1 = modes.modes[0].p, p2 = modes.modes[1].p;
        // the working mode below the elbows, on the home branches; the other above, off them
        EXPECT_TRUE(modes.modes[0].working && modes.modes[0].home_branches);
        EXPECT_FALSE(modes.modes[1].working || modes.modes[1].home_branches);
        EXPECT_LT(p1.z(), p2.z());
        // the centres c_j: each elbow turned by u_j, shifted back by the platform joint's offset
        std::array<Eigen::Vector3d, 3> c, elbow;
        for (std::size_t j = 0; j < 3; ++j) {
            const std::vector<Freedom>& f = model.limb[j].freedoms;
            elbow[j] =
                f[0].point + Eigen::AngleAxisd(u(static_cast<Eigen::Index>(j)), f[0].axis) * (f[1].point - f[0].point);
            c[j] = elbow[j] - (f[3].point - model.home.head<3>());
            EXPECT_NEAR((p1 - c[j]).norm(), (f[3].point - f[1].point).norm(), 1e-12);
            EXPECT_NEAR((p2 - c[j]).norm(), (f[3].point - f[1].point).norm(), 1e-12);
        }
        const Eigen::Vector3d normal = (c[1] - c[0]).cross(c[2] - c[0]).normalized();
        // p2 - p1 along the normal, the midpoint in the plane
        EXPECT_NEAR(std::abs((p2 - p1).normalized().dot(normal)), 1.0, 1e-12);
        EXPECT_NEAR((0.5 * (p1 + p2) - c[0]).dot(normal), 0.0, 1e-12);
        // the elbows' own plane is that plane only when the motors turn alike (the platform's
        // joints are then shifted alike in height, by nothing): otherwise the mirror is not
        // about the elbows
        const Eigen::Vector3d elbow_normal = (elbow[1] - elbow[0]).cross(elbow[2] - elbow[0]).normalized();
        const double off_elbows = std::abs((0.5 * (p1 + p2) - elbow[0]).dot(elbow_normal));
        if (u(0) == u(1) && u(1) == u(2)) {
            EXPECT_LT(off_elbows, 1e-12);
            EXPECT_NEAR(p1.x(), 0.0, 1e-12);
            EXPECT_NEAR(p2.y(), 0.0, 1e-12);
        } else {
            EXPECT_GT(off_elbows, 1e-3);
        }
    }
    // shorter forearms: the spheres miss, no mode
    ThreeSpheres short_forearms = *spheres;
    for (double& L : short_forearms.forearm) L = 0.2;
    std::array<Eigen::Vector3d, 2> points;
    double gap = 0.0;
    EXPECT_EQ(threeSpheresPoints(short_forearms, model.home.head<3>(), ActuatorVector::Constant(3, -0.5), points, gap),
              0);
    EXPECT_GT(gap, 0.0);
    // the hexapods are not of that form, and say why
    EXPECT_FALSE(threeSpheres(shipped("stewart"), why));
    EXPECT_EQ(why, "motion full: the platform turns");
}

TEST(SpatialDirectKinematics, TheTrackerFollowsAOneKilohertzTrajectoryWithoutAllocating) {
    for (const char* name : {"stewart", "hexa-6rus", "delta"}) {
        const Model model = shipped(name);
        Data truth(model), data(model);
        const int d = model.task_dimension;
        TaskVector p = model.home, q = model.home;
        const double scale = std::string(name) == "hexa-6rus" ? 0.01 : 0.05;  // the RUS's workspace is small
        double worst = 0.0;
        for (int k = 0; k <= 500; ++k) {  // 0.5 s at 1 kHz: a circle at 2 Hz, a bob and a wobble
            const double t = 1e-3 * k, w = 4.0 * M_PI;
            p = model.home;
            p(0) += scale * std::sin(w * t);
            p(1) += scale * (1.0 - std::cos(w * t));
            p(2) += 0.5 * scale * std::sin(2.0 * w * t);
            if (d == 6)
                p(3) += 2.0 * scale * std::sin(w * t), p(4) += 1.6 * scale * std::sin(3.0 * w * t),
                    p(5) -= 4.0 * scale * t;
            const Status truth_status = inverseKinematics(model, truth, p);
            ASSERT_TRUE(truth_status) << name << " at sample " << k << ": " << describe(truth_status, model);
            const ActuatorVector u = truth.u;
            const long before = test::allocationCount();
            const Status status = directKinematics(model, data, u, q);
            const long allocations = test::allocationCount() - before;
            ASSERT_TRUE(status) << name << " at sample " << k << ": " << describe(status, model);
            EXPECT_EQ(allocations, 0);
            worst = std::max(worst, poseGap(model, p, q));
            EXPECT_LE((data.u - u).cwiseAbs().maxCoeff(), 1e-13 * (1.0 + u.cwiseAbs().maxCoeff()));
        }
        EXPECT_LT(worst, 1e-11) << name;
    }
}

TEST(SpatialDirectKinematics, TheTrackerSaysWhyItStops) {
    const Model model = shipped("stewart");
    Data data(model);
    TaskVector p = model.home;
    ActuatorVector u = ActuatorVector::Zero(6);
    u(2) = std::nan("");
    EXPECT_EQ(directKinematics(model, data, u, p).code, StatusCode::not_finite);
    EXPECT_EQ(directKinematics(model, data, ActuatorVector::Zero(5), p).code, StatusCode::not_finite);
    // five legs of 4.2 m and one of 0.2 m: no pose, p left as it was
    ActuatorVector far = ActuatorVector::Constant(6, 3.0);
    far(5) = -1.0;
    const Status status = directKinematics(model, data, far, p);
    EXPECT_FALSE(status);
    EXPECT_FALSE(describeDirect(status, model).empty());
    EXPECT_EQ(p, model.home);
    EXPECT_THROW((void)assemblyModes(model, ActuatorVector::Zero(3)), Error);
    // the wrap of the angles keeps the rotation
    const TaskVector raw = (TaskVector(6) << 0.1, 0.2, 0.3, 3.5, 2.0, -4.0).finished();
    const TaskVector canonical = canonicalPose(raw);
    EXPECT_LE(std::abs(canonical(4)), M_PI / 2);
    EXPECT_LT(poseGap(model, raw, canonical), 1e-14);
}

// ---- the command ----

TEST(SpatialDirectKinematics, TheCommandListsTheDeltasTwoModesAndAHexapodsWorkingMode) {
    const test::CliResult delta = test::runCli("forward-kinematics 0.1 0.1 0.1 --json --robot " + shippedPath("delta"));
    ASSERT_EQ(delta.exit_code, 0) << delta.err;
    const nlohmann::json j = nlohmann::json::parse(delta.out);
    EXPECT_EQ(j["method"], "three spheres");
    EXPECT_TRUE(j["complete"].get<bool>());
    ASSERT_EQ(j["solutions"].size(), 2u);
    const nlohmann::json& working = j["solutions"][0];
    EXPECT_TRUE(working["working"].get<bool>());
    EXPECT_FALSE(j["solutions"][1]["working"].get<bool>());
    EXPECT_EQ(working["pose"].size(), 3u);
    EXPECT_NEAR(working["pose"]["x"].get<double>(), 0.0, 1e-12);
    EXPECT_NEAR(working["pose"]["y"].get<double>(), 0.0, 1e-12);
    EXPECT_LT(working["pose"]["z"].get<double>(), -0.8);  // the arms 0.1 rad further down than at home
    EXPECT_LE(working["u_error"].get<double>(), 1e-12);
    // the pose the hexapod's u came from comes back, keyed x .. yaw and marked working
    const Model model = shipped("stewart");
    TaskVector p = model.home;
    p(0) += 0.01, p(2) -= 0.02, p(5) += 0.05;
    const ActuatorVector u = actuatorsAt(model, p);
    std::string args = "forward-kinematics";
    for (int a = 0; a < 6; ++a) args += " " + number(u(a));
    const test::CliResult stewart = test::runCli(args + " --json --robot " + shippedPath("stewart"));
    ASSERT_EQ(stewart.exit_code, 0) << stewart.err;
    const nlohmann::json s = nlohmann::json::parse(stewart.out);
    EXPECT_EQ(s["method"], "many starts");
    const nlohmann::json& first = s["solutions"][0];
    EXPECT_TRUE(first["working"].get<bool>());
    const char* keys[] = {"x", "y", "z", "roll", "pitch", "yaw"};
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(first["pose"][keys[i]].get<double>(), p(i), 1e-9) << keys[i];
    // as text
    const test::CliResult text = test::runCli("forward-kinematics 0 0 0 --robot " + shippedPath("delta"));
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("real solutions: 2 (three spheres: every assembly mode)\n1. x = "), std::string::npos)
        << text.out;
    EXPECT_NE(text.out.find("z = -800.000000000 mm  [working mode]"), std::string::npos) << text.out;
}

TEST(SpatialDirectKinematics, TheCommandRefusesBadValuesInOneLine) {
    // one error line (after the warning of a value beyond its joint's range, if any)
    const auto oneLine = [](const test::CliResult& r) {
        EXPECT_NE(r.exit_code, 0);
        EXPECT_EQ(r.out, "");
        const std::size_t error = r.err.find("nocdyn: error: ");
        ASSERT_NE(error, std::string::npos) << r.err;
        EXPECT_TRUE(error == 0 || r.err.compare(0, 17, "nocdyn: warning: ") == 0) << r.err;
        EXPECT_EQ(r.err.find('\n', error), r.err.size() - 1) << r.err;
    };
    const test::CliResult count = test::runCli("forward-kinematics 0.1 0.1 --robot " + shippedPath("delta"));
    oneLine(count);
    EXPECT_NE(count.err.find("has 3 actuators: give 3 values U1 .. U3, not 2"), std::string::npos) << count.err;
    oneLine(test::runCli("forward-kinematics 0.1 nan 0.1 --robot " + shippedPath("delta")));
    const test::CliResult reach = test::runCli("forward-kinematics 3 3 3 3 3 -1 --robot " + shippedPath("stewart"));
    oneLine(reach);
    EXPECT_NE(reach.err.find("stewart.yaml: no pose closes the loops with these actuator values (out of reach)"),
              std::string::npos)
        << reach.err;
}

}  // namespace
}  // namespace nocdyn::spatial
