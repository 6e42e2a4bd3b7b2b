// The short form of a robot file: the symmetric 3-PRR of the paper by its parameters (SI
// units), the paper's prototype as the default, their validation, and their expansion to the
// general description that every algorithm takes. See docs/model-notes.md for where each default
// comes from (eq. 32, Table I, footnote 6).
#pragma once

#include <string>
#include <utility>

#include "nocdyn/description.hpp"
#include "nocdyn/error.hpp"

namespace nocdyn::io {

/// Parameters of a symmetric 3-limb planar parallel robot with prismatic actuators
/// (3-PRR). All values in SI: m, kg, kg m^2, N.
struct RobotParameters {
    std::string name = "paper-3prr";
    // geometry (eq. 32)
    double base_side = 0.400;      ///< b: side of the base triangle B_1 B_2 B_3 [m]
    double platform_side = 0.110;  ///< a: side of the platform triangle M_1 M_2 M_3 [m]
    double link_length = 0.15915;  ///< l: |A_j M_j| [m]
    double link_com = 0.079575;    ///< l_c: from A_j to the link's c.o.m. [m]
    // inertia (Table I)
    double slider_mass = 1.46966;             ///< moving coil + actuator plate [kg]
    double link_mass = 0.63863;               ///< [kg]
    double link_inertia = 1.5786066e-3;       ///< about the link's c.o.m. [kg m^2]
    double platform_mass = 1.75257;           ///< [kg]
    double platform_inertia = 6.17311382e-3;  ///< about C [kg m^2]
    // actuators (footnote 6)
    double stroke = 0.0249;     ///< total stroke, centred on the reference posture [m]
    double peak_force = 262.0;  ///< [N]
    // numerical limits
    double max_condition = 1.0e4;  ///< largest condition number of H or D accepted

    /// Base circumradius R = b / sqrt(3).
    [[nodiscard]] double baseCircumradius() const;
    /// Platform circumradius r = a / sqrt(3).
    [[nodiscard]] double platformCircumradius() const;
};

/// A robot parameter out of its accepted range. field() is its dotted name in the robot file
/// (e.g. "geometry.link_com"), reason() the message without the robot's name, so that a
/// reader can prefix the file and line of that field.
class ParameterError : public Error {
public:
    ParameterError(const std::string& robot, std::string field, std::string reason)
        : Error("robot '" + robot + "': " + field + ": " + reason),
          field_(std::move(field)),
          reason_(std::move(reason)) {}
    [[nodiscard]] const std::string& field() const { return field_; }
    [[nodiscard]] const std::string& reason() const { return reason_; }

private:
    std::string field_, reason_;
};

/// Plausibility range of the positive parameters (SI), so that no product in the model
/// overflows or loses all precision:
///   lengths (base_side, platform_side, link_length, stroke)  [1e-6, 1e3] m
///   masses                                                   [1e-6, 1e6] kg
///   moments of inertia                                       [1e-15, 1e12] kg m^2
///   peak_force                                               [1e-3, 1e9] N
///   max_condition                                            (1, 1e300]
/// link_com lies in [0, link_length].
namespace parameter_limits {
inline constexpr double kMinLength = 1e-6, kMaxLength = 1e3;
inline constexpr double kMinMass = 1e-6, kMaxMass = 1e6;
inline constexpr double kMinInertia = 1e-15, kMaxInertia = 1e12;
inline constexpr double kMinForce = 1e-3, kMaxForce = 1e9;
inline constexpr double kMaxCondition = 1e300;
}  // namespace parameter_limits

/// Throws nocdyn::ParameterError naming the field and the reason when the parameters are not
/// physical: a value outside its plausibility range above (NaN included), link_com outside
/// [0, link_length], or a robot that cannot be assembled at its reference posture
/// (0 < d_j^M < l must hold there).
void validate(const RobotParameters& robot);

/// The short form as a general description: limb j has a P joint
/// along e_j through A_j's reference position (actuated; limits +-stroke/2, peak force), an R
/// joint at A_j and an R joint at M_j; body 1 is the slider (c.o.m. at A_j, no rotational
/// inertia: it only translates), body 2 the link (c.o.m. l_c from A_j); home is the reference
/// posture (theta = 0, C = O). Validates the parameters first.
[[nodiscard]] RobotDescription expand(const RobotParameters& robot);

}  // namespace nocdyn::io
