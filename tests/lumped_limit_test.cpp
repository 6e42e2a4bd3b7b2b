// Where the lumped model K v = w^2 M v does not hold (elastic links next to a limb singularity,
// its first frequency more than kLumpedMismatch from the elastodynamic one), the first natural
// frequency every bound uses is the elastodynamic one (firstFrequency): the pose's,
// the envelope's band (its amplification summed over the elastodynamic modes) and the
// workspace map's; far from singularities nothing changes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <limits>
#include <numbers>
#include <string>

#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/analysis/frequency_map.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/analysis/workspace.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "robot_files.hpp"

namespace nocdyn {
namespace {

/// The 3-RRR with elastic links, its drives' ranges removed (nothing but the reach bounds a pose).
Model limitless3RrrElastic() {
    RobotDescription robot = robotDescription("3-rrr-elastic");
    for (LimbDescription& limb : robot.limbs) limb.joints[0].limits = JointLimits{};
    return Model(robot);
}

/// 1e-9 m inside the reach boundary below home (bisection on y): a limb next to its singularity,
/// its condition number within max_condition.
Pose nextToTheReachBelowHome(const Model& model) {
    const StiffnessModel compliance(model);
    Data data(model);
    StiffnessData K;
    LumpedModes modes;
    double lo = 0.0, hi = 0.2;
    for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (stiffnessAndModes(model, compliance, data, Pose(0.0, 0.0, -mid), K, modes).ok() ? lo : hi) = mid;
    }
    return {0.0, 0.0, -(lo - 1e-9)};
}

struct Both {
    LumpedModes lumped;
    ElastodynamicModes elastic;
    double first = 0.0;  ///< firstFrequency
    std::string warning;
};

Both bothAt(const Model& model, const Pose& p) {
    const StiffnessModel compliance(model);
    Data data(model);
    StiffnessData K;
    Both out;
    EXPECT_TRUE(stiffnessAndModes(model, compliance, data, p, K, out.lumped).ok());
    EXPECT_TRUE(elastodynamicModes(model, compliance, data, out.elastic).ok());
    out.first = firstFrequency(model, compliance, data, out.lumped, &out.warning);
    return out;
}

TEST(LumpedLimit, NextToALimbSingularityTheFirstFrequencyIsTheElastodynamicOne) {
    const Model model = limitless3RrrElastic();
    const Both near = bothAt(model, nextToTheReachBelowHome(model));
    // the lumped f_1 collapses to a third of the elastodynamic one (9.805 against 29.905 Hz) ...
    EXPECT_NEAR(near.lumped.frequency(0) / near.elastic.frequency(0), 0.328, 1e-3);
    // ... and the one reported is within kLumpedMismatch of the elastodynamic model (it is it)
    EXPECT_LT(std::abs(near.first / near.elastic.frequency(0) - 1.0), kLumpedMismatch);
    EXPECT_EQ(near.first, near.elastic.frequency(0));
    EXPECT_NE(near.warning.find("the elastodynamic frequencies are used here"), std::string::npos) << near.warning;
    // far from singularities the lumped f_1 stands, bit for bit and without a word
    for (const Pose& p : {Pose(0.0, 0.0, 0.0), Pose(0.1, 0.02, -0.01), Pose(-0.05, -0.03, 0.04)}) {
        const Both far = bothAt(model, p);
        EXPECT_EQ(far.first, far.lumped.frequency(0)) << p.transpose();
        EXPECT_EQ(far.warning, "") << p.transpose();
        EXPECT_LT(std::abs(far.lumped.frequency(0) / far.elastic.frequency(0) - 1.0), 0.01) << p.transpose();
    }
}

TEST(LumpedLimit, TheElastodynamicModesSumToTheIdentityDrivenByTheRigidImage) {
    // platform_shape * participation = H(0) = I: at rest the platform follows the commanded motion
    const Model model = limitless3RrrElastic();
    for (const Pose& p : {Pose(0.0, 0.0, 0.0), nextToTheReachBelowHome(model)}) {
        const Both both = bothAt(model, p);
        ASSERT_EQ(both.elastic.participation.rows(), both.elastic.dofs);
        ASSERT_EQ(both.elastic.participation.cols(), 3);
        const Eigen::MatrixXd H0 = both.elastic.platform_shape * both.elastic.participation;
        EXPECT_LT((H0 - Eigen::MatrixXd::Identity(3, 3)).cwiseAbs().maxCoeff(), 1e-8) << H0;
    }
}

TEST(LumpedLimit, WhereTheLumpedModelHoldsBothModelsGiveTheSameAmplification) {
    // at home (the two first frequencies 0.01 % apart) the elastodynamic modes' H_aa is the
    // lumped model's: an independent check of the participation the elastodynamic band uses
    const Model model = limitless3RrrElastic();
    const EnvelopeResonance lumped = envelopeResonance(model);
    ASSERT_TRUE(lumped.known);
    EXPECT_EQ(lumped.model, FrequencyModel::lumped);
    EXPECT_EQ(lumped.warning, "");
    EXPECT_EQ(lumped.frequency, lumped.modes.frequency(0));
    const Both home = bothAt(model, model.home);
    EnvelopeResonance elastic = lumped;
    elastic.modal_frequency = home.elastic.frequency;
    elastic.modal_shape = home.elastic.platform_shape;
    elastic.modal_participation = home.elastic.participation;
    for (const EnvelopeAxis axis : kEnvelopeAxes) {
        // to 0.2 % up to 0.6 f_1; the links' own modes (above 300 Hz) add 1 % at 0.9 f_1
        for (const auto& [ratio, tolerance] : {std::pair{0.01, 2e-3}, {0.3, 2e-3}, {0.6, 2e-3}, {0.9, 1.5e-2}}) {
            const double f = ratio * lumped.frequency;
            EXPECT_NEAR(dynamicAmplification(elastic, axis, f) / dynamicAmplification(lumped, axis, f), 1.0, tolerance)
                << axisName(axis) << " at " << f << " Hz";
        }
        // and the band ends where the lumped model's does, to 1 %
        const double end = lumped.band_end[static_cast<std::size_t>(axis)];
        ASSERT_TRUE(std::isfinite(end));
        const double h = dynamicAmplification(elastic, axis, 0.99 * end),
                     H = dynamicAmplification(elastic, axis, 1.01 * end);
        EXPECT_TRUE(h < lumped.amplification && h > 1.0 / lumped.amplification) << axisName(axis) << " " << h;
        EXPECT_TRUE(H > lumped.amplification || H < 1.0 / lumped.amplification) << axisName(axis) << " " << H;
    }
}

TEST(LumpedLimit, AnEnvelopeWhoseHomeIsNextToALimbSingularityUsesTheElastodynamicModel) {
    // the same robot with its home moved next to the reach boundary (theta unchanged)
    const Model regular = limitless3RrrElastic();
    Model model = limitless3RrrElastic();
    model.home = nextToTheReachBelowHome(model);
    const Both near = bothAt(model, model.home);
    const EnvelopeResonance r = envelopeResonance(model);
    ASSERT_TRUE(r.known);
    EXPECT_EQ(r.model, FrequencyModel::elastodynamic);
    EXPECT_EQ(r.frequency, near.elastic.frequency(0));
    EXPECT_NE(r.warning.find("lumped model does not hold"), std::string::npos) << r.warning;
    EXPECT_EQ(r.modal_frequency.size(), near.elastic.dofs);
    // every band ends below f_1, and above where the lumped model (f_1 9.8 Hz) would end it
    EnvelopeResonance lumped = r;
    lumped.modal_frequency = r.modes.frequency;
    lumped.modal_shape = r.modes.shape;
    lumped.modal_participation = r.modes.shape.transpose() * r.modes.M;
    int below = 0;
    for (const EnvelopeAxis axis : kEnvelopeAxes) {
        const double end = r.band_end[static_cast<std::size_t>(axis)];
        ASSERT_TRUE(std::isfinite(end)) << axisName(axis);
        below += end < r.frequency ? 1 : 0;
        // the lumped modes would have ended it earlier: at this end their H_aa is out of the band
        const double hl = dynamicAmplification(lumped, axis, end);
        EXPECT_TRUE(hl > r.amplification || hl < 1.0 / r.amplification) << axisName(axis) << " " << hl;
        // the band's end is where |H_aa| leaves [1 / 1.1, 1.1]
        const double h = dynamicAmplification(r, axis, end * (1.0 + 1e-6));
        EXPECT_TRUE(h > r.amplification || h < 1.0 / r.amplification) << axisName(axis) << " " << h;
        EXPECT_LT(std::abs(dynamicAmplification(r, axis, end * (1.0 - 1e-6)) - 1.0), r.amplification - 1.0);
    }
    // an axis coupled to the first mode ends below it (y hardly moves in it: it ends above)
    EXPECT_GT(below, 0);
    // x and theta: 12.96 and 7.717 Hz (the lumped modes would end them at 1.9 and 2.1 Hz)
    EXPECT_NEAR(r.band_end[static_cast<std::size_t>(EnvelopeAxis::x)], 12.96, 0.01);
    EXPECT_NEAR(r.band_end[static_cast<std::size_t>(EnvelopeAxis::theta)], 7.717, 0.001);
    // the regular home is untouched
    EXPECT_EQ(envelopeResonance(regular).model, FrequencyModel::lumped);
}

TEST(LumpedLimit, TheMapChecksThePointsNextToALimbSingularityAndReplacesWhereTheLumpedModelFails) {
    const Model model = limitless3RrrElastic();
    const WorkspaceMap map = workspaceMap(model, WorkspaceOptions{model.home(0), 41, false});
    const FirstFrequencyMap f = firstFrequencyMap(model, map);
    const StiffnessModel compliance(model);
    Data data(model);
    StiffnessData K;
    LumpedModes modes;
    int replaced = 0, checked = 0;
    for (int i = 0; i < map.n; ++i) {
        for (int k = 0; k < map.n; ++k) {
            if (map.cell(i, k) != WorkspaceCell::feasible) continue;
            ASSERT_TRUE(stiffnessAndModes(model, compliance, data,
                                          Pose(map.theta, map.x0 + i * map.step, map.y0 + k * map.step), K, modes));
            // the exhaustive answer: firstFrequency at every point
            const double first = firstFrequency(model, compliance, data, modes);
            EXPECT_EQ(f.at(i, k, map.n), first) << i << ", " << k;
            replaced += first != modes.frequency(0) ? 1 : 0;
            checked += nearLimbSingularity(model, data) ? 1 : 0;
        }
    }
    EXPECT_EQ(f.elastodynamic_points, replaced);
    EXPECT_EQ(f.elastodynamic_checks, checked);
    EXPECT_LT(checked, f.points);
}

TEST(LumpedLimit, AMapNextToALimbSingularityGivesTheElastodynamicFirstFrequency) {
    // a 3 x 3 grid 2e-10 m apart, its lowest row 1e-9 m inside the reach below home: every
    // point within 1.5e-9 m of the limb singularity, where the lumped model does not hold
    const Model model = limitless3RrrElastic();
    const Pose near = nextToTheReachBelowHome(model);
    WorkspaceMap map;
    map.n = 3;
    map.step = 2e-10;
    map.x0 = -map.step;
    map.y0 = near(2);
    map.cells.assign(9, WorkspaceCell::feasible);
    const FirstFrequencyMap f = firstFrequencyMap(model, map);
    EXPECT_EQ(f.points, 9);
    EXPECT_EQ(f.elastodynamic_checks, 9);
    EXPECT_EQ(f.elastodynamic_points, 9);
    const Both at = bothAt(model, near);
    EXPECT_NEAR(f.at(1, 0, 3), at.elastic.frequency(0), 1e-12 * at.elastic.frequency(0));
    for (const double first : f.first) {
        // the lumped model gives 9.8 to 12 Hz here
        EXPECT_LT(std::abs(first / at.elastic.frequency(0) - 1.0), kLumpedMismatch) << first;
    }
    EXPECT_NE(f.warning.find("the elastodynamic first frequency is used at 9 of 9 points"), std::string::npos)
        << f.warning;
}

}  // namespace
}  // namespace nocdyn
