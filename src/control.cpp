// Computed-torque and PD control of the 3-PRR, plants, closed-loop simulation (see the header).
#include "nocdyn/control.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"
#include "nocdyn/prr3/sampling.hpp"

namespace nocdyn::control {

Status desiredMotion(const prr3::Model& model, prr3::Data& data, const PoseTrajectory& trajectory, double t,
                     Reference& reference) {
    trajectory.evaluate(t, reference.p, reference.dp, reference.ddp);
    if (const Status status = prr3::inverseDisplacement(model, data, reference.p); !status) return status;
    if (const Status status = prr3::velocityFromPlatformTwist(model, data, reference.dp); !status) return status;
    prr3::twistShaping(model, data);
    prr3::actuatorAccelerations(data, reference.ddp);  // d/dt of eq. 5
    reference.u = data.u;
    reference.du = data.du;
    reference.ddu = data.ddu;
    return {};
}

Gains criticallyDamped(double natural_frequency) {
    const double w = 2.0 * std::numbers::pi * natural_frequency;
    return {JointVector::Constant(w * w), JointVector::Constant(2.0 * w)};
}

Gains equivalentPdGains(const prr3::Model& model, const Gains& computed_torque) {
    prr3::Data data;
    (void)prr3::inverseDynamics(model, data, Pose::Zero(), Twist::Zero(), Twist::Zero());
    const JointVector inertia = data.I.diagonal();
    return {inertia.cwiseProduct(computed_torque.kp), inertia.cwiseProduct(computed_torque.kd)};
}

ComputedTorqueController::ComputedTorqueController(const prr3::Model& model, const Gains& gains)
    : model_(model), gains_(gains) {}

void ComputedTorqueController::reset(const Pose& p) { pose_ = p; }

Status ComputedTorqueController::compute(const JointVector& u, const JointVector& du, const Reference& reference,
                                         JointVector& tau) {
    // I(u), C(u, du): tracker -> velocity -> shaping -> dynamics stages
    if (const Status status = prr3::trackPose(model_, data_, u, pose_); !status) return status;
    if (const Status status = prr3::velocityFromActuatorRates(model_, data_, du); !status) return status;
    prr3::twistShaping(model_, data_);
    prr3::jointSpaceDynamics(model_, data_);
    // tau = I (ddu_d + K_d e' + K_p e) + C du   (eq. 20 with the servo acceleration)
    const JointVector servo =
        reference.ddu + gains_.kd.cwiseProduct(reference.du - du) + gains_.kp.cwiseProduct(reference.u - u);
    tau.noalias() = data_.I * servo;
    tau.noalias() += data_.C * du;
    return {};
}

Status PdController::compute(const JointVector& u, const JointVector& du, const Reference& reference,
                             JointVector& tau) {
    tau = gains_.kp.cwiseProduct(reference.u - u) + gains_.kd.cwiseProduct(reference.du - du);
    return {};
}

SimulatorPlant::SimulatorPlant(const prr3::Model& model, const prr3::SimulatorOptions& options)
    : simulator_(model, options) {}

void SimulatorPlant::reset(const Pose& p, const Twist& dp) {
    if (const Status status = simulator_.reset(p, dp); !status) {
        throw Error("plant reset: " + describe(status, simulator_.model().parameters));
    }
    tau_.setZero();
}

void SimulatorPlant::advance(double dt) {
    if (const Status status = simulator_.advance(dt, tau_); !status) {
        std::ostringstream out;
        out.precision(9);
        out << "plant: t = " << simulator_.time() << " s: " << describe(status, simulator_.model().parameters);
        throw Error(out.str());
    }
}

ClosedLoopResult runClosedLoop(Controller& controller, const prr3::Model& controller_model, Plant& plant,
                               const PoseTrajectory& trajectory, const ClosedLoopOptions& options) {
    const std::vector<double> times = prr3::sampleTimes(options.duration, options.rate);
    // The reference must not alias at the controller rate, nor leave the workspace between ticks.
    prr3::requireRateAboveNyquist(trajectory, options.rate);
    prr3::requireReachable(controller_model, trajectory, times.back());
    const double dt = 1.0 / options.rate;
    ClosedLoopResult result;
    result.controller = controller.name();
    result.plant = plant.name();
    for (auto* v : {&result.p, &result.p_d}) v->reserve(times.size());
    for (auto* v : {&result.u, &result.u_d, &result.du, &result.tau}) v->reserve(times.size());
    result.t.reserve(times.size());

    prr3::Data data;
    Reference reference;
    auto fail = [&](double t, const Status& status, const char* what) {
        std::ostringstream out;
        out.precision(9);
        out << "t = " << t << " s: " << what << ": " << describe(status, controller_model.parameters);
        throw Error(out.str());
    };
    if (const Status status = desiredMotion(controller_model, data, trajectory, 0.0, reference); !status) {
        fail(0.0, status, "reference");
    }
    plant.reset(reference.p, reference.dp);
    controller.reset(reference.p);

    std::mt19937 rng(options.seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    JointVector tau;
    for (const double t : times) {
        if (const Status status = desiredMotion(controller_model, data, trajectory, t, reference); !status) {
            fail(t, status, "reference");
        }
        const JointVector u = plant.u();
        const JointVector du = plant.du();
        JointVector u_measured = u, du_measured = du;
        for (int j = 0; j < prr3::kDof; ++j) {
            if (options.noise_u > 0.0) u_measured(j) += options.noise_u * normal(rng);
            if (options.noise_du > 0.0) du_measured(j) += options.noise_du * normal(rng);
        }
        if (const Status status = controller.compute(u_measured, du_measured, reference, tau); !status) {
            fail(t, status, "controller");
        }
        if (options.peak_force > 0.0) {
            const JointVector clipped = tau.cwiseMax(-options.peak_force).cwiseMin(options.peak_force);
            if (clipped != tau) ++result.saturated_ticks;
            tau = clipped;
        }
        result.t.push_back(t);
        result.p.push_back(plant.pose());
        result.p_d.push_back(reference.p);
        result.u.push_back(u);
        result.u_d.push_back(reference.u);
        result.du.push_back(du);
        result.tau.push_back(tau);
        plant.setForces(tau);
        plant.advance(dt);
    }

    const double n = static_cast<double>(result.t.size());
    for (std::size_t k = 0; k < result.t.size(); ++k) {
        const JointVector e = result.u_d[k] - result.u[k];
        result.rms_error += e.cwiseAbs2();
        result.peak_error = result.peak_error.cwiseMax(e.cwiseAbs());
        const Vector3 e_p = result.p_d[k] - result.p[k];
        result.pose_rms_error += e_p.cwiseAbs2();
        result.pose_peak_error = result.pose_peak_error.cwiseMax(e_p.cwiseAbs());
    }
    result.rms_error = (result.rms_error / n).cwiseSqrt();
    result.pose_rms_error = (result.pose_rms_error / n).cwiseSqrt();
    return result;
}

io::Table toTable(const ClosedLoopResult& result) {
    io::Table table;
    table.columns = {"t",    "x",    "y",    "theta", "x_d", "y_d", "theta_d", "u1",   "u2",  "u3",
                     "u1_d", "u2_d", "u3_d", "e1",    "e2",  "e3",  "tau1",    "tau2", "tau3"};
    table.rows.reserve(result.t.size());
    for (std::size_t k = 0; k < result.t.size(); ++k) {
        const Pose& p = result.p[k];
        const Pose& q = result.p_d[k];
        const JointVector& u = result.u[k];
        const JointVector& d = result.u_d[k];
        const JointVector& f = result.tau[k];
        table.rows.push_back({result.t[k], p(1), p(2), p(0), q(1), q(2), q(0), u(0), u(1), u(2), d(0), d(1), d(2),
                              d(0) - u(0), d(1) - u(1), d(2) - u(2), f(0), f(1), f(2)});
    }
    return table;
}

RobotParameters withPayload(RobotParameters robot, double mass, double inertia) {
    if (!(mass >= 0.0) || !(inertia >= 0.0) || !std::isfinite(mass) || !std::isfinite(inertia)) {
        throw Error("payload: mass and inertia must be finite and >= 0");
    }
    robot.platform_mass += mass;
    robot.platform_inertia += inertia;
    if (mass > 0.0 || inertia > 0.0) robot.name += " + payload";
    return robot;
}

}  // namespace nocdyn::control
