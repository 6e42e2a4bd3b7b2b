// A planar robot written as a spatial robot file (space: spatial, motion: full;
// docs/robot-files-spatial.md), for the tests that check the spatial model gives the planar
// results on a motion that stays in the plane.
//
// Each planar limb J1 J2 J3 (R about z through the same point, P along the same in-plane
// direction) keeps its joints and bodies (c.o.m. at z = 0, Izz the planar inertia, Ixx = Iyy =
// Izz / 2), and gains the three out-of-plane freedoms between its last planar joint and the
// platform: an actuated P along z, then a U with axes x, y through the limb's platform point
// (1 + 1 + 1 + 1 + 2 = 6 freedoms). The five listed joints have four bodies: the planar two and
// two massless ones (J3 to P(z), P(z) to U). At z = 0 and roll = pitch = 0 every screw lies in
// one of two complementary subspaces, in-plane (w_z, v_x, v_y) or out-of-plane (w_x, w_y, v_z),
// so the limb Jacobians and the actuation map are block-diagonal: the planar actuators give the
// planar forces, and the z actuators carry what acts out of the plane (the platform's weight
// when gravity is along -z).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/description.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::test {

/// Where gravity points in the spatial file.
enum class EmbeddedGravity {
    in_plane,  ///< the planar robot's [gx, gy] as [gx, gy, 0]
    vertical,  ///< [0, 0, -g]: the plane is horizontal (the planar reference then has none)
};

/// Options of the spatial writing.
struct EmbeddingOptions {
    EmbeddedGravity gravity = EmbeddedGravity::in_plane;
    double g = 9.81;  ///< [m/s^2] with EmbeddedGravity::vertical
    /// Added to the first limb's first body's c.o.m. (a deliberately wrong file).
    Eigen::Vector3d com_shift = Eigen::Vector3d::Zero();
    /// Added to the platform's c.o.m. (platform frame).
    Eigen::Vector3d platform_com_shift = Eigen::Vector3d::Zero();
};

/// The spatial robot file's text, and where its actuators are.
struct SpatialEmbedding {
    std::string yaml;
    std::vector<int> in_plane;  ///< the spatial actuator index of planar actuator k (file order)
    std::vector<int> lift;      ///< the spatial index of limb j's P(z) actuator
};

namespace embedding_detail {

inline std::string number(double value) { return text::shortest(value); }

inline std::string vector3(double x, double y, double z) {
    std::string s = "[";
    s.append(number(x)).append(", ").append(number(y)).append(", ").append(number(z)).append("]");
    return s;
}

/// diag(I/2, I/2, I): the planar moment about z, a thin body's moments about x and y.
inline std::string planarInertia(double izz) {
    std::string s = "[";
    s.append(vector3(0.5 * izz, 0.0, 0.0)).append(", ").append(vector3(0.0, 0.5 * izz, 0.0)).append(", ");
    s.append(vector3(0.0, 0.0, izz)).append("]");
    return s;
}

/// limits: {...} with the finite fields only (an absent one is infinite in both forms).
inline std::string limits(const JointLimits& lim) {
    std::string s;
    const auto field = [&s](const char* key, double value) {
        if (!std::isfinite(value)) return;
        s.append(s.empty() ? "" : ", ").append(key).append(": ").append(number(value));
    };
    field("lower", lim.lower);
    field("upper", lim.upper);
    field("effort", lim.effort);
    field("velocity", lim.velocity);
    if (s.empty()) return s;
    std::string out = ", limits: {";
    out.append(s).append("}");
    return out;
}

}  // namespace embedding_detail

/// Where the limb's U joins the platform, at home in the plane.
inline Eigen::Vector2d embeddingPoint(const LimbDescription& limb) {
    return limb.joints[2].type == JointType::revolute ? limb.joints[2].point : limb.bodies[1].com;
}

/// The planar robot (general form, motion full) as a spatial robot file. The planar home
/// [theta, x, y] (the core's order) becomes [x, y, 0, 0, 0, theta].
inline SpatialEmbedding spatialEmbedding(const RobotDescription& planar, const EmbeddingOptions& options = {}) {
    using embedding_detail::number;
    using embedding_detail::vector3;
    SpatialEmbedding out;
    std::string& y = out.yaml;
    y.append("name: ").append(planar.name).append("-spatial\n");
    y.append("space: spatial\nmotion: full\n");
    if (options.gravity == EmbeddedGravity::in_plane) {
        y.append("gravity: ").append(vector3(planar.gravity.x(), planar.gravity.y(), 0.0)).append("\n");
    } else {
        y.append("gravity: ").append(vector3(0.0, 0.0, -options.g)).append("\n");
    }
    y.append("home: [")
        .append(number(planar.home(1)))
        .append(", ")
        .append(number(planar.home(2)))
        .append(", 0.0, 0.0, 0.0, ")
        .append(number(planar.home(0)))
        .append("]\n");
    y.append("max_condition: ").append(number(planar.max_condition)).append("\n");
    y.append("platform: {mass: ")
        .append(number(planar.platform.mass))
        .append(", com: ")
        .append(vector3(planar.platform.com.x() + options.platform_com_shift.x(),
                        planar.platform.com.y() + options.platform_com_shift.y(), options.platform_com_shift.z()))
        .append(", inertia: ")
        .append(embedding_detail::planarInertia(planar.platform.inertia))
        .append("}\n");
    y.append("limbs:\n");
    int actuator = 0;
    for (std::size_t j = 0; j < planar.limbs.size(); ++j) {
        const LimbDescription& limb = planar.limbs[j];
        y.append("  - name: ").append(limb.name.empty() ? "limb" + std::to_string(j + 1) : limb.name).append("\n");
        y.append("    joints:\n");
        for (const JointDescription& joint : limb.joints) {
            if (joint.type == JointType::revolute) {
                y.append("      - {type: R, point: ")
                    .append(vector3(joint.point.x(), joint.point.y(), 0.0))
                    .append(", axis: [0.0, 0.0, 1.0]");
            } else {
                y.append("      - {type: P, direction: ")
                    .append(vector3(joint.direction.x(), joint.direction.y(), 0.0));
            }
            if (joint.actuated) {
                y.append(", actuated: true");
                out.in_plane.push_back(actuator++);
            }
            y.append(embedding_detail::limits(joint.limits));
            y.append(", damping: ").append(number(joint.damping));
            y.append(", friction: ").append(number(joint.friction)).append("}\n");
        }
        // the out-of-plane freedoms: P along z (actuated), U about x then y through the limb's
        // platform point: its last R joint's axis, or after a last P joint the second body's
        // c.o.m. at home (any point fixed in the platform serves; distinct limbs' points keep
        // the z actuators from lying on one line)
        const Eigen::Vector2d point = embeddingPoint(limb);
        y.append("      - {type: P, direction: [0.0, 0.0, 1.0], actuated: true}\n");
        out.lift.push_back(actuator++);
        y.append("      - {type: U, point: ")
            .append(vector3(point.x(), point.y(), 0.0))
            .append(", axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]}\n");
        y.append("    bodies:\n");
        for (std::size_t b = 0; b < 2; ++b) {
            const BodyDescription& body = limb.bodies[b];
            Eigen::Vector3d com(body.com.x(), body.com.y(), 0.0);
            if (j == 0 && b == 0) com += options.com_shift;
            y.append("      - {mass: ")
                .append(number(body.mass))
                .append(", com: ")
                .append(vector3(com.x(), com.y(), com.z()))
                .append(", inertia: ")
                .append(embedding_detail::planarInertia(body.inertia))
                .append("}\n");
        }
        for (int b = 0; b < 2; ++b) {  // J3 to P(z), P(z) to U: massless
            y.append("      - {mass: 0.0, com: ")
                .append(vector3(point.x(), point.y(), 0.0))
                .append(", inertia: ")
                .append(embedding_detail::planarInertia(0.0))
                .append("}\n");
        }
    }
    return out;
}

}  // namespace nocdyn::test
