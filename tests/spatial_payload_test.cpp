// A platform payload's 10 inertial parameters on a six-DOF table (nocdyn/sim/spatial_payload.hpp):
// the regressor against inverse dynamics with and without the payload, the identification of a
// random payload from an exact log, the printed standard deviations against the spread over
// noise seeds, and `nocdyn shake --identify-payload` on robots/stewart.yaml.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "allocation_counter.hpp"
#include "cli_support.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/spatial_payload.hpp"

namespace nocdyn::spatial {
namespace {

const std::string kSource = NOCDYN_SOURCE_DIR;

SpatialRobotDescription shipped(const std::string& name) {
    return io::loadSpatialRobotDescription(kSource + "/robots/" + name + ".yaml");
}

/// A payload of `mass` with its c.o.m. off-centre and a full, physical inertia tensor.
SpatialPayload randomPayload(std::mt19937& rng, double mass) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    SpatialPayload p;
    p.mass = mass;
    p.com = Eigen::Vector3d(0.15 * u(rng), 0.15 * u(rng), 0.1 + 0.05 * u(rng));
    const Eigen::Matrix3d Q = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    // principal moments from a box's: the triangle inequality holds
    const Eigen::Vector3d side(0.3 + 0.1 * u(rng), 0.2 + 0.1 * u(rng), 0.25 + 0.1 * u(rng));
    const Eigen::Vector3d s2 = side.cwiseAbs2();
    const Eigen::Vector3d principal = mass / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
    p.inertia = Q * principal.asDiagonal() * Q.transpose();
    return p;
}

TaskVector randomState(std::mt19937& rng, const TaskVector& centre, double size) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    TaskVector v = centre;
    for (int i = 0; i < v.size(); ++i) v(i) += size * (i < 3 ? 0.05 : 0.08) * u(rng);
    return v;
}

TEST(SpatialPayload, TheParametersRoundTripAndThePayloadAddsToThePlatform) {
    std::mt19937 rng(3);
    const SpatialPayload p = randomPayload(rng, 12.5);
    const SpatialPayload back = payloadOf(payloadParameters(p));
    EXPECT_NEAR(back.mass, p.mass, 1e-12);
    EXPECT_LT((back.com - p.com).norm(), 1e-13);
    EXPECT_LT((back.inertia - p.inertia).norm(), 1e-12);
    // the platform with the payload: the total first and second moments about the platform origin add
    const SpatialRobotDescription d = shipped("stewart");
    const SpatialRobotDescription w = withPayload(d, p);
    const auto about = [](const SpatialBodyDescription& b) {
        return Eigen::Matrix3d(
            b.inertia + b.mass * (b.com.squaredNorm() * Eigen::Matrix3d::Identity() - b.com * b.com.transpose()));
    };
    EXPECT_NEAR(w.platform.mass, d.platform.mass + p.mass, 1e-12);
    EXPECT_LT((w.platform.mass * w.platform.com - d.platform.mass * d.platform.com - p.mass * p.com).norm(), 1e-12);
    EXPECT_LT((about(w.platform) - about(d.platform) - payloadOf(payloadParameters(p)).inertia -
               p.mass * (p.com.squaredNorm() * Eigen::Matrix3d::Identity() - p.com * p.com.transpose()))
                  .norm(),
              1e-10);
    EXPECT_THROW((void)payloadOf(PayloadVector::Zero()), Error);
}

// tau(with payload) - tau(robot alone) = Y pi at random states, friction on, on both hexapods; Y
// allocates nothing.
TEST(SpatialPayload, TheRegressorIsTheDifferenceOfInverseDynamicsWithAndWithoutThePayload) {
    std::mt19937 rng(7);
    for (const char* robot : {"stewart", "hexa-6rus"}) {
        const SpatialRobotDescription d = shipped(robot);
        const Model alone(d);
        Data data(alone);
        PayloadRegressor Y(alone.actuators, kPayloadParameters);
        for (int trial = 0; trial < 5; ++trial) {
            const SpatialPayload p = randomPayload(rng, 5.0 + 40.0 * trial);
            const Model carrying(withPayload(d, p));
            Data with(carrying);
            const TaskVector q = randomState(rng, alone.home, 1.0);
            const TaskVector dq = randomState(rng, TaskVector::Zero(6), 4.0);
            const TaskVector ddq = randomState(rng, TaskVector::Zero(6), 40.0);
            ASSERT_TRUE(inverseDynamics(carrying, with, q, dq, ddq).ok()) << robot;
            const long before = test::allocationCount();
            ASSERT_TRUE(payloadRegressor(alone, data, q, dq, ddq, Y).ok()) << robot;
            if (test::kCountsMalloc) {
                EXPECT_EQ(test::allocationCount(), before) << robot;
            }
            const ActuatorVector difference = with.tau - data.tau;
            const ActuatorVector predicted = Y * payloadParameters(p);
            EXPECT_LT((difference - predicted).norm(), 1e-10 * with.tau.norm())
                << robot << " trial " << trial << ": " << difference.transpose() << " vs " << predicted.transpose();
            // and not trivially: the payload's share is a sizeable part of the forces
            EXPECT_GT(difference.norm(), 1e-3 * with.tau.norm()) << robot;
        }
    }
}

PayloadExcitationOptions quick(double duration) {
    PayloadExcitationOptions o;
    o.duration = duration;
    o.loop.simulator.atol = 1e-9;
    o.loop.simulator.rtol = 1e-7;
    o.loop.simulator.floor_step = 5e-5;
    return o;
}

// An exact log (no force noise) gives back a random payload: mass, c.o.m. off-centre, full tensor.
TEST(SpatialPayload, AnExactLogRecoversARandomPayload) {
    std::mt19937 rng(11);
    const SpatialRobotDescription d = shipped("stewart");
    const SpatialPayload truth = randomPayload(rng, 25.0);
    const Model alone(d), carrying(withPayload(d, truth));
    PayloadExcitationOptions o = quick(1.0);
    o.force_noise = 0.0;
    LimitUse use;
    const Trajectory excitation = payloadExcitation(carrying, o, &use);
    EXPECT_LE(use.ratio, 1.0);
    EXPECT_GT(use.ratio, 0.99);  // as large as the limits allow
    const SpatialPayloadEstimate e = identifySpatialPayload(alone, excitePayload(carrying, alone, excitation, o));
    EXPECT_EQ(e.samples, 1000);
    EXPECT_NEAR(e.payload.mass, truth.mass, 1e-8 * truth.mass);
    EXPECT_LT((e.payload.com - truth.com).norm(), 1e-8 * truth.com.norm()) << e.payload.com.transpose();
    EXPECT_LT((e.payload.inertia - truth.inertia).norm(), 1e-8 * truth.inertia.norm()) << e.payload.inertia;
    EXPECT_LT(e.residual_rms, 1e-6);
}

// The printed standard deviations are the spread's: 20 runs of one excitation, each its own
// force noise; the sample standard deviation of each parameter within a factor 1.5 of the mean
// printed one, and the estimates unbiased (their mean within 3 standard errors of the truth).
// The noise enters the logged forces only, so the motion is simulated once and measured with
// each seed (withForceNoise, as excitePayload measures it).
TEST(SpatialPayload, ThePrintedUncertaintyIsTheSpreadOverNoiseSeeds) {
    const SpatialRobotDescription d = shipped("stewart");
    SpatialPayload truth;
    truth.mass = 0.5;  // the shake command's default specimen, a point mass at the platform origin
    const Model alone(d), carrying(withPayload(d, truth));
    PayloadExcitationOptions o = quick(0.5);
    o.force_noise = 2.0;
    const Trajectory excitation = payloadExcitation(carrying, o);
    PayloadExcitationOptions exact = o;
    exact.force_noise = 0.0;
    const PayloadLog run_log = excitePayload(carrying, alone, excitation, exact);
    // one seed measured both ways: the same log
    o.seed = 100;
    const PayloadLog simulated = excitePayload(carrying, alone, excitation, o);
    const PayloadLog measured = withForceNoise(run_log, o.force_noise, o.seed);
    ASSERT_EQ(simulated.tau.size(), measured.tau.size());
    for (std::size_t k = 0; k < simulated.tau.size(); ++k) ASSERT_EQ(simulated.tau[k], measured.tau[k]) << k;
    constexpr int kRuns = 20;
    std::vector<PayloadVector> estimates;
    PayloadVector printed = PayloadVector::Zero();
    for (int run = 0; run < kRuns; ++run) {
        o.seed = 100 + static_cast<unsigned>(run);
        const SpatialPayloadEstimate e = identifySpatialPayload(alone, withForceNoise(run_log, o.force_noise, o.seed));
        estimates.push_back(e.parameters);
        printed += e.parameters_sd / kRuns;
        EXPECT_NEAR(e.residual_rms, o.force_noise, 0.05 * o.force_noise);
    }
    PayloadVector mean = PayloadVector::Zero(), spread = PayloadVector::Zero();
    for (const PayloadVector& x : estimates) mean += x / kRuns;
    for (const PayloadVector& x : estimates) spread += (x - mean).cwiseAbs2() / (kRuns - 1);
    spread = spread.cwiseSqrt();
    const PayloadVector pi = payloadParameters(truth);
    for (int i = 0; i < kPayloadParameters; ++i) {
        const char* name = payloadParameterNames()[static_cast<std::size_t>(i)];
        EXPECT_GT(spread(i), printed(i) / 1.5) << name;
        EXPECT_LT(spread(i), printed(i) * 1.5) << name;
        EXPECT_LT(std::abs(mean(i) - pi(i)), 3.0 * printed(i) / std::sqrt(kRuns)) << name;
    }
}

// The measurement's noise: none for 0, refused when negative or not a number.
TEST(SpatialPayload, ForceNoiseIsAddedOnlyToTheForcesAndRefusedWhenNegative) {
    PayloadLog log;
    log.t = {0.0, 0.001};
    log.p = log.dp = log.ddp = {TaskVector::Zero(6), TaskVector::Zero(6)};
    log.tau = {ActuatorVector::Constant(6, 1.0), ActuatorVector::Constant(6, 2.0)};
    const PayloadLog same = withForceNoise(log, 0.0, 3);
    EXPECT_EQ(same.tau[1], log.tau[1]);
    const PayloadLog noisy = withForceNoise(log, 0.5, 3);
    EXPECT_EQ(noisy.p[1], log.p[1]);
    EXPECT_NE(noisy.tau[0], log.tau[0]);
    EXPECT_EQ(withForceNoise(log, 0.5, 3).tau[1], noisy.tau[1]);  // the seed's draws
    EXPECT_NE(withForceNoise(log, 0.5, 4).tau[1], noisy.tau[1]);
    for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
        try {
            (void)withForceNoise(log, bad, 1);
            FAIL() << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("force noise"), std::string::npos) << e.what();
        }
    }
}

// A bad noise is refused before the excitation runs, not after the whole simulation.
TEST(SpatialPayload, ABadForceNoiseIsRefusedBeforeTheFirstTick) {
    const Model alone(shipped("stewart"));
    PayloadExcitationOptions o = quick(1.0);
    const Trajectory excitation = payloadExcitation(alone, o, nullptr);
    int ticks = 0;
    o.loop.progress = [&ticks](double) { ++ticks; };
    for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
        o.force_noise = bad;
        try {
            (void)excitePayload(alone, alone, excitation, o);
            FAIL() << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("force noise"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(ticks, 0);
}

TEST(SpatialPayload, AMotionWithoutRotationsDoesNotDetermineTheInertia) {
    const SpatialRobotDescription d = shipped("stewart");
    const Model alone(d);
    PayloadLog log;
    Data data(alone);
    for (int k = 0; k < 50; ++k) {
        TaskVector p = alone.home, dp = TaskVector::Zero(6), ddp = TaskVector::Zero(6);
        p(0) += 0.01 * std::sin(0.3 * k);
        ddp(2) = std::cos(0.2 * k);
        ASSERT_TRUE(inverseDynamics(alone, data, p, dp, ddp).ok());
        log.t.push_back(0.001 * k);
        log.p.push_back(p);
        log.dp.push_back(dp);
        log.ddp.push_back(ddp);
        log.tau.push_back(data.tau);
    }
    try {
        (void)identifySpatialPayload(alone, log);
        FAIL() << "a translation alone identified the inertia";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("does not determine"), std::string::npos) << e.what();
    }
}

// `nocdyn shake --identify-payload` on the hexapod: the specimen identified first, reported
// next to the truth in shake.json and the summary, and the replay as good as with the model known.
TEST(SpatialPayload, TheHexapodReplayIdentifiesTheSpecimenFirst) {
    const std::filesystem::path out = test::freshScratchDirectory("spatial_payload");
    const auto component = [](const char* c) { return kSource + "/data/records3/RSN6_IMPVALL.I_I-ELC" + c; };
    const std::string command = "shake --robot " + kSource + "/robots/stewart.yaml --record " +
                                component("180-hor1.AT2") + " --record " + component("270-hor2.AT2") + " --record " +
                                component("-UP.AT2") + " --window 1 --payload-mass 40 --identify-payload --out-dir ";
    const test::CliResult run = test::runCli(command + (out / "a").string());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("specimen identified first"), std::string::npos) << run.out;
    std::ifstream file(out / "a" / "shake.json");
    const nlohmann::json json = nlohmann::json::parse(file);
    const nlohmann::json& e = json.at("payload_estimate");
    EXPECT_EQ(e.at("true").at("mass").get<double>(), 40.0);
    const double m = e.at("mass").get<double>(), sd = e.at("mass_sd").get<double>();
    EXPECT_GT(sd, 0.0);
    EXPECT_LT(std::abs(m - 40.0), 5.0 * sd) << m << " +- " << sd;
    EXPECT_LT(sd, 1.0);
    for (int i = 0; i < 3; ++i)
        EXPECT_LT(std::abs(e.at("com")[i].get<double>()), 5.0 * e.at("com_sd")[i].get<double>());
    EXPECT_EQ(e.at("inertia").size(), 3u);
    EXPECT_EQ(e.at("parameters").size(), 10u);
    for (const char* axis : {"ax", "ay", "az"})
        EXPECT_LT(json["metrics"][axis]["rms_error_percent"].get<double>(), 5.0) << axis;
    // a suite identifies nothing yet: refused by name
    const test::CliResult suite =
        test::runCli("shake --robot " + kSource + "/robots/stewart.yaml --record " + kSource +
                     "/data/records3 --window 1 --identify-payload --out-dir " + (out / "b").string());
    EXPECT_NE(suite.exit_code, 0);
    EXPECT_NE(suite.err.find("identify-payload: a six-DOF table identifies the specimen before one record"),
              std::string::npos)
        << suite.err;
}

}  // namespace
}  // namespace nocdyn::spatial
