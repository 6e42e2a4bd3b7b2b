// A rigid payload fixed to the platform of a six-DOF spatial robot (motion: full), identified from
// a short excitation as a shake table does before a test.
//
// The payload's wrench on the platform is linear in its 10 inertial parameters
//   pi = [m, m c_x, m c_y, m c_z, I_xx, I_yy, I_zz, I_xy, I_xz, I_yz]
// (c its c.o.m. and I its inertia about the platform frame's origin P, both in the platform
// frame; I = I_c + m S(c), S(r) = |r|^2 1 - r r^T). In the platform frame, with omega, alpha the
// angular velocity and acceleration and b = R^T (a_P - g) (a_P the acceleration of P):
//   f = m b + (alpha x + omega x omega x) (m c),
//   n_P = I alpha + omega x I omega + (m c) x b,
// referred to O in the base frame, w = [R n_P + r x R f; R f] = Y_w pi (6 x 10). The actuator
// forces take it through the NOC as the platform's own wrench: A_E^T tau = E^T W_P, so
//   tau(with payload) - tau(robot alone) = A_E (A_E^T A_E)^-1 Y_w pi = Y pi   (n x 10).
// Stacked over the samples of a logged motion, tau_measured - tau_robot = Y pi is solved by
// least squares, its covariance s^2 (Y^T Y)^-1 from the residuals (white force noise: the
// actuators' force sensors; the motion is measured by the encoders and the platform's
// accelerometers and gyros, taken as exact).
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/sim/shake.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/sim/spatial_control.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_description.hpp"
#include "nocdyn/spatial_trajectory.hpp"

namespace nocdyn::spatial {

inline constexpr int kPayloadParameters = 10;
using PayloadVector = Eigen::Matrix<double, kPayloadParameters, 1>;
using PayloadCovariance = Eigen::Matrix<double, kPayloadParameters, kPayloadParameters>;
/// Y: n x 10, one row per actuator.
using PayloadRegressor =
    Eigen::Matrix<double, Eigen::Dynamic, kPayloadParameters, 0, kMaxActuators, kPayloadParameters>;

/// The parameters' names in pi's order (m, mc_x, ..., I_yz).
[[nodiscard]] const std::array<const char*, kPayloadParameters>& payloadParameterNames();

/// A rigid payload in the platform frame.
struct SpatialPayload {
    double mass = 0.0;                                  ///< [kg]
    Eigen::Vector3d com = Eigen::Vector3d::Zero();      ///< [m]
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about its c.o.m. [kg m^2]
};

/// pi of a payload (the inertia carried to P by the parallel-axis theorem).
[[nodiscard]] PayloadVector payloadParameters(const SpatialPayload& payload);
/// The payload of pi: c = (m c) / m, I_c = I_P - m S(c). Throws nocdyn::Error for m <= 0.
[[nodiscard]] SpatialPayload payloadOf(const PayloadVector& pi);

/// The description with `payload` fixed to the platform (the combined mass, c.o.m. and inertia
/// about it). Throws nocdyn::Error when the combined mass is not positive or a value not finite.
[[nodiscard]] SpatialRobotDescription withPayload(SpatialRobotDescription description, const SpatialPayload& payload);

/// Inverse dynamics of the robot alone at (p, dp, ddp) (data.tau: its forces) and the payload's
/// regressor Y (see the header comment). Motion full only (else StatusCode::not_finite with
/// value d). Allocation-free.
[[nodiscard]] Status payloadRegressor(const Model& model, Data& data, const TaskVector& p, const TaskVector& dp,
                                      const TaskVector& ddp, PayloadRegressor& Y);

/// The excitation run's loop: 1 kHz, error dynamics at 30 Hz, the forces of the hold's middle.
[[nodiscard]] inline LoopOptions excitationLoop() {
    LoopOptions loop;
    loop.rate = 1000.0;
    loop.natural_frequency = 30;
    loop.mid_hold = true;
    return loop;
}

/// The excitation and its run on the simulated table.
struct PayloadExcitationOptions {
    double duration = 2.0;     ///< [s]
    int harmonics = 3;         ///< sines per pose coordinate
    double margin = 0.1;       ///< of each leg's stroke, rate and force kept free
    double force_noise = 1.0;  ///< std. dev. of each logged actuator force [N or N m]
    unsigned seed = 1;         ///< of the phases and the force noise
    /// The run on the table: its controller rate (and log samples) [Hz], the error dynamics'
    /// natural frequency [Hz], the mid-hold forces, the plant's integration and the progress
    /// callback. The run lasts `duration` and is computed torque on the robot alone, unsaturated,
    /// on the true state: the loop's duration, seed, law, saturation, sensor noise and
    /// controller model are not used.
    LoopOptions loop = excitationLoop();
};

/// A multi-sine in the six pose coordinates about home: coordinate i the sum of `harmonics`
/// sines at distinct multiples of 1 / duration (i + 1 + 6 k, k = 0, 1, ...: no two coordinates
/// share a frequency), amplitudes falling as 1 / f (equal rate per sine), seeded phases, a
/// rotation of 1 rad weighted as 0.5 m; scaled by one factor, the largest at which every leg
/// stays within (1 - margin) of its stroke, rate and force (inverse dynamics of `model`, which
/// should carry the specimen as weighed). `use` receives its limit use. Throws nocdyn::Error
/// when the robot is not a six-DOF one or no amplitude above 1e-6 fits.
[[nodiscard]] Trajectory payloadExcitation(const Model& model, const PayloadExcitationOptions& options,
                                           LimitUse* use = nullptr);

/// The table's log of a run: per controller tick the measured pose, rate, acceleration and
/// the actuator forces (with force_noise).
struct PayloadLog {
    std::vector<double> t;
    std::vector<TaskVector> p, dp, ddp;
    std::vector<ActuatorVector> tau;
};

/// `trajectory` run in computed torque: the plant the robot carrying the payload (`plant`), the
/// controller's model the robot alone (`controller`); each tick the plant's state, its
/// acceleration under the forces held (forward dynamics) and those forces plus seeded white
/// noise. Throws nocdyn::Error "t = ... s: reason" when the plant or the controller fails.
[[nodiscard]] PayloadLog excitePayload(const Model& plant, const Model& controller, const Trajectory& trajectory,
                                       const PayloadExcitationOptions& options);

/// The table's measurement of a run's forces: `log` with seeded white noise of standard deviation
/// `sigma` [N or N m] added to each force, drawn tick by tick, actuator by actuator (excitePayload
/// logs its forces so). A noise-free log (force_noise 0) measured with many seeds gives the
/// spread of the estimates over noise draws without simulating the same motion again.
[[nodiscard]] PayloadLog withForceNoise(PayloadLog log, double sigma, unsigned seed);

struct SpatialPayloadEstimate {
    SpatialPayload payload;    ///< the estimate
    PayloadVector parameters;  ///< pi
    PayloadVector parameters_sd;
    PayloadCovariance covariance;  ///< of pi
    double mass_sd = 0.0;
    Eigen::Vector3d com_sd = Eigen::Vector3d::Zero();
    Eigen::Matrix3d inertia_sd = Eigen::Matrix3d::Zero();  ///< of I_c (first order in pi)
    double residual_rms = 0.0;                             ///< s [N or N m]
    double condition = 0.0;                                ///< of the column-scaled stacked regressor
    int samples = 0;
};

/// The payload by least squares on tau_measured - tau_robot = Y pi over the log (`model` the
/// robot alone), its covariance s^2 (Y^T Y)^-1, s^2 the residuals' mean square over the N n - 10
/// degrees of freedom; the c.o.m.'s and I_c's standard deviations by the first-order map from pi.
/// Throws nocdyn::Error for fewer than 2 samples, a log of a robot that is not six-DOF, a
/// sample out of reach, a motion that does not determine the parameters (condition above 1e8),
/// or an identified mass that is not positive.
[[nodiscard]] SpatialPayloadEstimate identifySpatialPayload(const Model& model, const PayloadLog& log);

}  // namespace nocdyn::spatial
