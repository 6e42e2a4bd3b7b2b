// 3-PRR model construction: geometry of eqs. 8, 35 and 40, inertia dyads of eq. 9.
#include "nocdyn/prr3/model.hpp"

#include <numbers>

#include "nocdyn/prr3/batch.hpp"
#include "nocdyn/prr3/kinematics.hpp"

namespace nocdyn::prr3 {

Model::Model(const io::RobotParameters& robot) : parameters(robot) {
    validate(parameters);
    constexpr double pi = std::numbers::pi;
    R = parameters.baseCircumradius();
    r = parameters.platformCircumradius();
    l = parameters.link_length;
    l_c = parameters.link_com;
    // eq. 8
    phi = {0.0, 2.0 * pi / 3.0, -2.0 * pi / 3.0};
    for (int j = 0; j < kLimbs; ++j) {
        e[j] = unitVector(phi[j]);                         // eq. 40
        n[j] = perp(e[j]);                                 // points into the base triangle
        B[j] = R * unitVector(phi[j] - pi / 6.0);          // eq. 35
        M_local[j] = r * unitVector(phi[j] - pi / 6.0);    // M_j - C at theta = 0 (eq. 41)
        M[sliderBody(j)] = {0.0, parameters.slider_mass};  // sliders only translate
        M[linkBody(j)] = {parameters.link_inertia, parameters.link_mass};
    }
    M[kPlatformBody] = {parameters.platform_inertia, parameters.platform_mass};

    // u_j = 0 at the reference posture: measure where each A_j sits there.
    s_ref = {0.0, 0.0, 0.0};
    Data reference;
    // validate() has checked that the reference posture is assembled.
    (void)inverseDisplacement(*this, reference, Pose::Zero());
    for (int j = 0; j < kLimbs; ++j) s_ref[j] = reference.u(j);
    kernel = batch_detail::constants(*this);
}

}  // namespace nocdyn::prr3
