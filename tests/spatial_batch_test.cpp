// The spatial batch (nocdyn/spatial_batch.hpp) against the per-sample path on one Data carried
// from sample to sample: the same bits for any thread count and memory order on the shipped
// Delta, 6-UPS and 6-RUS; the first failing sample and the first beyond a limit in index order
// whatever the split, failed rows NaN; the shapes checked; nothing allocated per sample.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "allocation_counter.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_batch.hpp"
#include "nocdyn/spatial_limits.hpp"

namespace nocdyn::spatial {
namespace {

using RowMajor = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Strided = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;

/// A C-ordered array as the batch reads it from NumPy: a column-major map, row stride = columns.
Eigen::Map<const Eigen::ArrayXXd, 0, Strided> in(const RowMajor& a) {
    return {a.data(), a.rows(), a.cols(), Strided(1, a.cols())};
}
Eigen::Map<Eigen::ArrayXXd, 0, Strided> to(RowMajor& a) { return {a.data(), a.rows(), a.cols(), Strided(1, a.cols())}; }

Model shipped(const std::string& name) {
    return Model(io::loadSpatialRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml"));
}

/// N samples about home: two harmonics per coordinate (1-2 cm, 0.02-0.04 rad), exact rates.
struct Motion {
    RowMajor p, dp, ddp;
    Motion(const Model& model, Eigen::Index n)
        : p(n, model.task_dimension), dp(n, model.task_dimension), ddp(n, model.task_dimension) {
        for (Eigen::Index k = 0; k < n; ++k) {
            const double t = 1e-3 * static_cast<double>(k);
            for (int i = 0; i < model.task_dimension; ++i) {
                const double amplitude = i < 3 ? 0.01 + 0.003 * i : 0.02 + 0.005 * (i - 3);
                p(k, i) = model.home(i), dp(k, i) = 0.0, ddp(k, i) = 0.0;
                for (const double f : {1.0 + i, 2.0 + 2.0 * i}) {
                    const double w = 2.0 * M_PI * f, phase = 0.3 * i;
                    p(k, i) += amplitude * std::sin(w * t + phase) / f;
                    dp(k, i) += amplitude * w * std::cos(w * t + phase) / f;
                    ddp(k, i) -= amplitude * w * w * std::sin(w * t + phase) / f;
                }
            }
        }
    }
};

struct Outputs {
    RowMajor u, du, ddu, tau;
    Outputs(Eigen::Index n, int actuators) : u(n, actuators), du(n, actuators), ddu(n, actuators), tau(n, actuators) {}
};

/// The per-sample path over the motion on one Data (failed rows NaN), and the first failing
/// and first beyond-limits samples as a serial loop finds them.
struct Serial {
    Outputs out;
    Eigen::Index first_failure = BatchResult::npos, first_beyond_limits = BatchResult::npos;
    Status status, limits;
    Serial(const Model& model, const Motion& m) : out(m.p.rows(), model.actuators) {
        Data data(model);
        const int d = model.task_dimension;
        for (Eigen::Index k = 0; k < m.p.rows(); ++k) {
            const TaskVector p = m.p.row(k).transpose().matrix().head(d);
            const TaskVector dp = m.dp.row(k).transpose().matrix().head(d);
            const TaskVector ddp = m.ddp.row(k).transpose().matrix().head(d);
            const Status s = inverseDynamics(model, data, p, dp, ddp);
            if (!s) {
                for (RowMajor* a : {&out.u, &out.du, &out.ddu, &out.tau}) a->row(k).setConstant(NAN);
                if (first_failure == BatchResult::npos) first_failure = k, status = s;
                continue;
            }
            out.u.row(k) = data.u.transpose().array();
            out.du.row(k) = data.du.transpose().array();
            out.ddu.row(k) = data.ddu.transpose().array();
            out.tau.row(k) = data.tau.transpose().array();
            if (first_beyond_limits == BatchResult::npos) {
                if (const Status l = checkLimits(model, data); !l) first_beyond_limits = k, limits = l;
            }
        }
    }
};

BatchResult run(const Model& model, const Motion& m, Outputs& out, const BatchOptions& options) {
    return inverseDynamicsBatch(model, in(m.p), in(m.dp), in(m.ddp), to(out.u), to(out.du), to(out.ddu), to(out.tau),
                                options);
}

/// Row k of a and b hold the same bits (NaN included).
bool sameRow(const RowMajor& a, const RowMajor& b, Eigen::Index k) {
    return std::memcmp(a.row(k).data(), b.row(k).data(), sizeof(double) * static_cast<std::size_t>(a.cols())) == 0;
}

void expectSameRows(const Outputs& a, const Outputs& b, Eigen::Index k, const std::string& what) {
    EXPECT_TRUE(sameRow(a.u, b.u, k) && sameRow(a.du, b.du, k) && sameRow(a.ddu, b.ddu, k) && sameRow(a.tau, b.tau, k))
        << what << ", sample " << k << ": tau " << a.tau.row(k) << " against " << b.tau.row(k);
}

class SpatialBatch : public testing::TestWithParam<const char*> {};

TEST_P(SpatialBatch, EqualsThePerSamplePathBitForBitForOneTwoAndEveryHardwareThread) {
    const Model model = shipped(GetParam());
    const Motion m(model, 203);  // not a multiple of the chunks' grain of 8
    const Serial serial(model, m);
    ASSERT_EQ(serial.first_failure, BatchResult::npos) << "the motion stays in the workspace";
    ASSERT_GT(serial.out.tau.abs().maxCoeff(), 0.1) << "forces that are not all zero";
    for (const unsigned threads : {1u, 2u, 0u}) {
        Outputs out(m.p.rows(), model.actuators);
        BatchOptions options;
        options.threads = threads;
        const BatchResult r = run(model, m, out, options);
        EXPECT_TRUE(r.ok());
        EXPECT_EQ(r.first_failure, BatchResult::npos);
        for (Eigen::Index k = 0; k < m.p.rows(); ++k)
            expectSameRows(out, serial.out, k, std::string(GetParam()) + ", threads " + std::to_string(threads));
    }
    // Eigen's default (column-major) layout of the outputs: the same numbers
    Eigen::ArrayXXd u(m.p.rows(), model.actuators), du(u), ddu(u), tau(u);
    BatchOptions two;
    two.threads = 2;
    ASSERT_TRUE(inverseDynamicsBatch(model, in(m.p), in(m.dp), in(m.ddp), u, du, ddu, tau, two).ok());
    EXPECT_TRUE((tau == serial.out.tau).all() && (u == serial.out.u).all());
}

INSTANTIATE_TEST_SUITE_P(Shipped, SpatialBatch, testing::Values("stewart", "delta", "hexa-6rus"),
                         [](const testing::TestParamInfo<const char*>& info) {
                             std::string name = info.param;
                             for (char& c : name)
                                 if (c == '-') c = '_';
                             return name;
                         });

/// A pose 10 m away from home in x: beyond the reach of a 6-RUS's limbs (a 6-UPS's legs, of no
/// stroke limit in the kinematics, reach it).
void outOfReach(Motion& m, Eigen::Index k) { m.p(k, 0) += 10.0; }

TEST(SpatialBatchFailure, TheFirstFailingSampleInIndexOrderWhateverTheSplitItsRowNaN) {
    const Model model = shipped("hexa-6rus");  // cranks and rods of fixed lengths: a reach
    Motion m(model, 203);
    // threads = 2 splits [0, 104) and [104, 203): the second chunk meets its failure at once,
    // the first only at its end
    outOfReach(m, 100);
    outOfReach(m, 104);
    const Serial serial(model, m);
    ASSERT_EQ(serial.first_failure, 100);
    ASSERT_EQ(serial.status.code, StatusCode::unreachable);
    for (const bool stop : {false, true}) {
        for (const unsigned threads : {1u, 2u, 0u}) {
            const std::string what = "threads " + std::to_string(threads) + (stop ? ", stop" : "");
            Outputs out(m.p.rows(), model.actuators);
            BatchOptions options;
            options.threads = threads;
            options.stop_at_failure = stop;
            const BatchResult r = run(model, m, out, options);
            EXPECT_EQ(r.first_failure, 100) << what;
            EXPECT_EQ(r.status.code, serial.status.code) << what;
            EXPECT_EQ(r.status.limb, serial.status.limb) << what;
            EXPECT_EQ(r.status.value, serial.status.value) << what;
            EXPECT_EQ(r.failed, stop ? 1 : 2) << what;
            EXPECT_TRUE(out.u.row(100).isNaN().all() && out.tau.row(100).isNaN().all()) << what;
            EXPECT_TRUE(out.ddu.row(104).isNaN().all()) << what;
            for (Eigen::Index k = 0; k < 100; ++k) expectSameRows(out, serial.out, k, what);
            for (Eigen::Index k = 101; k < m.p.rows(); ++k) {
                if (stop) {
                    EXPECT_TRUE(out.tau.row(k).isNaN().all()) << what << ": sample " << k << " after the stop";
                } else {
                    expectSameRows(out, serial.out, k, what);
                }
            }
        }
    }
}

TEST(SpatialBatchFailure, TheFirstSampleBeyondALimitInIndexOrderAndOnlyBeforeAStop) {
    const Model model = shipped("stewart");
    Motion m(model, 203);
    // a leg's velocity limit is 0.5 m/s: 2 m/s along z passes it at samples 60 and 150
    m.dp(60, 2) += 2.0;
    m.dp(150, 2) += 2.0;
    const Serial serial(model, m);
    ASSERT_EQ(serial.first_beyond_limits, 60);
    ASSERT_EQ(serial.limits.code, StatusCode::velocity_exceeded);
    for (const unsigned threads : {1u, 2u}) {
        Outputs out(m.p.rows(), model.actuators);
        BatchOptions options;
        options.threads = threads;
        options.check_limits = true;
        BatchResult r = run(model, m, out, options);
        EXPECT_TRUE(r.ok());
        EXPECT_EQ(r.first_beyond_limits, 60);
        EXPECT_EQ(r.limits.code, serial.limits.code);
        EXPECT_EQ(r.limits.limb, serial.limits.limb);
        EXPECT_EQ(r.limits.value, serial.limits.value);
        expectSameRows(out, serial.out, 60, "written all the same");
        // a failure at 20 stops a serial loop before it sees 60: not reported with the stop
        Motion failing = m;
        failing.ddp(20, 0) = NAN;  // not_finite
        options.stop_at_failure = true;
        r = run(model, failing, out, options);
        EXPECT_EQ(r.first_failure, 20);
        EXPECT_EQ(r.first_beyond_limits, BatchResult::npos);
        options.stop_at_failure = false;
        r = run(model, failing, out, options);
        EXPECT_EQ(r.first_failure, 20);
        EXPECT_EQ(r.first_beyond_limits, 60);
    }
}

TEST(SpatialBatchShapes, ArraysOfTheWrongSizeAreRefusedBeforeAnySample) {
    const Model model = shipped("delta");
    const Motion m(model, 10);
    Outputs out(10, model.actuators);
    const RowMajor short_dp = m.dp.topRows(9);
    EXPECT_THROW((void)inverseDynamicsBatch(model, in(m.p), in(short_dp), in(m.ddp), to(out.u), to(out.du), to(out.ddu),
                                            to(out.tau)),
                 Error);
    RowMajor wide(10, model.actuators + 1);
    EXPECT_THROW(
        (void)inverseDynamicsBatch(model, in(m.p), in(m.dp), in(m.ddp), to(out.u), to(out.du), to(out.ddu), to(wide)),
        Error);
    const RowMajor six = RowMajor::Zero(10, 6);  // the Delta's pose has three coordinates
    EXPECT_THROW(
        (void)inverseDynamicsBatch(model, in(six), in(six), in(six), to(out.u), to(out.du), to(out.ddu), to(out.tau)),
        Error);
}

TEST(SpatialBatchAllocation, NothingIsAllocatedPerSample) {
    if (!test::kCountsMalloc) GTEST_SKIP() << "malloc is not counted in this build";
    const Model model = shipped("stewart");
    const auto allocations = [&](Eigen::Index n) {
        const Motion m(model, n);
        Outputs out(n, model.actuators);
        BatchOptions options;
        options.check_limits = true;
        const long before = test::allocationCount();
        const BatchResult r = run(model, m, out, options);
        const long count = test::allocationCount() - before;
        EXPECT_TRUE(r.ok());
        return count;
    };
    const long few = allocations(8), many = allocations(800);
    EXPECT_EQ(few, many) << "allocations that grow with the samples";
    EXPECT_GT(few, 0) << "the Data of the call is counted (the counter works)";
}

}  // namespace
}  // namespace nocdyn::spatial
