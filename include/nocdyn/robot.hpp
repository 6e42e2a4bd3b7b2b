// Robot parameters: what a robot file holds (SI units), the paper's prototype as the
// default, and their validation. See ../shared/model-notes.md for where each default
// comes from (eq. 32, Table I, footnote 6).
#pragma once

#include <string>

namespace nocdyn {

/// Parameters of a symmetric 3-limb planar parallel robot with prismatic actuators
/// (3-PRR). All values in SI: m, kg, kg m^2, N.
struct RobotParameters {
    std::string name = "paper-3prr";
    // geometry (eq. 32)
    double base_side = 0.400;          ///< b: side of the base triangle B_1 B_2 B_3 [m]
    double platform_side = 0.110;      ///< a: side of the platform triangle M_1 M_2 M_3 [m]
    double link_length = 0.15915;      ///< l: |A_j M_j| [m]
    double link_com = 0.079575;        ///< l_c: from A_j to the link's c.o.m. [m]
    // inertia (Table I)
    double slider_mass = 1.46966;      ///< moving coil + actuator plate [kg]
    double link_mass = 0.63863;        ///< [kg]
    double link_inertia = 1.5786066e-3;       ///< about the link's c.o.m. [kg m^2]
    double platform_mass = 1.75257;           ///< [kg]
    double platform_inertia = 6.17311382e-3;  ///< about C [kg m^2]
    // actuators (footnote 6)
    double stroke = 0.0249;            ///< total stroke, centred on the reference posture [m]
    double peak_force = 262.0;         ///< [N]
    // numerical limits
    double max_condition = 1.0e4;      ///< largest condition number of H or D accepted

    /// Base circumradius R = b / sqrt(3).
    [[nodiscard]] double baseCircumradius() const;
    /// Platform circumradius r = a / sqrt(3).
    [[nodiscard]] double platformCircumradius() const;
};

/// Throws nocdyn::Error naming the field and the reason when the parameters are not
/// physical: a non-positive (or non-finite) length, mass, inertia, stroke or force,
/// link_com outside [0, link_length], max_condition <= 1, or a robot that cannot be
/// assembled at its reference posture (0 < d_j^M < l must hold there).
void validate(const RobotParameters& robot);

}  // namespace nocdyn
