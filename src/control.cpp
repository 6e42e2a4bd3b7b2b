// Computed-torque and PD control in actuator space, plants, closed-loop simulation (see the header).
#include "nocdyn/control.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/sampling.hpp"

namespace nocdyn::control {

namespace {

constexpr int kActuators = 3;

void requireThreeActuators(const Model& model, const char* what) {
    if (model.actuators != kActuators) {
        throw Error(std::string(what) + ": actuator-space control needs three actuators, the robot has " +
                    std::to_string(model.actuators) + " (use the task-space PoseController)");
    }
}

}  // namespace

Status desiredMotion(const Model& model, Data& data, const PoseTrajectory& trajectory, double t, Reference& reference) {
    trajectory.evaluate(t, reference.p, reference.dp, reference.ddp);
    if (const Status status = inverseDisplacement(model, data, reference.p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model, data, reference.dp); !status) return status;
    accelerationFromPlatform(model, data, reference.ddp);  // d/dt of eq. 5
    reference.u = data.u;
    reference.du = data.du;
    reference.ddu = data.ddu;
    return {};
}

Gains criticallyDamped(double natural_frequency) {
    const double w = 2.0 * std::numbers::pi * natural_frequency;
    return {JointVector::Constant(w * w), JointVector::Constant(2.0 * w)};
}

Gains equivalentPdGains(const Model& model, const Gains& computed_torque) {
    requireThreeActuators(model, "PD gains");
    Data data(model);
    (void)inverseDynamics(model, data, model.home, Twist::Zero(), Twist::Zero());
    const JointVector inertia = data.I.diagonal();
    return {inertia.cwiseProduct(computed_torque.kp), inertia.cwiseProduct(computed_torque.kd)};
}

ComputedTorqueController::ComputedTorqueController(const Model& model, const Gains& gains)
    : model_(model), gains_(gains), data_(model_), u_(kActuators), du_(kActuators) {
    requireThreeActuators(model_, "computed-torque controller");
}

void ComputedTorqueController::reset(const Pose& p) { pose_ = p; }

Status ComputedTorqueController::compute(const JointVector& u, const JointVector& du, const Reference& reference,
                                         JointVector& tau) {
    // I(u), C(u, du): tracker -> velocity -> shaping -> dynamics stages
    u_ = u;
    du_ = du;
    if (const Status status = trackPose(model_, data_, u_, pose_); !status) return status;
    if (const Status status = velocityFromActuatorRates(model_, data_, du_); !status) return status;
    twistShaping(model_, data_);
    jointSpaceDynamics(model_, data_);
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

SimulatorPlant::SimulatorPlant(const Model& model, const SimulatorOptions& options) : simulator_(model, options) {
    requireThreeActuators(model, "plant");
}

void SimulatorPlant::reset(const Pose& p, const Twist& dp) {
    if (const Status status = simulator_.reset(p, dp); !status) {
        throw Error("plant reset: " + describe(status, simulator_.model()));
    }
    tau_.setZero();
}

void SimulatorPlant::advance(double dt) {
    const ActuatorVector tau = tau_;
    if (const Status status = simulator_.advance(dt, tau); !status) {
        std::ostringstream out;
        out.precision(9);
        out << "plant: t = " << simulator_.time() << " s: " << describe(status, simulator_.model());
        throw Error(out.str());
    }
}

ClosedLoopResult runClosedLoop(Controller& controller, const Model& controller_model, Plant& plant,
                               const PoseTrajectory& trajectory, const ClosedLoopOptions& options) {
    requireThreeActuators(controller_model, "closed loop");
    const std::vector<double> times = sampleTimes(options.duration, options.rate);
    // The reference must not alias at the controller rate, nor leave the workspace between ticks.
    requireRateAboveNyquist(trajectory, options.rate);
    requireReachable(controller_model, trajectory, times.back());
    const double dt = 1.0 / options.rate;
    ClosedLoopResult result;
    result.controller = controller.name();
    result.plant = plant.name();
    for (auto* v : {&result.p, &result.p_d}) v->reserve(times.size());
    for (auto* v : {&result.u, &result.u_d, &result.du, &result.tau}) v->reserve(times.size());
    result.t.reserve(times.size());

    Data data(controller_model);
    Reference reference;
    auto fail = [&](double t, const Status& status, const char* what) {
        std::ostringstream out;
        out.precision(9);
        out << "t = " << t << " s: " << what << ": " << describe(status, controller_model);
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
        for (int j = 0; j < kActuators; ++j) {
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
