// A simulated 10 kHz control loop: 10^6 ticks, each evaluating the trajectory and running the
// per-sample inverse dynamics, timed tick by tick with steady_clock: the lean entry
// (prr3::inverseDynamicsFast) by default, the full path (prr3::inverseDynamics) with --full;
// with --robot FILE the general model of that robot file (inverseDynamicsFast, or
// inverseDynamics with --full).
// Reports the latency percentiles p50, p99, p99.9, p99.99 and max, and the clock's own cost.
//
//   nocdyn_realtime_loop [--ticks N] [--paced] [--full] [--robot FILE]
// --paced waits for each 100 us deadline (a real 10 kHz loop: 100 s for 10^6 ticks); the
// default runs the ticks back to back. Memory is locked and SCHED_FIFO requested when allowed.
#include <sched.h>
#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fixture.hpp"
#include "nocdyn/io/short_form.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/prr3/fast.hpp"

int main(int argc, char** argv) {
    long ticks = 1000000;
    bool paced = false;
    bool full = false;
    const char* robot = nullptr;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--ticks") == 0 && i + 1 < argc)
            ticks = std::atol(argv[++i]);
        else if (std::strcmp(argv[i], "--paced") == 0)
            paced = true;
        else if (std::strcmp(argv[i], "--full") == 0)
            full = true;
        else if (std::strcmp(argv[i], "--robot") == 0 && i + 1 < argc)
            robot = argv[++i];
    }
    if (ticks < 1 || ticks > 100000000) {
        std::fprintf(stderr, "nocdyn_realtime_loop: --ticks must be in [1, 1e8]\n");
        return 2;
    }
    // the general model of a robot file (loaded before the loop), or the paper's 3-PRR
    const nocdyn::Model general = robot ? nocdyn::Model(nocdyn::io::loadRobotDescription(robot))
                                        : nocdyn::Model(nocdyn::io::expand(nocdyn::io::RobotParameters{}));
    nocdyn::Data general_data(general);
    using Clock = std::chrono::steady_clock;
    const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
    sched_param param{};
    param.sched_priority = 80;
    const bool fifo = sched_setscheduler(0, SCHED_FIFO, &param) == 0;

    const nocdyn::prr3::Model model;
    nocdyn::prr3::Data data;
    nocdyn::prr3::FastData fast;
    const nocdyn::PoseTrajectory trajectory = nocdyn::bench::benchmarkTrajectory();
    std::vector<float> latency_ns(static_cast<std::size_t>(ticks));  // allocated before the loop
    std::vector<float> clock_ns(static_cast<std::size_t>(ticks));
    nocdyn::Pose p, dp, ddp;
    double checksum = 0.0;
    long failures = 0;
    const auto start = Clock::now();
    for (long k = 0; k < ticks; ++k) {
        if (paced) {
            const auto deadline = start + std::chrono::nanoseconds(100000 * k);
            while (Clock::now() < deadline) {
            }
        }
        const auto t0 = Clock::now();
        trajectory.evaluate(static_cast<double>(k) / nocdyn::bench::kRate, p, dp, ddp);
        bool ok = false;
        if (robot) {
            ok = (full ? nocdyn::inverseDynamics(general, general_data, p, dp, ddp)
                       : nocdyn::inverseDynamicsFast(general, general_data, p, dp, ddp))
                     .ok();
        } else {
            ok = (full ? nocdyn::prr3::inverseDynamics(model, data, p, dp, ddp)
                       : nocdyn::prr3::inverseDynamicsFast(model, fast, p, dp, ddp))
                     .ok();
        }
        const auto t1 = Clock::now();
        const auto t2 = Clock::now();  // the cost of one clock read, measured alongside
        failures += ok ? 0 : 1;
        checksum += robot ? general_data.tau(0) : (full ? data.tau(0) : fast.tau(0));
        latency_ns[static_cast<std::size_t>(k)] =
            static_cast<float>(std::chrono::duration<double, std::nano>(t1 - t0).count());
        clock_ns[static_cast<std::size_t>(k)] =
            static_cast<float>(std::chrono::duration<double, std::nano>(t2 - t1).count());
    }
    auto percentile = [](std::vector<float> v, double q) {
        const auto i = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
        std::nth_element(v.begin(), v.begin() + static_cast<long>(i), v.end());
        return v[i];
    };
    if (robot) std::printf("robot %s (general model, %d actuators)\n", robot, general.actuators);
    std::printf("ticks %ld (%s), mlockall %s, SCHED_FIFO %s, failures %ld, checksum %.6g\n", ticks,
                paced ? "paced at 10 kHz" : "back to back", locked ? "yes" : "no", fifo ? "yes" : "no", failures,
                checksum);
    std::printf("latency of trajectory evaluation + %s per tick [ns]:\n",
                full ? "inverseDynamics (full path)" : "inverseDynamicsFast (lean entry)");
    std::printf("  p50 %.0f  p99 %.0f  p99.9 %.0f  p99.99 %.0f  max %.0f\n", percentile(latency_ns, 0.5),
                percentile(latency_ns, 0.99), percentile(latency_ns, 0.999), percentile(latency_ns, 0.9999),
                *std::max_element(latency_ns.begin(), latency_ns.end()));
    std::printf("one steady_clock read [ns]: p50 %.0f  max %.0f\n", percentile(clock_ns, 0.5),
                *std::max_element(clock_ns.begin(), clock_ns.end()));
    std::printf("10 kHz budget 100000 ns: worst tick uses %.2f%% of it\n",
                100.0 * *std::max_element(latency_ns.begin(), latency_ns.end()) / 100000.0);
    return failures == 0 ? 0 : 1;
}
