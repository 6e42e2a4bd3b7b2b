// General robot descriptions: the 3-PRR short form's expansion and validation (description.hpp).
#include "nocdyn/description.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include <Eigen/Geometry>

#include "nocdyn/error.hpp"
#include "nocdyn/printable.hpp"
#include "nocdyn/spatial_description.hpp"
#include "nocdyn/detail/eigen_instances.hpp"

namespace nocdyn {

std::string LimbDescription::type() const {
    std::string out;
    for (const JointDescription& joint : joints) out += joint.type == JointType::revolute ? 'R' : 'P';
    return out;
}

int RobotDescription::actuatorCount() const {
    int count = 0;
    for (const LimbDescription& limb : limbs) {
        for (const JointDescription& joint : limb.joints) count += joint.actuated ? 1 : 0;
    }
    return count;
}

bool RobotDescription::hasCompliance() const {
    for (const LimbDescription& limb : limbs) {
        for (const JointDescription& joint : limb.joints) {
            if (joint.stiffness) return true;
        }
    }
    return hasElasticBody();
}

bool RobotDescription::hasElasticBody() const {
    for (const LimbDescription& limb : limbs) {
        for (const BodyDescription& body : limb.bodies) {
            if (body.elastic) return true;
        }
    }
    return false;
}

std::string where(const RobotDescription& robot, int line) {
    if (robot.source.empty()) return "";
    if (line <= 0) return robot.source + ": ";
    return robot.source + ":" + std::to_string(line) + ": ";
}

namespace {

// Plausibility ranges: beyond them products of the values overflow or lose all precision.
constexpr double kMaxLength = 1.0e3;   // [m]
constexpr double kMaxMass = 1.0e6;     // [kg]
constexpr double kMaxInertia = 1.0e9;  // [kg m^2]
constexpr double kMaxGravity = 1.0e4;  // [m/s^2]
constexpr double kMaxCoefficient = 1.0e9;
constexpr double kMaxStiffness = 1.0e15;  // [N/m, N m/rad, N, N m^2]
// Below it a compliance 1/k (or l^3 / (3 EI)) is so large that the limb's stiffness matrix
// K_j = N (N^T C_j N)^-1 N^T over- or underflows; no mechanism is that soft.
constexpr double kMinStiffness = 1.0e-9;  // [N/m, N m/rad, N, N m^2]

class Checker {
public:
    explicit Checker(const RobotDescription& robot) : robot_(robot) {}

    [[noreturn]] void fail(int line, const std::string& field, const std::string& reason) const {
        std::ostringstream msg;
        msg << where(robot_, line) << field << ": " << reason;
        throw Error(msg.str());
    }

    void finiteIn(double value, double lo, double hi, int line, const std::string& field, const char* unit) const {
        if (!std::isfinite(value) || value < lo || value > hi) {
            std::ostringstream msg;
            msg << "must be a finite number in [" << lo << ", " << hi << "] " << unit << ", got " << value;
            fail(line, field, msg.str());
        }
    }

    void point(const Eigen::Vector2d& v, int line, const std::string& field) const {
        finiteIn(v.x(), -kMaxLength, kMaxLength, line, field + "[0]", "m");
        finiteIn(v.y(), -kMaxLength, kMaxLength, line, field + "[1]", "m");
    }

private:
    const RobotDescription& robot_;
};

/// Motion translation: every limb ends in an R joint at one common point, the tool point, which
/// is the home position; that joint's variable is not defined by the pose [x, y] (it takes up
/// the platform's fictitious rotation), so it is passive and free; the platform is a point mass
/// at the tool point.
void validateTranslation(RobotDescription& robot, const Checker& check) {
    if (robot.home(0) != 0.0) check.fail(0, "home", "a translating platform has no angle in its pose [x, y]");
    const PlatformDescription& platform = robot.platform;
    if (platform.inertia != 0.0) {
        check.fail(platform.line, "platform.inertia",
                   "a translating point tool is a point mass: its inertia must be 0 (or absent)");
    }
    if (!platform.com.isZero()) {
        check.fail(platform.line, "platform.com", "a translating point tool is a point mass at the tool point: [0, 0]");
    }
    const Eigen::Vector2d tool = robot.home.tail<2>();
    double scale = 0.0;
    for (const LimbDescription& limb : robot.limbs) {
        for (const JointDescription& joint : limb.joints) {
            if (joint.type == JointType::revolute) scale = std::max(scale, (joint.point - tool).norm());
        }
    }
    const double tolerance = 1e-12 * std::max(1.0, scale);
    for (std::size_t j = 0; j < robot.limbs.size(); ++j) {
        const LimbDescription& limb = robot.limbs[j];
        const JointDescription& last = limb.joints[2];
        const std::string field = "limbs[" + std::to_string(j) + "] (" + text::printable(limb.name) + ").joints[2]";
        if (last.type != JointType::revolute) {
            check.fail(last.line, field,
                       "with motion translation every limb ends in an R joint at the tool point, but this limb is " +
                           limb.type());
        }
        if (!((last.point - tool).norm() <= tolerance)) {
            std::ostringstream msg;
            msg.precision(17);
            msg << "the limbs' last R joints must meet at one point, the tool point at home [" << tool.x() << ", "
                << tool.y() << "], but this one is at [" << last.point.x() << ", " << last.point.y() << "]";
            check.fail(last.line, field + ".point", msg.str());
        }
        const JointLimits free;
        if (last.actuated || last.limits.lower != free.lower || last.limits.upper != free.upper ||
            last.limits.effort != free.effort || last.limits.velocity != free.velocity || last.damping != 0.0 ||
            last.friction != 0.0 || last.stiffness) {
            check.fail(last.line, field,
                       "the last R joint's angle is not set by the pose [x, y]: it cannot be actuated and takes no "
                       "limits, damping, friction or stiffness");
        }
    }
}

}  // namespace

void validate(RobotDescription& robot) {
    const Checker check(robot);
    const int limbs = static_cast<int>(robot.limbs.size());
    if (limbs < 2 || limbs > kMaxLimbs) {
        check.fail(0, "limbs",
                   "a robot has 2 to " + std::to_string(kMaxLimbs) + " limbs, got " + std::to_string(limbs));
    }
    check.finiteIn(robot.gravity.x(), -kMaxGravity, kMaxGravity, 0, "gravity[0]", "m/s^2");
    check.finiteIn(robot.gravity.y(), -kMaxGravity, kMaxGravity, 0, "gravity[1]", "m/s^2");
    check.finiteIn(robot.home(0), -std::numbers::pi, std::numbers::pi, 0, "home[0]", "rad");
    check.finiteIn(robot.home(1), -kMaxLength, kMaxLength, 0, "home[1]", "m");
    check.finiteIn(robot.home(2), -kMaxLength, kMaxLength, 0, "home[2]", "m");
    if (!std::isfinite(robot.max_condition) || robot.max_condition <= 1.0 || robot.max_condition > 1.0e12) {
        check.fail(0, "max_condition", "must be a finite number in (1, 1e12]");
    }
    if (!std::isfinite(robot.damping_ratio) || robot.damping_ratio < 0.0 || robot.damping_ratio >= 1.0) {
        check.fail(0, "damping_ratio", "must be a number in [0, 1) (the lumped modes' damping ratio)");
    }
    const PlatformDescription& platform = robot.platform;
    check.finiteIn(platform.mass, 0.0, kMaxMass, platform.line, "platform.mass", "kg");
    check.finiteIn(platform.inertia, 0.0, kMaxInertia, platform.line, "platform.inertia", "kg m^2");
    check.point(platform.com, platform.line, "platform.com");
    double total_mass = platform.mass;
    for (int j = 0; j < limbs; ++j) {
        LimbDescription& limb = robot.limbs[static_cast<std::size_t>(j)];
        if (limb.name.empty()) limb.name = "limb" + std::to_string(j + 1);
        const std::string prefix = "limbs[" + std::to_string(j) + "] (" + text::printable(limb.name) + ")";
        if (limb.type() == "PPP") {
            check.fail(limb.line, prefix, "a limb of three prismatic joints cannot carry the platform's rotation");
        }
        for (int k = 0; k < 3; ++k) {
            JointDescription& joint = limb.joints[static_cast<std::size_t>(k)];
            const std::string field = prefix + ".joints[" + std::to_string(k) + "]";
            if (joint.type == JointType::revolute) {
                check.point(joint.point, joint.line, field + ".point");
            } else {
                check.finiteIn(joint.direction.x(), -kMaxLength, kMaxLength, joint.line, field + ".direction[0]", "");
                check.finiteIn(joint.direction.y(), -kMaxLength, kMaxLength, joint.line, field + ".direction[1]", "");
                const double norm = joint.direction.norm();
                if (!(norm > 1e-9)) check.fail(joint.line, field + ".direction", "must be a non-zero vector");
                // unit length; a direction already unit to round-off is kept as written, so that
                // a file written by `convert` reads back bit for bit
                if (std::abs(norm - 1.0) > 4.0 * std::numeric_limits<double>::epsilon()) joint.direction /= norm;
            }
            const JointLimits& lim = joint.limits;
            if (std::isnan(lim.lower) || std::isnan(lim.upper) || !(lim.lower < lim.upper) || lim.lower > 0.0 ||
                lim.upper < 0.0) {
                check.fail(joint.line, field + ".limits",
                           "need lower < upper with the home value 0 inside [lower, upper]");
            }
            if (std::isnan(lim.effort) || !(lim.effort > 0.0)) {
                check.fail(joint.line, field + ".limits.effort", "must be a positive number");
            }
            if (std::isnan(lim.velocity) || !(lim.velocity > 0.0)) {
                check.fail(joint.line, field + ".limits.velocity", "must be a positive number");
            }
            check.finiteIn(joint.damping, 0.0, kMaxCoefficient, joint.line, field + ".damping", "");
            check.finiteIn(joint.friction, 0.0, kMaxCoefficient, joint.line, field + ".friction", "");
            if (joint.stiffness) {
                // 0 is a free joint (a force actuator); any other value a spring
                const double k = *joint.stiffness;
                if (!std::isfinite(k) || (k != 0.0 && !(k >= kMinStiffness && k <= kMaxStiffness))) {
                    std::ostringstream msg;
                    msg << "must be 0 (free) or a finite number in [" << kMinStiffness << ", " << kMaxStiffness << "] "
                        << (joint.type == JointType::revolute ? "N m/rad" : "N/m") << ", got " << k;
                    check.fail(joint.line, field + ".stiffness", msg.str());
                }
            }
        }
        for (int b = 0; b < 2; ++b) {
            const BodyDescription& body = limb.bodies[static_cast<std::size_t>(b)];
            const std::string field = prefix + ".bodies[" + std::to_string(b) + "]";
            check.finiteIn(body.mass, 0.0, kMaxMass, body.line, field + ".mass", "kg");
            check.finiteIn(body.inertia, 0.0, kMaxInertia, body.line, field + ".inertia", "kg m^2");
            check.point(body.com, body.line, field + ".com");
            total_mass += body.mass;
            if (body.elastic) {
                const JointDescription& inboard = limb.joints[static_cast<std::size_t>(b)];
                const JointDescription& outboard = limb.joints[static_cast<std::size_t>(b) + 1];
                if (inboard.type != JointType::revolute || outboard.type != JointType::revolute) {
                    check.fail(body.line, field + ".elastic",
                               "an elastic body is a beam between two revolute joints, but " +
                                   text::printable(limb.name) + "'s body " + std::to_string(b + 1) +
                                   " is carried by a prismatic joint (" + limb.type() + ")");
                }
                if (!((outboard.point - inboard.point).norm() > 1e-9)) {
                    check.fail(body.line, field + ".elastic", "the beam between the body's two joints has zero length");
                }
                const auto positive = [&](double value, const char* key, const char* unit) {
                    if (!std::isfinite(value) || !(value >= kMinStiffness) || value > kMaxStiffness) {
                        std::ostringstream msg;
                        msg << "must be a finite number in [" << kMinStiffness << ", " << kMaxStiffness << "] " << unit
                            << ", got " << value;
                        check.fail(body.line, field + ".elastic." + key, msg.str());
                    }
                };
                positive(body.elastic->EA, "EA", "N");
                positive(body.elastic->EI, "EI", "N m^2");
            }
        }
    }
    if (!(total_mass > 0.0)) check.fail(0, "platform.mass", "the robot has no mass at all");
    const int actuators = robot.actuatorCount();
    if (robot.motion == PlatformMotion::translation) {
        validateTranslation(robot, check);
        if (actuators < 2) {
            check.fail(0, "limbs",
                       "a translating point tool needs at least 2 actuated joints, got " + std::to_string(actuators));
        }
        return;
    }
    if (actuators < 3) {
        check.fail(0, "limbs", "a planar platform needs at least 3 actuated joints, got " + std::to_string(actuators));
    }
}

}  // namespace nocdyn

// Spatial robot descriptions (spatial_description.hpp): the joint screws at home and the checks
// the reader makes with them.

namespace nocdyn {

int SpatialJointDescription::freedoms() const {
    switch (type) {
        case SpatialJointType::universal:
            return 2;
        case SpatialJointType::spherical:
            return 3;
        default:
            return 1;
    }
}

char SpatialJointDescription::letter() const {
    switch (type) {
        case SpatialJointType::revolute:
            return 'R';
        case SpatialJointType::prismatic:
            return 'P';
        case SpatialJointType::universal:
            return 'U';
        case SpatialJointType::spherical:
            return 'S';
    }
    return '?';
}

std::string SpatialLimbDescription::type() const {
    std::string out;
    for (const SpatialJointDescription& joint : joints) out += joint.letter();
    return out;
}

int SpatialLimbDescription::freedoms() const {
    int count = 0;
    for (const SpatialJointDescription& joint : joints) count += joint.freedoms();
    return count;
}

int SpatialRobotDescription::actuatorCount() const {
    int count = 0;
    for (const SpatialLimbDescription& limb : limbs) {
        for (const SpatialJointDescription& joint : limb.joints) count += joint.actuated ? 1 : 0;
    }
    return count;
}

double SpatialRobotDescription::totalMass() const {
    double mass = platform.mass;
    for (const SpatialLimbDescription& limb : limbs) {
        for (const SpatialBodyDescription& body : limb.bodies) mass += body.mass;
    }
    return mass;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> limbScrews(const SpatialLimbDescription& limb) {
    Eigen::Matrix<double, 6, Eigen::Dynamic> screws(6, limb.freedoms());
    Eigen::Index column = 0;
    // an R screw [a; p x a]: the axis a through the point p
    const auto revolute = [&](const Eigen::Vector3d& point, const Eigen::Vector3d& axis) {
        screws.col(column).head<3>() = axis;
        screws.col(column).tail<3>() = point.cross(axis);
        ++column;
    };
    for (const SpatialJointDescription& joint : limb.joints) {
        switch (joint.type) {
            case SpatialJointType::revolute:
                revolute(joint.point, joint.axis);
                break;
            case SpatialJointType::prismatic:
                screws.col(column).head<3>().setZero();
                screws.col(column).tail<3>() = joint.direction;
                ++column;
                break;
            case SpatialJointType::universal:
                revolute(joint.point, joint.axis1);
                revolute(joint.point, joint.axis2);
                break;
            case SpatialJointType::spherical:
                for (int e = 0; e < 3; ++e) revolute(joint.point, Eigen::Vector3d::Unit(e));
                break;
        }
    }
    return screws;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> freeRotationsAtHome(const SpatialRobotDescription& robot) {
    // The twists every limb allows are the intersection of the spans of their screws, i.e. the
    // orthogonal complement of the sum of the spans' complements: stack each limb's complement
    // basis (the left singular vectors past its rank) and take the null space of the stack.
    // Rank decisions relative to the largest singular value: the linear rows scale with the
    // lengths, the angular rows are unit.
    Eigen::Matrix<double, Eigen::Dynamic, 6> complements(0, 6);
    for (const SpatialLimbDescription& limb : robot.limbs) {
        const Eigen::Matrix<double, 6, Eigen::Dynamic> screws = limbScrews(limb);
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(screws, Eigen::ComputeFullU);
        const Eigen::VectorXd& sigma = svd.singularValues();
        const double tolerance = 1e-9 * std::max(1.0, sigma.size() > 0 ? sigma(0) : 0.0);
        Eigen::Index rank = 0;
        while (rank < sigma.size() && sigma(rank) > tolerance) ++rank;
        const Eigen::Index extra = 6 - rank;
        if (extra == 0) continue;
        complements.conservativeResize(complements.rows() + extra, 6);
        complements.bottomRows(extra) = svd.matrixU().rightCols(extra).transpose();
    }
    Eigen::Matrix<double, 6, Eigen::Dynamic> common;
    if (complements.rows() == 0) {
        common = Eigen::Matrix<double, 6, 6>::Identity();
    } else {
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(complements, Eigen::ComputeFullV);
        const Eigen::VectorXd& sigma = svd.singularValues();
        Eigen::Index rank = 0;
        while (rank < sigma.size() && sigma(rank) > 1e-9) ++rank;
        common = svd.matrixV().rightCols(6 - rank);
    }
    if (common.cols() == 0) return Eigen::Matrix<double, 3, Eigen::Dynamic>(3, 0);
    // the rotations: the range of the intersection's angular rows
    const Eigen::JacobiSVD<Eigen::MatrixXd> angular(common.topRows<3>(), Eigen::ComputeFullU);
    const Eigen::VectorXd& sigma = angular.singularValues();
    Eigen::Index rank = 0;
    while (rank < sigma.size() && sigma(rank) > 1e-9) ++rank;
    return angular.matrixU().leftCols(rank);
}

std::string inertiaProblem(const Eigen::Matrix3d& inertia) {
    std::ostringstream msg;
    msg.precision(17);
    if (!inertia.allFinite()) return "the tensor's entries must be finite numbers";
    const Eigen::Matrix3d symmetric = 0.5 * (inertia + inertia.transpose());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(symmetric, Eigen::EigenvaluesOnly);
    const Eigen::Vector3d& moments = eigen.eigenvalues();  // ascending
    const double tolerance = 1e-12 * moments.cwiseAbs().maxCoeff();
    for (int i = 0; i < 3; ++i) {
        for (int j = i + 1; j < 3; ++j) {
            if (std::abs(inertia(i, j) - inertia(j, i)) > tolerance) {
                msg << "the tensor must be symmetric, but entry [" << i << "][" << j << "] = " << inertia(i, j)
                    << " and [" << j << "][" << i << "] = " << inertia(j, i);
                return msg.str();
            }
        }
    }
    if (moments(0) < -tolerance) {
        msg << "the tensor must be positive semi-definite, but a principal moment is " << moments(0);
        return msg.str();
    }
    // the largest principal moment at most the sum of the other two (the others follow)
    if (moments(2) > moments(0) + moments(1) + tolerance) {
        msg << "the principal moments " << moments(0) << ", " << moments(1) << ", " << moments(2)
            << " break the triangle inequality (the largest exceeds the sum of the other two): no body has them";
        return msg.str();
    }
    return {};
}

}  // namespace nocdyn
