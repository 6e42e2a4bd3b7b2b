// Batch inverse dynamics of the general model (batch.hpp): the lean kernel over a range of
// samples, four or eight at a time in the lanes of a packet (vectorised across samples, for any
// robot), the full path for the rare samples it rejects, and a split over threads (parallel.hpp).
#include "nocdyn/batch.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "batch_chunk.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/parallel.hpp"

// A packet lives in registers inside chunk4 (everything it calls is inlined): the note that a
// 32-byte vector's ABI depends on AVX does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace nocdyn {

namespace {

// On x86-64 with GCC, four-sample packets are built as an AVX2+FMA clone (one register per
// packet) beside the baseline one (two). Eight-sample packets (one AVX-512 register) are
// batch_avx512.cpp's, built for x86-64-v4 when CMake defines NOCDYN_EIGHT_LANES, and taken
// where the CPU has it.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(NOCDYN_NO_TARGET_CLONES)
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
BatchResult
chunk4(const Model& model, const Arrays& a, Eigen::Index begin, Eigen::Index end) {
    return chunkOf<fastmath::Pack>(model, a, begin, end);
}

/// Whether this CPU runs the eight-lane packets.
bool cpuHasEightLanes() {
#if defined(NOCDYN_EIGHT_LANES)
    // x86-64-v4's AVX-512 subsets and the AVX2 level below them (every CPU with these has the
    // rest of x86-64-v3: MOVBE, F16C, LZCNT)
    static const bool yes = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                            __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
                            __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx2") &&
                            __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
    return yes;
#else
    return false;
#endif
}

std::atomic<int> packet_width{0};  // 0 until chosen: 4 or 8

int chooseWidth(BatchPackets packets) { return packets == BatchPackets::four ? 4 : cpuHasEightLanes() ? 8 : 4; }

BatchResult chunk(const Model& model, const Arrays& a, Eigen::Index begin, Eigen::Index end) {
#if defined(NOCDYN_EIGHT_LANES)
    if (batchPacketWidth() == 8) return detail::chunk8(model, a, begin, end);
#endif
    return chunk4(model, a, begin, end);
}

void requireShape(const char* name, Eigen::Index rows, Eigen::Index cols, Eigen::Index n, Eigen::Index m) {
    if (rows != n || cols != m) {
        throw Error(std::string("inverseDynamicsBatch: ") + name + " is " + std::to_string(rows) + " x " +
                    std::to_string(cols) + ", expected " + std::to_string(n) + " x " + std::to_string(m));
    }
}

}  // namespace

int setBatchPackets(BatchPackets packets) {
    const int width = chooseWidth(packets);
    packet_width.store(width, std::memory_order_relaxed);
    return width;
}

int batchPacketWidth() {
    int width = packet_width.load(std::memory_order_relaxed);
    if (width == 0) {
        width = chooseWidth(BatchPackets::automatic);
        packet_width.store(width, std::memory_order_relaxed);
    }
    return width;
}

Status checkActuatorLimits(const Model& model, const ActuatorVector& u, const ActuatorVector& du,
                           const ActuatorVector& tau) {
    return LimitTable(model).check(model, u, du, tau);
}

bool limitsOnActuatedJointsOnly(const Model& model) {
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        for (std::size_t k = 0; k < 3; ++k) {
            const JointLimits& lim = limb.limits[k];
            if (limb.actuator[k] < 0 && !(lim.lower == -INFINITY && lim.upper == INFINITY && lim.velocity == INFINITY))
                return false;
        }
    }
    return true;
}

Status checkSampleLimits(const Model& model, const Data& data) {
    if (const Status s = checkJointLimits(model, data); !s) return s;
    return checkEffort(model, data);
}

Eigen::Index firstSampleBeyondLimits(const Model& model, const BatchInput& p, const BatchInput& dp,
                                     const BatchInput& ddp, PoseColumns order, Status& status) {
    Data data(model);
    for (Eigen::Index k = 0; k < p.rows(); ++k) {
        if (!inverseDynamics(model, data, poseRow(p, k, order), poseRow(dp, k, order), poseRow(ddp, k, order)))
            continue;
        if (status = checkSampleLimits(model, data); !status) return k;
    }
    status = Status{};
    return BatchResult::npos;
}

std::string describeFailure(const Model& model, const BatchResult& result, Eigen::Index samples) {
    if (result.ok()) return {};
    return "sample " + std::to_string(result.first_failure + 1) + ": " + describe(result.status, model) + " (" +
           std::to_string(result.failed) + " of " + std::to_string(samples) + " samples failed)";
}

std::string describeLimits(const Model& model, const BatchResult& result) {
    if (result.first_beyond_limits == BatchResult::npos) return {};
    return "sample " + std::to_string(result.first_beyond_limits + 1) + ": " + describe(result.limits, model);
}

BatchResult inverseDynamicsBatch(const Model& model, const ConstRef& p, const ConstRef& dp, const ConstRef& ddp, Ref u,
                                 Ref du, Ref ddu, Ref tau, unsigned threads, PoseColumns order, ActuatorLimits limits) {
    const Eigen::Index n = p.rows();
    requireShape("p", p.rows(), p.cols(), n, 3);
    requireShape("dp", dp.rows(), dp.cols(), n, 3);
    requireShape("ddp", ddp.rows(), ddp.cols(), n, 3);
    requireShape("u", u.rows(), u.cols(), n, model.actuators);
    requireShape("du", du.rows(), du.cols(), n, model.actuators);
    requireShape("ddu", ddu.rows(), ddu.cols(), n, model.actuators);
    requireShape("tau", tau.rows(), tau.cols(), n, model.actuators);
    if (u.outerStride() != du.outerStride() || u.outerStride() != ddu.outerStride() ||
        u.outerStride() != tau.outerStride()) {
        throw Error("inverseDynamicsBatch: u, du, ddu and tau must have the same layout");
    }
    // a limited passive joint: the kernel checks nothing, the full path every sample after it
    const bool passive = limits == ActuatorLimits::every_joint && !limitsOnActuatedJointsOnly(model);
    const ActuatorLimits kernel =
        limits == ActuatorLimits::ignore || passive ? ActuatorLimits::ignore : ActuatorLimits::check;
    const Arrays a{p, dp, ddp, u, du, ddu, tau, order, kernel};
    // at most one thread per hardware thread and per chunk of 8 samples (more only adds
    // start-up), chunks of multiples of 8 samples so that no two threads share a cache line
    const ParallelSplit split = splitRange(n, threads, 8);
    BatchResult result;
    if (split.workers == 1) {
        result = chunk(model, a, 0, n);
    } else {
        std::vector<BatchResult> results(split.workers);
        parallelFor("inverseDynamicsBatch", split, [&](unsigned w, Eigen::Index begin, Eigen::Index end) {
            results[w] = chunk(model, a, begin, end);
        });
        result = combineChunks(results);
    }
    if (passive) result.first_beyond_limits = firstSampleBeyondLimits(model, p, dp, ddp, order, result.limits);
    return result;
}

BatchResult combineChunks(const std::vector<BatchResult>& chunks) {
    BatchResult total;
    for (const BatchResult& r : chunks) {  // chunks are in sample order: the first failure wins
        if (r.failed > 0 && total.failed == 0) {
            total.first_failure = r.first_failure;
            total.status = r.status;
        }
        total.failed += r.failed;
        if (r.first_beyond_limits != BatchResult::npos && total.first_beyond_limits == BatchResult::npos) {
            total.first_beyond_limits = r.first_beyond_limits;
            total.limits = r.limits;
        }
    }
    return total;
}

}  // namespace nocdyn
