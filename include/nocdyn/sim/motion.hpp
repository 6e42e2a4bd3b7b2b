// The motion of an identification experiment: what the sensors logged (actuator positions and
// forces), and the platform's pose, rates and accelerations reconstructed from it by the
// direct-kinematics tracker and a zero-phase low-pass (filter.hpp).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "nocdyn/model.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification_options.hpp"

namespace nocdyn {

/// What a logger recorded: time, actuator positions and forces (rows = samples, columns =
/// actuators in file order); du and ddu when measured or known (else empty).
struct Measurements {
    std::vector<double> t;
    Eigen::MatrixXd u, tau, du, ddu;
    /// What tau is: false, the force at each sample's instant (a force sensor's reading); true,
    /// the command applied from each sample until the next (zero-order hold, as sensorLog and
    /// `nocdyn control --log` give it; a log names these columns tau{a}_held).
    bool held_forces = false;
};

/// Motion from the measurements: the platform pose by the direct-kinematics tracker (PoseTracker), its rates
/// from du (ddu) as given or by zero-phase low-pass filtering and differentiating u (tau is then
/// filtered alike). Throws nocdyn::Error naming the sample time on a lost tracker or a singular
/// posture, and on too few samples or a non-monotonic time.
struct Motion {
    std::vector<double> t;
    std::vector<Pose> p;
    std::vector<Twist> dp, ddp;
    Eigen::MatrixXd tau;
    /// The zero-phase low-pass u and tau went through [Hz] and the sampling rate [Hz]; 0 when
    /// the rates were given. The regressor's Coulomb friction columns (sign q', a step at every
    /// reversal) then go through the same filter, as the force's friction part did.
    double cutoff = 0.0, rate = 0.0;
};
[[nodiscard]] Motion reconstructMotion(const Model& model, const Measurements& data,
                                       const IdentificationOptions& options = {});

/// The experiment's log as the sensors see it: t, u and tau of a closed-loop run, du and ddu
/// left empty. u: when the run measured through its encoders (run.u_measured), their readings,
/// the very draws the controller used (noise_u is then not drawn again); else the plant's u
/// plus Gaussian encoder noise of std. dev. noise_u (each actuator's unit). tau: the applied
/// force plus Gaussian force-measurement noise noise_tau (the force sensor's alone).
[[nodiscard]] Measurements sensorLog(const PoseLoopResult& run, double noise_u, double noise_tau, unsigned seed = 1);

}  // namespace nocdyn
