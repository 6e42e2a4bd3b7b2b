// The batch (inverseDynamicsBatch: the lean kernel on packets of four or eight samples, compiled per
// limb kind) against the per-sample lean path (inverseDynamicsFast), on every example robot,
// random robots of every limb type and mixed ones, in Eigen's column-major layout and in
// NumPy's C order; and a finite input whose results overflow, a failed sample.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "nocdyn/batch.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/examples.hpp"
#include "batch_packets.hpp"
#include "random_robots.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

/// Each test on packets of four and of eight samples.
class Batch : public BatchPacketsTest {};
NOCDYN_BATCH_PACKETS(Batch);

using RowMajor = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Strided = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;

/// Largest condition number (of A and of every J_j) of the poses compared.
constexpr double kCondition = 100.0;

/// Samples of a robot: random regular poses of its box, random twists and twist rates.
struct Samples {
    Eigen::ArrayXXd p, dp, ddp;
};

Samples samplesOf(const RobotCase& c, Eigen::Index n, bool expect_enough = true) {
    WorkspaceSampler sampler(*c.model, 11, c.angle, c.position);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Samples s{Eigen::ArrayXXd(n, 3), Eigen::ArrayXXd(n, 3), Eigen::ArrayXXd(n, 3)};
    Data data(*c.model);
    Eigen::Index k = 0;
    for (int tried = 0; k < n && tried < 100 * n; ++tried) {
        const Pose p = sampler.next();
        s.p.row(k) = p.transpose();
        s.dp.row(k) << 2.0 * unit(rng), 0.2 * unit(rng), 0.2 * unit(rng);
        s.ddp.row(k) << 50.0 * unit(rng), 5.0 * unit(rng), 5.0 * unit(rng);
        // well inside the workspace: rounding grows with the condition numbers (up to the
        // model's limit near a singularity), and this compares two roundings
        if (!inverseDynamics(*c.model, data, p, s.dp.row(k).transpose(), s.ddp.row(k).transpose()) ||
            data.cond_A > kCondition)
            continue;
        bool regular = true;
        for (int j = 0; j < c.model->limbs; ++j)
            regular = regular && data.limb[static_cast<std::size_t>(j)].cond <= kCondition;
        k += regular ? 1 : 0;
    }
    if (expect_enough) {
        EXPECT_GE(k, n / 4) << c.name << ": too few poses with condition numbers below " << kCondition;
    }
    s.p.conservativeResize(k, 3), s.dp.conservativeResize(k, 3), s.ddp.conservativeResize(k, 3);
    return s;
}

/// The example robots, random robots of every limb type, and mixed robots (every limb type
/// in one robot, redundant actuation, gravity and friction).
std::vector<RobotCase> robots() {
    std::vector<RobotCase> out = exampleAndRandomRobots(2, 2024);
    const std::vector<RandomRobotSpec> mixed{{{"RRR", "PRR", "RPR"}, 3, true, false},
                                             {{"RRP", "PRP", "RPP", "PPR"}, 5, false, true},
                                             {{"PRR", "RRR", "RPR", "RRR", "PRR"}, 6, true, true}};
    std::mt19937 rng(23);
    for (const RandomRobotSpec& spec : mixed) {
        for (int tried = 0; tried < 100; ++tried) {
            if (const auto robot = randomRobot(spec, rng)) {
                out.push_back({"mixed " + std::to_string(spec.limb_types.size()) + " limbs",
                               std::make_unique<Model>(*robot), 0.1, 0.01});
                break;
            }
        }
    }
    return out;
}

// Within 2e-13 of each output column's peak, sample by sample: the batch's packets and the
// per-sample path are the same arithmetic (one kernel), to rounding; a sample count that is
// not a multiple of four exercises the last, partial packet.
TEST_P(Batch, EqualsThePerSamplePathToTheColumnPeakInEveryLayout) {
    // the worst seen: 1.9e-14 of the peak (paper-3prr's tau_3), 1.6e-13 for a redundant robot
    // (the minimum-norm solve)
    constexpr double kTolerance = 2e-13;
    int columns = 0;
    for (const RobotCase& c : robots()) {
        const Model& model = *c.model;
        const Samples s = samplesOf(c, 203);
        const Eigen::Index n_samples = s.p.rows();
        if (n_samples < 50) continue;  // reported by samplesOf
        const int n = model.actuators;
        // the per-sample path, and each column's peak
        Eigen::ArrayXXd ref[4] = {Eigen::ArrayXXd(n_samples, n), Eigen::ArrayXXd(n_samples, n),
                                  Eigen::ArrayXXd(n_samples, n), Eigen::ArrayXXd(n_samples, n)};
        Data data(model);
        for (Eigen::Index k = 0; k < n_samples; ++k) {
            const Status status = inverseDynamicsFast(model, data, s.p.row(k).transpose(), s.dp.row(k).transpose(),
                                                      s.ddp.row(k).transpose());
            ASSERT_TRUE(status.ok()) << c.name << ", sample " << k << ": " << describe(status, model);
            ref[0].row(k) = data.u.head(n).transpose();
            ref[1].row(k) = data.du.head(n).transpose();
            ref[2].row(k) = data.ddu.head(n).transpose();
            ref[3].row(k) = data.tau.head(n).transpose();
        }
        // column-major (Eigen), row-major (NumPy's C order: rows of 3, transposed in packets) and
        // rows padded to one value more (a strided view: gathered and scattered lane by lane)
        RowMajor pr = s.p, dpr = s.dp, ddpr = s.ddp;
        RowMajor pw(n_samples, 4), dpw(n_samples, 4), ddpw(n_samples, 4);
        pw << s.p, Eigen::ArrayXd::Constant(n_samples, 1e300);
        dpw << s.dp, Eigen::ArrayXd::Constant(n_samples, 1e300);
        ddpw << s.ddp, Eigen::ArrayXd::Constant(n_samples, 1e300);
        const auto in = [n_samples](const RowMajor& a) {
            return Eigen::Map<const Eigen::ArrayXXd, 0, Strided>(a.data(), n_samples, 3, Strided(1, a.cols()));
        };
        for (const int layout : {0, 1, 2}) {
            Eigen::ArrayXXd col[4];
            RowMajor row[4];
            BatchResult result;
            if (layout > 0) {
                const Eigen::Index width = layout == 1 ? n : n + 1;
                for (RowMajor& r : row) r.setConstant(n_samples, width, -1.0);
                const auto out = [&](int i) {
                    return Eigen::Map<Eigen::ArrayXXd, 0, Strided>(row[i].data(), n_samples, n, Strided(1, width));
                };
                result =
                    layout == 1
                        ? inverseDynamicsBatch(model, in(pr), in(dpr), in(ddpr), out(0), out(1), out(2), out(3), 1)
                        : inverseDynamicsBatch(model, in(pw), in(dpw), in(ddpw), out(0), out(1), out(2), out(3), 1);
                for (int i = 0; i < 4; ++i) {
                    col[i] = row[i].leftCols(n);
                    // the padding is left as it was
                    if (layout == 2) {
                        EXPECT_TRUE((row[i].col(n) == -1.0).all()) << c.name;
                    }
                }
            } else {
                for (Eigen::ArrayXXd& r : col) r.setConstant(n_samples, n, -1.0);
                result = inverseDynamicsBatch(model, s.p, s.dp, s.ddp, col[0], col[1], col[2], col[3], 1);
            }
            EXPECT_TRUE(result.ok()) << c.name << ": " << describe(result.status, model);
            const char* names[4] = {"u", "du", "ddu", "tau"};
            for (int i = 0; i < 4; ++i) {
                for (int a = 0; a < n; ++a, ++columns) {
                    const double peak = ref[i].col(a).abs().maxCoeff();
                    const double worst = (col[i].col(a) - ref[i].col(a)).abs().maxCoeff();
                    EXPECT_LE(worst, kTolerance * peak)
                        << c.name
                        << (layout == 1   ? ", C order"
                            : layout == 2 ? ", strided"
                                          : ", column-major")
                        << ": " << names[i] << "_" << a + 1 << " differs by " << worst << " (peak " << peak << ")";
                }
            }
        }
    }
    EXPECT_GT(columns, 4 * 3 * 3 * 20);
}

/// The example robots and, for every limb type and every actuated joint, a random robot of
/// three such limbs (Model::uniform_limbs: the batch's terms compiled for that kind and
/// joint), with gravity and friction on every other one.
std::vector<RobotCase> uniformRobots() {
    std::vector<RobotCase> out;
    for (const std::string& name : io::exampleRobotNames()) {
        out.push_back({name, std::make_unique<Model>(io::exampleRobot(name)), 0.35, 0.06});
    }
    std::mt19937 rng(31);
    int index = 0;
    for (const std::string& type : limbTypes()) {
        for (int joint = 0; joint < 3; ++joint, ++index) {
            const bool loaded = index % 2 == 1;
            for (int tried = 0; tried < 100; ++tried) {
                if (const auto robot = randomRobot({{type, type, type}, 3, loaded, loaded, joint}, rng)) {
                    RobotCase c{"random " + type + " actuated at joint " + std::to_string(joint + 1),
                                std::make_unique<Model>(*robot), 0.1, 0.01};
                    // a robot well conditioned over enough of its box (some are not anywhere)
                    if (samplesOf(c, 200, false).p.rows() < 100) continue;
                    out.push_back(std::move(c));
                    EXPECT_EQ(out.back().model->uniform_limbs,
                              3 * static_cast<int>(out.back().model->limb[0].kind) + joint)
                        << out.back().name;
                    break;
                }
            }
        }
    }
    return out;
}

// Within 3e-14 of each output column's peak on every example robot and on uniform random robots
// of every limb type and actuated joint: the batch's terms compiled per kind and actuated joint
// and the per-sample path (the limbs in lanes) are the same formulas, summed in another order.
// The worst seen: 1.9e-14 of the peak (the paper robot's tau_3: 1.1e-12 N of 59 N), every other
// column within 1e-14.
TEST_P(Batch, UniformRobotsOfEveryKindAndJointAgreeWithThePerSamplePathTo3e14OfThePeak) {
    constexpr double kTolerance = 3e-14;
    int columns = 0;
    double worst_seen = 0.0;
    for (const RobotCase& c : uniformRobots()) {
        const Model& model = *c.model;
        const Samples s = samplesOf(c, 203);
        const Eigen::Index n_samples = s.p.rows();
        if (n_samples < 50) continue;  // reported by samplesOf
        const int n = model.actuators;
        Eigen::ArrayXXd ref[4], col[4];
        for (int i = 0; i < 4; ++i) ref[i].resize(n_samples, n), col[i].setConstant(n_samples, n, -1.0);
        Data data(model);
        for (Eigen::Index k = 0; k < n_samples; ++k) {
            const Status status = inverseDynamicsFast(model, data, s.p.row(k).transpose(), s.dp.row(k).transpose(),
                                                      s.ddp.row(k).transpose());
            ASSERT_TRUE(status.ok()) << c.name << ", sample " << k << ": " << describe(status, model);
            ref[0].row(k) = data.u.head(n).transpose();
            ref[1].row(k) = data.du.head(n).transpose();
            ref[2].row(k) = data.ddu.head(n).transpose();
            ref[3].row(k) = data.tau.head(n).transpose();
        }
        const BatchResult result = inverseDynamicsBatch(model, s.p, s.dp, s.ddp, col[0], col[1], col[2], col[3], 1);
        EXPECT_TRUE(result.ok()) << c.name << ": " << describe(result.status, model);
        const char* names[4] = {"u", "du", "ddu", "tau"};
        for (int i = 0; i < 4; ++i) {
            for (int a = 0; a < n; ++a, ++columns) {
                const double peak = ref[i].col(a).abs().maxCoeff();
                const double worst = (col[i].col(a) - ref[i].col(a)).abs().maxCoeff();
                worst_seen = std::max(worst_seen, worst / peak);
                EXPECT_LE(worst, kTolerance * peak) << c.name << ": " << names[i] << "_" << a + 1 << " differs by "
                                                    << worst << " (peak " << peak << ")";
            }
        }
    }
    EXPECT_GE(columns, 4 * 3 * 21);
    RecordProperty("worst_of_peak", std::to_string(worst_seen));
    std::printf("worst difference: %.3g of the column's peak\n", worst_seen);
}

// Finite input whose results overflow (a rate of 1e155 squared is beyond the doubles): a failed
// sample with a non-finite actuator effort, its row NaN, the others untouched; no output is
// ever inf or a NaN that the result does not count.
TEST_P(Batch, AFiniteInputWhoseResultsOverflowIsAFailedSample) {
    const Model model(io::exampleRobot("paper-3prr-general"));
    constexpr Eigen::Index kN = 9;
    Eigen::ArrayXXd p = model.home.transpose().replicate(kN, 1), dp = Eigen::ArrayXXd::Zero(kN, 3),
                    ddp = Eigen::ArrayXXd::Zero(kN, 3);
    dp(2, 1) = 1e155;
    ddp(6, 2) = 1e308;
    Eigen::ArrayXXd u(kN, 3), du(kN, 3), ddu(kN, 3), tau(kN, 3);
    const BatchResult result = inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1);
    EXPECT_EQ(result.failed, 2);
    EXPECT_EQ(result.first_failure, 2);
    EXPECT_EQ(result.status.code, StatusCode::effort_exceeded);
    EXPECT_FALSE(std::isfinite(result.status.value));
    EXPECT_NE(describe(result.status, model).find("not finite"), std::string::npos) << describe(result.status, model);
    for (Eigen::Index k = 0; k < kN; ++k) {
        const bool failed = k == 2 || k == 6;
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(std::isnan(tau(k, a)), failed) << "sample " << k;
            EXPECT_EQ(std::isnan(du(k, a)), failed) << "sample " << k;
            if (!failed) {
                EXPECT_TRUE(std::isfinite(tau(k, a)) && std::isfinite(ddu(k, a)) && std::isfinite(u(k, a)));
            }
        }
    }
}

}  // namespace
}  // namespace nocdyn::test
