// The real assembly modes of 6-UPS robots by PHCpack (nocdyn/analysis/assembly_modes.hpp): the
// pose the leg lengths came from is among them; every mode gives back u by the inverse
// kinematics; on random hexapods, every pose a many-start Newton finds is among them and phc
// finds the 40 complex solutions of a general platform; all 40 real modes of Dietmaier's platform
// are found; robots of other kinds, a missing phc, a phc that fails, writes nonsense or runs too
// long give one clear error and leave no folder.
// Without phc (Debian package phcpack) the tests that need it skip, and fail under CI=true.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "nocdyn/analysis/assembly_modes.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "skip.hpp"

namespace nocdyn::spatial {
namespace {

namespace fs = std::filesystem;

constexpr double kRoundTrip = 1e-9;   ///< u(mode) - u, m
constexpr double kSamePose = 1e-7;    ///< two poses within this (m, rotation entries) are one
constexpr unsigned kSeed = 20261129;  ///< phc's random numbers, fixed so that a run is repeatable

#define NOCDYN_REQUIRE_PHC()                                                                               \
    do {                                                                                                   \
        if (findPhc().empty()) NOCDYN_SKIP_OR_FAIL_IN_CI("phc is not installed (Debian package phcpack)"); \
    } while (false)

Model shipped(const std::string& name) {
    return Model(io::loadSpatialRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml"));
}

HomotopyOptions seeded() {
    HomotopyOptions options;
    options.seed = kSeed;
    return options;
}

ActuatorVector actuatorValues(const Model& model, const TaskVector& p) {
    Data data(model);
    const Status status = inverseKinematics(model, data, p);
    EXPECT_TRUE(status.ok()) << describe(status, model);
    return data.u;
}

bool samePose(const TaskVector& x, const TaskVector& y) {
    const Eigen::Matrix3d Rx = rotation(x(3), x(4), x(5)), Ry = rotation(y(3), y(4), y(5));
    return (x.head<3>() - y.head<3>()).cwiseAbs().maxCoeff() <= kSamePose &&
           (Rx - Ry).cwiseAbs().maxCoeff() <= kSamePose;
}

bool among(const TaskVector& p, const std::vector<HomotopyMode>& modes) {
    return std::any_of(modes.begin(), modes.end(), [&](const HomotopyMode& m) { return samePose(p, m.pose); });
}

/// The leg geometry, read from the model's freedoms independently of the solver: base point a,
/// platform point b (platform frame), leg length L at u.
struct Geometry {
    std::vector<Eigen::Vector3d> a, b;
    std::vector<double> L;
    Geometry(const Model& model, const ActuatorVector& u) {
        for (int k = 0; k < model.actuators; ++k) {
            const auto [j, f] = model.actuator[static_cast<std::size_t>(k)];
            const Limb& limb = model.limb[static_cast<std::size_t>(j)];
            a.push_back(limb.freedoms[0].point);
            b.push_back(model.home_rotation.transpose() * (limb.freedoms[3].point - model.home.head<3>()));
            L.push_back((limb.freedoms[3].point - limb.freedoms[0].point +
                         u(k) * limb.freedoms[static_cast<std::size_t>(f)].axis)
                            .norm());
        }
    }
    Eigen::Matrix<double, 6, 1> residual(const TaskVector& p) const {
        const Eigen::Matrix3d R = rotation(p(3), p(4), p(5));
        Eigen::Matrix<double, 6, 1> r;
        for (int i = 0; i < 6; ++i) {
            const auto k = static_cast<std::size_t>(i);
            r(i) = (p.head<3>() + R * b[k] - a[k]).norm() - L[k];
        }
        return r;
    }
};

/// Newton on the leg lengths over [x, y, z, roll, pitch, yaw] (Jacobian by central differences)
/// from many random poses (seeded): the distinct converged poses.
std::vector<TaskVector> manyStartNewton(const Geometry& geometry, unsigned seed, int starts) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> position(-1.5, 1.5), angle(-M_PI, M_PI), pitch(-1.4, 1.4);
    std::vector<TaskVector> found;
    for (int s = 0; s < starts; ++s) {
        TaskVector p(6);
        p << position(rng), position(rng), position(rng), angle(rng), pitch(rng), angle(rng);
        bool converged = false;
        for (int iteration = 0; iteration < 60 && !converged; ++iteration) {
            const Eigen::Matrix<double, 6, 1> r = geometry.residual(p);
            Eigen::Matrix<double, 6, 6> J;
            for (int c = 0; c < 6; ++c) {
                TaskVector h = TaskVector::Zero(6);
                h(c) = 1e-7;
                J.col(c) = (geometry.residual(p + h) - geometry.residual(p - h)) / 2e-7;
            }
            const Eigen::Matrix<double, 6, 1> step = Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>>(J).solve(-r);
            if (!step.allFinite() || step.norm() > 10.0) break;
            p += step;
            converged = geometry.residual(p).cwiseAbs().maxCoeff() < 1e-12 && step.norm() < 1e-9;
        }
        if (!converged || !(std::abs(std::cos(p(4))) > 1e-3)) continue;
        for (int k = 3; k < 6; ++k) p(k) = std::atan2(std::sin(p(k)), std::cos(p(k)));
        const bool known = std::any_of(found.begin(), found.end(), [&](const TaskVector& q) { return samePose(p, q); });
        if (!known) found.push_back(p);
    }
    return found;
}

/// Leg i + 1 of a 6-UPS hexapod from its base point b to its platform point `top`: a U (a1
/// horizontal across the leg, a2 across both), the actuated P along the leg, an S; two bodies of
/// `mass` each, their c.o.m. at 0.3 and 0.7 of the leg.
SpatialLimbDescription upsLeg(int i, const Eigen::Vector3d& b, const Eigen::Vector3d& top, double mass) {
    const Eigen::Vector3d e = (top - b).normalized();
    SpatialJointDescription u, p, s;
    u.type = SpatialJointType::universal;
    u.point = b;
    u.axis1 = e.cross(Eigen::Vector3d::UnitZ()).normalized();
    u.axis2 = e.cross(u.axis1).normalized();
    p.type = SpatialJointType::prismatic;
    p.direction = e;
    p.actuated = true;
    s.type = SpatialJointType::spherical;
    s.point = top;
    SpatialBodyDescription body1, body2;
    body1.mass = body2.mass = mass;
    body1.com = b + 0.3 * (top - b);
    body2.com = b + 0.7 * (top - b);
    body1.inertia = body2.inertia = 0.01 * Eigen::Matrix3d::Identity();
    SpatialLimbDescription limb;
    limb.name = "leg" + std::to_string(i + 1);
    limb.joints = {u, p, s};
    limb.bodies = {body1, body2};
    return limb;
}

/// A random 6-UPS hexapod as tests/spatial_dynamics_test.cpp builds them: base points near a
/// circle of radius 1 at z ~ 0, platform points near a circle of 0.6 at z ~ 1, each leg a U (a1
/// horizontal across the leg, a2 across both), the actuated P along the leg, an S.
SpatialRobotDescription randomHexapod(std::mt19937& rng) {
    std::uniform_real_distribution<double> jitter(-0.08, 0.08);
    SpatialRobotDescription d;
    d.name = "random-6ups";
    d.motion = PlatformMotion::full;
    d.home << jitter(rng), jitter(rng), 1.0 + jitter(rng), jitter(rng), jitter(rng), jitter(rng);
    d.platform.mass = 30.0;
    d.platform.inertia = Eigen::Vector3d(2.0, 2.5, 4.0).asDiagonal();
    const Eigen::Matrix3d R_home = rotation(d.home(3), d.home(4), d.home(5));
    for (int i = 0; i < 6; ++i) {
        const double base_angle = (120.0 * (i / 2) + (i % 2 == 0 ? -15.0 : 15.0)) * M_PI / 180.0 + jitter(rng);
        const double top_angle =
            (60.0 + 120.0 * ((i + 1) / 2 % 3) + (i % 2 == 0 ? 15.0 : -15.0)) * M_PI / 180.0 + jitter(rng);
        const Eigen::Vector3d b(std::cos(base_angle) * (1.0 + jitter(rng)), std::sin(base_angle) * (1.0 + jitter(rng)),
                                jitter(rng));
        const Eigen::Vector3d top =
            d.home.head<3>() + R_home * Eigen::Vector3d(0.6 * std::cos(top_angle), 0.6 * std::sin(top_angle), 0.0);
        d.limbs.push_back(upsLeg(i, b, top, 2.0));
    }
    return d;
}

int temporaryFolders() {
    int count = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(fs::temp_directory_path(), ec)) {
        count += entry.path().filename().string().rfind("nocdyn-phc-", 0) == 0 ? 1 : 0;
    }
    return count;
}

/// Points TMPDIR at a folder of this test's own while it lives, so that the phc folders other
/// tests running beside it create and remove are not counted as this test's.
class PrivateTemporaryFolder {
public:
    PrivateTemporaryFolder() {
        const char* previous = std::getenv("TMPDIR");
        if (previous != nullptr) previous_ = previous;
        std::string pattern = (fs::temp_directory_path() / "nocdyn-modes-test-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
        folder_ = pattern;
        ::setenv("TMPDIR", folder_.c_str(), 1);
    }
    ~PrivateTemporaryFolder() {
        if (previous_) {
            ::setenv("TMPDIR", previous_->c_str(), 1);
        } else {
            ::unsetenv("TMPDIR");
        }
        std::error_code ec;
        fs::remove_all(folder_, ec);
    }
    PrivateTemporaryFolder(const PrivateTemporaryFolder&) = delete;
    PrivateTemporaryFolder& operator=(const PrivateTemporaryFolder&) = delete;

private:
    fs::path folder_;
    std::optional<std::string> previous_;
};

TEST(HomotopyModes, TheHomePoseIsAModeOfTheShippedStewartAtItsHomeLegLengths) {
    NOCDYN_REQUIRE_PHC();
    const Model model = shipped("stewart");
    const ActuatorVector u = actuatorValues(model, model.home);
    const auto start = std::chrono::steady_clock::now();
    const HomotopyModes result = homotopyModes(model, u, seeded());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "stewart at home: " << result.paths << " paths, " << result.solutions << " finite solutions, "
              << result.real_solutions << " real, " << result.modes.size() << " modes, " << result.rejected
              << " rejected; phc " << result.seconds << " s (CPU " << result.cpu_seconds << " s), the call " << seconds
              << " s\n";
    EXPECT_EQ(result.paths, 128);  // 2^7, the mixed volume
    // this symmetric design has fewer than a general platform's 40
    EXPECT_EQ(result.solutions, 28);
    ASSERT_FALSE(result.modes.empty());
    // nearest to home first, and the home pose itself, which the inverse kinematics from home
    // takes back to u (the modes far from home it may close on the other root of each leg's
    // length, u' = -u - 2.4 m: the solver's own check starts each limb at its closed form)
    EXPECT_TRUE(samePose(result.modes.front().pose, model.home)) << result.modes.front().pose.transpose();
    EXPECT_LE((actuatorValues(model, result.modes.front().pose) - u).cwiseAbs().maxCoeff(), kRoundTrip);
    const Geometry geometry(model, u);
    for (const HomotopyMode& mode : result.modes) {
        EXPECT_LE(mode.u_error, kRoundTrip) << mode.pose.transpose();
        EXPECT_LT(geometry.residual(mode.pose).cwiseAbs().maxCoeff(), 1e-12) << mode.pose.transpose();
    }
    // every pose a many-start Newton finds (its U joints reach every direction)
    const std::vector<TaskVector> newton = manyStartNewton(geometry, 11, 300);
    std::cout << "  many-start Newton: " << newton.size() << " poses\n";
    EXPECT_GE(newton.size(), 2u);
    for (const TaskVector& q : newton) {
        EXPECT_TRUE(among(q, result.modes)) << "Newton's pose " << q.transpose();
    }
    // base points at z = 0 and platform points in one plane: the table reflected in the base
    // plane, which for a plane of points is the translation to z -> -z, has the same leg lengths
    TaskVector mirrored = model.home;
    mirrored(2) = -mirrored(2);
    EXPECT_TRUE(among(mirrored, result.modes)) << "no mode at " << mirrored.transpose();
}

TEST(HomotopyModes, EveryManyStartNewtonPoseOfRandomHexapodsIsAmongPhcsModes) {
    NOCDYN_REQUIRE_PHC();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> offset(-1.0, 1.0);
    for (int design = 0; design < 1; ++design) {  // one random design: a phc run is about 2 s
        const Model model(randomHexapod(rng));
        TaskVector p = model.home;
        for (int k = 0; k < 6; ++k) p(k) += (k < 3 ? 0.05 : 0.08) * offset(rng);
        const ActuatorVector u = actuatorValues(model, p);
        const HomotopyModes result = homotopyModes(model, u, seeded());
        std::cout << "random hexapod " << design << ": " << result.solutions << " finite solutions, "
                  << result.modes.size() << " modes; phc " << result.seconds << " s (CPU " << result.cpu_seconds
                  << " s)\n";
        EXPECT_EQ(result.solutions, 40) << "design " << design;  // a general platform's count
        EXPECT_EQ(result.rejected, 0) << "design " << design;    // its U joints reach every direction
        EXPECT_TRUE(among(p, result.modes)) << "design " << design << ": the pose " << p.transpose();
        for (const HomotopyMode& mode : result.modes) EXPECT_LE(mode.u_error, kRoundTrip);
        const std::vector<TaskVector> newton = manyStartNewton(Geometry(model, u), 100 + design, 300);
        std::cout << "  many-start Newton: " << newton.size() << " poses\n";
        EXPECT_GE(newton.size(), 2u);
        for (const TaskVector& q : newton) {
            EXPECT_TRUE(among(q, result.modes)) << "design " << design << ": Newton's pose " << q.transpose();
        }
    }
}

/// P. Dietmaier's platform with 40 real assembly modes ("The Stewart-Gough platform of general
/// geometry can have 40 real postures", ARK 1998; the numbers as E. Martyushev's fkSGP tests give
/// them): base points A_i, platform points B_i (platform frame), leg lengths L_i. Built as a 6-UPS
/// robot whose home puts the platform frame at `home`; each leg's P along the leg at home, so
/// that u_i = L_i - |leg i at home|.
struct Dietmaier {
    SpatialRobotDescription description;
    ActuatorVector u = ActuatorVector::Zero(6);
    Dietmaier() {
        const double A[6][3] = {{0, 0, 0},
                                {1.107915, 0, 0},
                                {0.549094, 0.756063, 0},
                                {0.735077, -0.223935, 0.525991},
                                {0.514188, -0.526063, -0.368418},
                                {0.590473, 0.094733, -0.205018}};
        const double B[6][3] = {{0, 0, 0},
                                {0.542805, 0, 0},
                                {0.956919, -0.528915, 0},
                                {0.665885, -0.353482, 1.402538},
                                {0.478359, 1.158742, 0.107672},
                                {-0.137087, -0.235121, 0.353913}};
        const double L[6] = {1, 0.645275, 1.086284, 1.503439, 1.281933, 0.771071};
        SpatialRobotDescription& d = description;
        d.name = "dietmaier-40";
        d.motion = PlatformMotion::full;
        d.home << 0.3, -0.2, 2.0, 0.1, 0.2, 0.3;
        d.platform.mass = 30.0;
        d.platform.inertia = Eigen::Vector3d(2.0, 2.5, 4.0).asDiagonal();
        const Eigen::Matrix3d R_home = rotation(d.home(3), d.home(4), d.home(5));
        for (int i = 0; i < 6; ++i) {
            const Eigen::Vector3d a(A[i][0], A[i][1], A[i][2]);
            const Eigen::Vector3d top = d.home.head<3>() + R_home * Eigen::Vector3d(B[i][0], B[i][1], B[i][2]);
            u(i) = L[i] - (top - a).norm();
            d.limbs.push_back(upsLeg(i, a, top, 1.0));
        }
    }
};

TEST(HomotopyModes, DietmaiersPlatformHasFortyRealAssemblyModes) {
    NOCDYN_REQUIRE_PHC();
    const Dietmaier dietmaier;
    const Model model(dietmaier.description);
    const HomotopyModes result = homotopyModes(model, dietmaier.u, seeded());
    std::cout << "Dietmaier's platform: " << result.solutions << " finite solutions, " << result.real_solutions
              << " real, " << result.modes.size() << " modes; phc " << result.seconds << " s (CPU "
              << result.cpu_seconds << " s)\n";
    EXPECT_EQ(result.solutions, 40);
    EXPECT_EQ(result.real_solutions, 40);
    EXPECT_EQ(result.rejected, 0);
    EXPECT_EQ(result.modes.size(), 40u);
    const Geometry geometry(model, dietmaier.u);
    for (const HomotopyMode& mode : result.modes) {
        EXPECT_LE(mode.u_error, kRoundTrip) << mode.pose.transpose();
        EXPECT_LT(geometry.residual(mode.pose).cwiseAbs().maxCoeff(), 1e-12) << mode.pose.transpose();
    }
}

TEST(HomotopyModes, RobotsOfOtherKindsAreRefusedNamingTheLimb) {
    const Model rus = shipped("hexa-6rus");
    try {
        (void)homotopyModes(rus, ActuatorVector::Zero(6));
        FAIL() << "a 6-RUS was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("is not a 6-UPS robot"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("limb 1"), std::string::npos) << e.what();
    }
    const Model delta = shipped("delta");
    EXPECT_THROW((void)homotopyModes(delta, ActuatorVector::Zero(3)), Error);
    std::string reason;
    EXPECT_TRUE(isUpsHexapod(shipped("stewart"), &reason)) << reason;
}

TEST(HomotopyModes, BadActuatorValuesAreRefused) {
    const Model model = shipped("stewart");
    EXPECT_THROW((void)homotopyModes(model, ActuatorVector::Zero(5)), Error);
    ActuatorVector u = ActuatorVector::Zero(6);
    u(2) = std::nan("");
    EXPECT_THROW((void)homotopyModes(model, u), Error);
    // leg 1 of length 0: u = -1.2 m
    u.setZero();
    u(0) = -1.2;
    try {
        (void)homotopyModes(model, u);
        FAIL() << "a leg of length 0 was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("limb 1 (leg1) has length 0"), std::string::npos) << e.what();
    }
    u(0) = 1e200;
    try {
        (void)homotopyModes(model, u);
        FAIL() << "a leg of 1e200 m was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("limb 1 (leg1) is too long"), std::string::npos) << e.what();
    }
}

TEST(HomotopyModes, AMissingPhcIsNamedWithItsPackage) {
    const Model model = shipped("stewart");
    HomotopyOptions options;
    options.executable = "/nonexistent/phc";
    try {
        (void)homotopyModes(model, ActuatorVector::Zero(6), options);
        FAIL() << "no error without phc";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("phcpack"), std::string::npos) << e.what();
    }
    const std::string path = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
    ::setenv("PATH", "/nonexistent", 1);
    EXPECT_TRUE(findPhc().empty());
    try {
        (void)homotopyModes(model, ActuatorVector::Zero(6));
        ADD_FAILURE() << "no error without phc on PATH";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("Debian package phcpack"), std::string::npos) << e.what();
    }
    ::setenv("PATH", path.c_str(), 1);
}

/// A stand-in for phc: a shell script (written here, run by path with no shell between) that
/// does `body` in the solver's folder.
std::string fakePhc(const std::string& name, const std::string& body) {
    const char* scratch = std::getenv("TEST_TMPDIR");
    const fs::path folder = fs::path(scratch != nullptr ? scratch : fs::temp_directory_path().string()) / "fake-phc";
    fs::create_directories(folder);
    const fs::path script = folder / name;
    std::ofstream(script) << "#!/bin/sh\nPATH=/usr/bin:/bin\n" << body << "\n";
    ::chmod(script.c_str(), 0755);
    return script.string();
}

TEST(HomotopyModes, APhcThatFailsOrWritesNonsenseGivesOneErrorAndLeavesNoFolder) {
    const Model model = shipped("stewart");
    const PrivateTemporaryFolder privateFolder;
    const int before = temporaryFolders();
    ASSERT_EQ(before, 0);
    const auto message = [&](const std::string& executable, double timeout = 120.0) {
        HomotopyOptions options;
        options.executable = executable;
        options.timeout = timeout;
        try {
            (void)homotopyModes(model, ActuatorVector::Zero(6), options);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(fakePhc("exit3", "echo 'something went wrong' >&2; exit 3"))
                  .find("exit status 3): something went wrong"),
              std::string::npos);
    EXPECT_NE(message(fakePhc("nolist", "touch output")).find("no solution list"), std::string::npos);
    EXPECT_NE(message(fakePhc("count", "printf 'THE SOLUTIONS :\\n2 8\\n' >> input; touch output"))
                  .find("announces 2 solutions and has 0"),
              std::string::npos);
    EXPECT_NE(message(fakePhc("name",
                              "printf 'THE SOLUTIONS :\\n1 8\\nthe solution for t :\\n x : 1 0\\n' >> input; "
                              "touch output"))
                  .find("unknown variable 'x'"),
              std::string::npos);
    EXPECT_NE(message(fakePhc("number",
                              "printf 'THE SOLUTIONS :\\n1 8\\nthe solution for t :\\n q0 : 1e999 0\\n' >> "
                              "input; touch output"))
                  .find("cannot be read"),
              std::string::npos);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_NE(message(fakePhc("sleeps", "exec sleep 30"), 0.3).find("did not finish within 0.3 s"), std::string::npos);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
    EXPECT_EQ(temporaryFolders(), before);
}

}  // namespace
}  // namespace nocdyn::spatial
