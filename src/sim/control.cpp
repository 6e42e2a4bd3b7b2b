// Task-space computed-torque and PD control of any robot, plants, closed-loop simulation
// (see the header).
#include "nocdyn/sim/control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Cholesky>

#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/analysis/sampling.hpp"

#include "loop.hpp"

namespace nocdyn {

namespace {

/// tau = minimum-norm solution of A_p^T tau = Q with A_p = A S(c) (n x 3, full column rank at
/// a regular pose): A_p (A_p^T A_p)^-1 Q, which is A_p^-T Q for n = 3. Needs the velocity stage.
void minimumNormForces(const Model& model, const Data& data, const Vector3& Q, ActuatorVector& tau) {
    tau.resize(model.actuators);
    if (model.task_dimension == 2) {
        // translation: A_p E = the x, y columns of A (S(c) E = [0; I]), tau = A_E (A_E^T A_E)^-1 E^T Q
        Matrix2 G = Matrix2::Zero();
        for (int a = 0; a < model.actuators; ++a)
            G.noalias() += data.A.row(a).tail<2>().transpose() * data.A.row(a).tail<2>();
        const Vector2 lambda = G.ldlt().solve(Q.tail<2>());
        for (int a = 0; a < model.actuators; ++a) tau(a) = data.A.row(a).tail<2>().dot(lambda);
        return;
    }
    const double cx = data.p(1), cy = data.p(2);
    Matrix3 G = Matrix3::Zero();  // A_p^T A_p
    for (int a = 0; a < model.actuators; ++a) {
        const Vector3 row = data.A.row(a).transpose();
        // row of A_p = row of A times S(c), S(c) = [1 0 0; c_y 1 0; -c_x 0 1]
        const Vector3 r(row(0) + cy * row(1) - cx * row(2), row(1), row(2));
        G.noalias() += r * r.transpose();
    }
    const Vector3 lambda = G.ldlt().solve(Q);
    for (int a = 0; a < model.actuators; ++a) {
        const Vector3 row = data.A.row(a).transpose();
        tau(a) = (row(0) + cy * row(1) - cx * row(2)) * lambda(0) + row(1) * lambda(1) + row(2) * lambda(2);
    }
}

/// The pose and its rate as a robot without a pose sensor measures them: u and du of the
/// plant's encoders (du from its pose rate at its pose, as a tachometer gives it) plus noise,
/// the pose by the tracker, dp/dt from A_p(p) dp/dt = du by the normal equations; u: the
/// encoder readings (noise included). Throws
/// nocdyn::Error "t = ... s: ..." when the tracker loses the mode.
void measureThroughEncoders(const Model& model, Data& sensor, PoseTracker& tracker,
                            const TrackerOptions& tracker_options, const RobotPlant& plant, const Pose& p,
                            const Twist& dp, const PoseLoopOptions& options, std::mt19937& rng,
                            std::normal_distribution<double>& normal, double t, ActuatorVector& u, Pose& p_measured,
                            Twist& dp_measured, int& max_iterations) {
    const int n = model.actuators;
    const auto fail = [&](const Status& status, const char* what) { detail::failTick(model, t, status, what); };
    // the encoder rates: du = A xi_P at the plant's pose
    if (const Status status = inverseDisplacement(model, sensor, p); !status) fail(status, "plant pose");
    if (const Status status = velocityFromPlatformTwist(model, sensor, dp); !status) fail(status, "plant pose");
    ActuatorVector du = sensor.du;
    u = plant.u();
    for (int a = 0; a < n; ++a) {
        if (options.noise_u > 0.0) u(a) += options.noise_u * normal(rng);
        if (options.noise_du > 0.0) du(a) += options.noise_du * normal(rng);
    }
    TrackerReport report;
    if (const Status status = tracker.step(model, sensor, u, tracker_options, &report); !status) {
        fail(status, "direct kinematics of the encoders (tracker)");
    }
    max_iterations = std::max(max_iterations, report.iterations);
    p_measured = tracker.pose();
    // dp/dt from du = A S(c) dp/dt at the measured pose (least squares: noisy rates of a redundant
    // robot need not be consistent, so any residual is accepted)
    if (const Status status = velocityFromActuatorRatesLeastSquares(model, sensor, du, dp_measured,
                                                                    std::numeric_limits<double>::infinity());
        !status) {
        fail(status, "measured pose");
    }
}

/// runPoseLoop's sensing: the plant's state itself, plus white noise, or the encoders through
/// the tracker (options.encoders); the controller tracks the reference.
class PoseSensing final : public detail::LoopSensing {
public:
    PoseSensing(const Model& model, const PoseLoopOptions& options, const Pose& start, PoseLoopResult& result)
        : model_(model),
          options_(options),
          result_(result),
          rng_(options.seed),
          noise_(options.noise_angle, options.noise_position, options.noise_position),
          sensor_(model),
          tracker_(start),
          tracker_options_(options.encoders ? noisyEncoderTrackerOptions(model, options.noise_u) : TrackerOptions{}),
          u_measured_(model.actuators) {}

    void sense(double t, const RobotPlant& plant, const Pose& p, const Twist& dp, const PoseReference& reference,
               const Twist& ddp_ff, detail::Sensed& out) override {
        out.command = reference;
        out.command.ddp = ddp_ff;
        out.p = p;
        out.dp = dp;
        out.u_measured = nullptr;
        if (options_.encoders) {
            measureThroughEncoders(model_, sensor_, tracker_, tracker_options_, plant, p, dp, options_, rng_, normal_,
                                   t, u_measured_, out.p, out.dp, result_.tracker_max_iterations);
            out.u_measured = &u_measured_;
        } else {
            for (int i = 0; i < 3; ++i) {
                if (noise_(i) > 0.0) out.p(i) += noise_(i) * normal_(rng_);
                if (options_.noise_rate > 0.0) out.dp(i) += options_.noise_rate * normal_(rng_);
            }
        }
        const Vector3 e_measured = (out.p - p).cwiseAbs();
        measurement_sq_ += e_measured.cwiseAbs2();
        result_.measurement_peak_error = result_.measurement_peak_error.cwiseMax(e_measured);
    }
    [[nodiscard]] bool readsEncoders() const override { return options_.encoders; }
    /// sum over the ticks of (p_measured - p)^2
    [[nodiscard]] const Vector3& measurementSquares() const { return measurement_sq_; }

private:
    const Model& model_;
    const PoseLoopOptions& options_;
    PoseLoopResult& result_;
    std::mt19937 rng_;
    std::normal_distribution<double> normal_{0.0, 1.0};
    Vector3 noise_;
    Data sensor_;
    PoseTracker tracker_;
    TrackerOptions tracker_options_;
    ActuatorVector u_measured_;
    Vector3 measurement_sq_ = Vector3::Zero();
};

}  // namespace

Status poseReference(const Model& model, Data& data, const PoseTrajectory& trajectory, double t,
                     PoseReference& reference) {
    trajectory.evaluate(t, reference.p, reference.dp, reference.ddp);
    if (const Status status = inverseDisplacement(model, data, reference.p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model, data, reference.dp); !status) return status;
    reference.u = data.u;
    reference.du = data.du;
    return {};
}

TaskGains taskCriticallyDamped(double natural_frequency) {
    const double w = 2.0 * std::numbers::pi * natural_frequency;
    return {Vector3::Constant(w * w), Vector3::Constant(2.0 * w)};
}

PoseController::PoseController(const Model& model, ControlLaw law, const TaskGains& gains)
    : model_(model), data_(model_), law_(law), gains_(gains) {
    effort_.resize(model_.actuators);
    for (int a = 0; a < model_.actuators; ++a) {
        const auto limb = static_cast<std::size_t>(model_.actuator_limb[static_cast<std::size_t>(a)]);
        const auto joint = static_cast<std::size_t>(model_.actuator_joint[static_cast<std::size_t>(a)]);
        effort_(a) = model_.limb[limb].limits[joint].effort;
    }
    // M_p at home, the constant inertia that scales the PD gains
    Status status = inverseDisplacement(model_, data_, model_.home);
    if (status) status = velocityFromPlatformTwist(model_, data_, Twist::Zero());
    if (!status) throw Error("controller: home pose: " + describe(status, model_));
    platformDynamics(model_, data_);
    M_home_ = data_.M_p;
}

Status PoseController::compute(const Pose& p, const Twist& dp, const PoseReference& reference, ActuatorVector& tau) {
    const Vector3 servo = gains_.kp.cwiseProduct(reference.p - p) + gains_.kd.cwiseProduct(reference.dp - dp);
    if (law_ == ControlLaw::computed_torque) {
        // A_p^T tau = M_p ddp_cmd + h_p: the inverse dynamics at the measured state (eq. 20,
        // minimum norm when redundant)
        const Twist ddp_cmd = reference.ddp + servo;
        if (const Status status = inverseDynamicsFast(model_, data_, p, dp, ddp_cmd); !status) return status;
        tau = data_.tau;
        return {};
    }
    if (const Status status = inverseDisplacement(model_, data_, p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model_, data_, dp); !status) return status;
    const Vector3 Q = M_home_ * servo;
    minimumNormForces(model_, data_, Q, tau);
    return {};
}

bool PoseController::saturate(ActuatorVector& tau) const {
    bool clipped = false;
    for (int a = 0; a < model_.actuators; ++a) {
        const double limit = effort_(a);
        if (!std::isfinite(limit)) continue;
        if (tau(a) > limit) {
            tau(a) = limit;
            clipped = true;
        } else if (tau(a) < -limit) {
            tau(a) = -limit;
            clipped = true;
        }
    }
    return clipped;
}

RobotDescription withPayload(RobotDescription robot, const Payload& payload) {
    if (!std::isfinite(payload.mass) || !std::isfinite(payload.inertia) || !payload.com.allFinite() ||
        payload.mass < 0.0 || payload.inertia < 0.0) {
        throw Error("payload: mass and inertia must be finite and >= 0, the c.o.m. finite");
    }
    if (payload.mass == 0.0 && payload.inertia == 0.0) return robot;
    PlatformDescription& platform = robot.platform;
    const double mass = platform.mass + payload.mass;
    const Vector2 com = mass > 0.0 ? Vector2((platform.mass * platform.com + payload.mass * payload.com) / mass)
                                   : Vector2(platform.com);
    // inertia about the combined c.o.m. (parallel-axis theorem)
    platform.inertia += platform.mass * (platform.com - com).squaredNorm() + payload.inertia +
                        payload.mass * (payload.com - com).squaredNorm();
    platform.mass = mass;
    platform.com = com;
    robot.name += " + payload";
    return robot;
}

TrackerOptions noisyEncoderTrackerOptions(const Model& model, double noise_u) {
    // redundant robots: noisy encoders are inconsistent by about noise_u (scaled)
    double inv_scale = 0.0;
    for (int a = 0; a < model.actuators; ++a) {
        const auto aa = static_cast<std::size_t>(a);
        inv_scale = std::max(inv_scale, model.limb[static_cast<std::size_t>(model.actuator_limb[aa])]
                                            .inv_joint_scale[static_cast<std::size_t>(model.actuator_joint[aa])]);
    }
    TrackerOptions options;
    options.max_residual = std::max(options.max_residual, 10.0 * noise_u * inv_scale);
    return options;
}

void summarizeLoop(PoseLoopResult& result) {
    const auto un = static_cast<std::size_t>(result.actuators);
    result.rms_error.assign(un, 0.0);
    result.peak_error.assign(un, 0.0);
    result.peak_tau.assign(un, 0.0);
    result.pose_rms_error.setZero();
    result.pose_peak_error.setZero();
    result.pose_late_peak_error.setZero();
    if (result.t.empty()) return;
    const std::size_t half = result.t.size() / 2;
    // a run that kept only t, p and p_d (ShakeLoopOptions::keep_actuators) has its actuator
    // summaries from the loop
    const bool actuators = result.u.size() == result.t.size() && result.u_d.size() == result.t.size() &&
                           result.tau.size() == result.t.size();
    for (std::size_t k = 0; k < result.t.size(); ++k) {
        const Vector3 e_p = (result.p_d[k] - result.p[k]).cwiseAbs();
        result.pose_rms_error += e_p.cwiseAbs2();
        result.pose_peak_error = result.pose_peak_error.cwiseMax(e_p);
        if (k >= half) result.pose_late_peak_error = result.pose_late_peak_error.cwiseMax(e_p);
        for (std::size_t a = 0; a < (actuators ? un : 0); ++a) {
            const auto ai = static_cast<Eigen::Index>(a);
            const double e = std::abs(result.u_d[k](ai) - result.u[k](ai));
            result.rms_error[a] += e * e;
            result.peak_error[a] = std::max(result.peak_error[a], e);
            result.peak_tau[a] = std::max(result.peak_tau[a], std::abs(result.tau[k](ai)));
        }
    }
    const double count = static_cast<double>(result.t.size());
    result.pose_rms_error = (result.pose_rms_error / count).cwiseSqrt();
    for (double& e : result.rms_error) e = std::sqrt(e / count);
}

PoseLoopResult runPoseLoop(PoseController& controller, RobotPlant& plant, const PoseTrajectory& trajectory,
                           const PoseLoopOptions& options, const Pose* start) {
    const Model& model = controller.model();
    const std::vector<double> times = sampleTimes(options.duration, options.rate);
    requireRateAboveNyquist(trajectory, options.rate);
    requireReachable(model, trajectory, times.back());
    PoseLoopResult result;
    result.controller = name(controller.law());
    result.plant = plant.name();
    result.actuators = model.actuators;

    Data data(model);
    PoseReference reference;
    if (const Status status = poseReference(model, data, trajectory, 0.0, reference); !status) {
        detail::failTick(model, 0.0, status, "reference");
    }
    plant.reset(start != nullptr ? *start : reference.p, reference.dp);
    // encoders: the tracker from the plant's start (the working mode it starts in)
    PoseSensing sensing(model, options, start != nullptr ? *start : reference.p, result);
    detail::runTicks(controller, plant, trajectory, times, data, sensing, options, {}, result);
    result.measurement_rms_error = (sensing.measurementSquares() / static_cast<double>(result.t.size())).cwiseSqrt();
    return result;
}

}  // namespace nocdyn
