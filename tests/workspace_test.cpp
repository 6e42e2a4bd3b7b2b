// Workspace map (workspace.hpp): the area of the paper's 3-PRR against an independent Monte
// Carlo estimate from the paper's equations (support.hpp, PaperGeometry: Appendix A and the
// stroke, no model code); the type-1
// points of a 3-RRR lie where a limb is stretched or folded (|r_3 - r_1| = l_1 + l_2 or
// |l_1 - l_2|), its type-2 points where A is singular; the area converges with the grid.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "nocdyn/error.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/analysis/workspace.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

Model example(const std::string& robot) {
    return Model(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
}

TEST(Workspace, PaperRobotAreaAgreesWithAnIndependentMonteCarloEstimate) {
    for (const std::string robot : {"paper-3prr", "paper-3prr-general"}) {
        SCOPED_TRACE(robot);
        const Model model(io::exampleRobot(robot));
        const WorkspaceMap map = workspaceMap(model, {0.0, 301});
        const PaperGeometry paper;
        std::mt19937_64 rng(3);
        const double side = (map.n - 1) * map.step;
        std::uniform_real_distribution<double> ux(map.x0, map.x0 + side), uy(map.y0, map.y0 + side);
        const int samples = 200000;
        int inside = 0;
        for (int s = 0; s < samples; ++s) {
            const std::optional<Vector3> u = paper.actuators(Pose(0.0, ux(rng), uy(rng)));
            if (u && u->cwiseAbs().maxCoeff() <= 0.5 * paper.stroke) ++inside;
        }
        const double estimate = side * side * inside / samples;
        EXPECT_GT(map.area, 1e-4);  // 100 mm^2 at least: the strokes are +-12.45 mm
        EXPECT_NEAR(map.area, estimate, 0.015 * estimate);
    }
}

TEST(Workspace, AreaConvergesWithTheGrid) {
    const Model model = example("3-rrr");
    const double coarse = workspaceMap(model, {0.0, 101}).area;
    const double fine = workspaceMap(model, {0.0, 401}).area;
    EXPECT_NEAR(coarse, fine, 0.02 * fine);
}

TEST(Workspace, SingularityPointsLieOnTheSingularities) {
    const Model model = example("3-rrr");
    const double theta = 0.3;
    const WorkspaceMap map = workspaceMap(model, {theta, 201});
    ASSERT_GT(map.limb_singular.size(), 50u);
    ASSERT_GT(map.actuation_singular.size(), 20u);
    // type 1: some limb stretched or folded, |G(r_3) - r_1| = l_1 + l_2 or |l_1 - l_2|
    const double dtheta = theta - model.home(0);
    const Eigen::Rotation2Dd R(dtheta);
    for (const Vector2& c : map.limb_singular) {
        double best = INFINITY;
        for (int j = 0; j < model.limbs; ++j) {
            const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
            const Vector2 r3 = R * (limb.point_home[2] - model.home.tail<2>()) + c;
            const double d = (r3 - limb.point_home[0]).norm();
            best = std::min({best, std::abs(d - (limb.length1 + limb.length2)),
                             std::abs(d - std::abs(limb.length1 - limb.length2))});
        }
        EXPECT_LT(best, 1e-9) << c.transpose();
    }
    // type 2: A (du = A xi_P) loses rank
    Data data(model);
    for (const Vector2& c : map.actuation_singular) {
        ASSERT_TRUE(inverseDisplacement(model, data, Pose(theta, c.x(), c.y())).ok());
        (void)velocityFromPlatformTwist(model, data, Twist::Zero());
        const Eigen::JacobiSVD<Matrix3> svd(Matrix3(data.A.topRows<3>()));
        EXPECT_LT(svd.singularValues()(2), 1e-8 * svd.singularValues()(0)) << c.transpose();
    }
}

TEST(Workspace, RefusesBadOptionsAndAnOrientationWithNoWorkspace) {
    const Model model = example("3-rrr");
    EXPECT_THROW((void)workspaceMap(model, {0.0, 5}), Error);
    EXPECT_THROW((void)workspaceMap(model, {std::nan(""), 101}), Error);
    // the paper's sliders (+-12.45 mm) cannot turn the platform by 1.5 rad
    EXPECT_THROW((void)workspaceMap(Model{io::expand(io::RobotParameters{})}, {1.5, 101}), Error);
}

}  // namespace
}  // namespace nocdyn::test
