// A platform payload's 10 inertial parameters identified on a six-DOF table (spatial_payload.hpp).
#include "nocdyn/sim/spatial_payload.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "nocdyn/error.hpp"
#include "nocdyn/sim/spatial_shake.hpp"
#include "nocdyn/sim/spatial_simulator.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::spatial {

namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Wrenches = Eigen::Matrix<double, 6, kPayloadParameters>;  // Y_w

/// S(r) = |r|^2 1 - r r^T: the inertia of a unit point mass at r about the origin.
Eigen::Matrix3d shift(const Eigen::Vector3d& r) {
    return r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose();
}

/// L(v): I v = L(v) [I_xx, I_yy, I_zz, I_xy, I_xz, I_yz].
Eigen::Matrix<double, 3, 6> inertiaMap(const Eigen::Vector3d& v) {
    Eigen::Matrix<double, 3, 6> L;
    L << v.x(), 0.0, 0.0, v.y(), v.z(), 0.0,  //
        0.0, v.y(), 0.0, v.x(), 0.0, v.z(),   //
        0.0, 0.0, v.z(), 0.0, v.x(), v.y();
    return L;
}

Eigen::Matrix<double, 6, 1> entries(const Eigen::Matrix3d& I) {
    Eigen::Matrix<double, 6, 1> e;
    e << I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2);
    return e;
}

Eigen::Matrix3d tensor(const Eigen::Matrix<double, 6, 1>& e) {
    Eigen::Matrix3d I;
    I << e(0), e(3), e(4), e(3), e(1), e(5), e(4), e(5), e(2);
    return I;
}

bool finite(const SpatialPayload& p) { return std::isfinite(p.mass) && p.com.allFinite() && p.inertia.allFinite(); }

/// The force sensor's sigma [N or N m]: finite and >= 0.
void checkForceNoise(double sigma) {
    if (!(sigma >= 0.0) || !std::isfinite(sigma)) throw Error("force noise: expected a finite value >= 0");
}

}  // namespace

const std::array<const char*, kPayloadParameters>& payloadParameterNames() {
    static constexpr std::array<const char*, kPayloadParameters> kNames = {"m",    "mc_x", "mc_y", "mc_z", "I_xx",
                                                                           "I_yy", "I_zz", "I_xy", "I_xz", "I_yz"};
    return kNames;
}

PayloadVector payloadParameters(const SpatialPayload& payload) {
    PayloadVector pi;
    pi(0) = payload.mass;
    pi.segment<3>(1) = payload.mass * payload.com;
    pi.tail<6>() = entries(payload.inertia + payload.mass * shift(payload.com));  // I_P = I_c + m S(c)
    return pi;
}

SpatialPayload payloadOf(const PayloadVector& pi) {
    if (!(pi(0) > 0.0)) throw Error("payload: the mass " + text::number(pi(0)) + " kg is not positive");
    SpatialPayload p;
    p.mass = pi(0);
    p.com = pi.segment<3>(1) / pi(0);
    p.inertia = tensor(pi.tail<6>()) - p.mass * shift(p.com);
    return p;
}

SpatialRobotDescription withPayload(SpatialRobotDescription description, const SpatialPayload& payload) {
    if (!finite(payload)) throw Error("payload: a value is not finite");
    SpatialBodyDescription& b = description.platform;
    const double total = b.mass + payload.mass;
    if (!(total > 0.0))
        throw Error("payload: the platform's mass with it, " + text::number(total) + " kg, is not positive");
    // the combined c.o.m. and the inertia about it (parallel axes)
    const Eigen::Vector3d c = (b.mass * b.com + payload.mass * payload.com) / total;
    b.inertia = b.inertia + b.mass * shift(b.com - c) + payload.inertia + payload.mass * shift(payload.com - c);
    b.com = c;
    b.mass = total;
    return description;
}

Status payloadRegressor(const Model& model, Data& data, const TaskVector& p, const TaskVector& dp,
                        const TaskVector& ddp, PayloadRegressor& Y) {
    if (model.task_dimension != 6) return {StatusCode::not_finite, -1, static_cast<double>(model.task_dimension)};
    if (const Status status = inverseDynamics(model, data, p, dp, ddp); !status) return status;
    const Eigen::Matrix3d& R = data.R;
    const Eigen::Vector3d r = data.position;
    const Eigen::Vector3d w = data.t_P.head<3>(), dw = data.dt_P.head<3>();
    // the velocity and acceleration of the platform's point P (t_P's linear part is O's)
    const Eigen::Vector3d v_P = data.t_P.tail<3>() + w.cross(r);
    const Eigen::Vector3d a_P = data.dt_P.tail<3>() + dw.cross(r) + w.cross(v_P);
    // in the platform frame
    const Eigen::Vector3d omega = R.transpose() * w, alpha = R.transpose() * dw;
    const Eigen::Vector3d b = R.transpose() * (a_P - model.gravity);
    const Eigen::Matrix3d W = skew(omega);
    Wrenches local = Wrenches::Zero();  // [n_P; f] per parameter, platform frame
    local.block<3, 1>(3, 0) = b;
    local.block<3, 3>(0, 1) = -skew(b);
    local.block<3, 3>(3, 1) = skew(alpha) + W * W;
    local.block<3, 6>(0, 4) = inertiaMap(alpha) + W * inertiaMap(omega);
    // referred to O in the base frame: [R n_P + r x R f; R f]
    Wrenches Yw;
    Yw.bottomRows<3>().noalias() = R * local.bottomRows<3>();
    Yw.topRows<3>().noalias() = R * local.topRows<3>();
    Yw.topRows<3>().noalias() += skew(r) * Yw.bottomRows<3>();
    // through the NOC as inverseDynamics takes W_P: tau = A_E (A_E^T A_E)^-1 Y_w
    const ActuationMatrix AE = data.A.rightCols(6);
    const Matrix6 gram = AE.transpose() * AE;
    const Wrenches lambda = Eigen::PartialPivLU<Matrix6>(gram).solve(Yw);
    Y.noalias() = AE * lambda;
    if (!Y.allFinite()) return {StatusCode::singular_actuation, -1, Y.sum()};
    return {};
}

Trajectory payloadExcitation(const Model& model, const PayloadExcitationOptions& options, LimitUse* use) {
    if (model.task_dimension != 6) throw Error(model.name + ": a six-DOF robot (motion: full) is needed");
    if (!(options.duration > 0.0) || options.harmonics < 1)
        throw Error("excitation: duration and harmonics must be positive");
    constexpr double kRotationLength = 0.5;  // [m] a rotation of 1 rad weighs as 0.5 m
    const double f0 = 1.0 / options.duration;
    std::mt19937 rng(options.seed);
    std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
    Trajectory shape;
    shape.name = "payload excitation";
    shape.dimension = 6;
    shape.duration = options.duration;
    for (int i = 0; i < 6; ++i) {
        AxisMotion& axis = shape.axis[static_cast<std::size_t>(i)];
        axis.offset = model.home(i);
        const double unit = i < 3 ? 1.0 : 1.0 / kRotationLength;
        for (int k = 0; k < options.harmonics; ++k) {
            const double f = f0 * (i + 1 + 6 * k);
            axis.harmonics.push_back({unit / (2.0 * std::numbers::pi * f), f, phase(rng)});  // 1 m/s (rad/s) each
        }
    }
    const double step = 1.0 / std::max(options.loop.rate, 200.0);
    const auto scaled = [&](double c) {
        Trajectory t = shape;
        for (AxisMotion& axis : t.axis) {
            for (Harmonic& h : axis.harmonics) h.amplitude *= c;
        }
        return t;
    };
    const auto usage = [&](double c) { return limitUse(model, scaled(c), options.duration, step, options.margin); };
    // the largest factor that fits: geometric bisection on [1e-6, 1]
    double lo = 1e-6, hi = 1.0;
    if (const LimitUse u = usage(lo); !(u.ratio <= 1.0))
        throw Error("excitation: does not fit even at amplitude 1e-6: " + u.what + " at " + text::sampleTime(u.t));
    if (usage(hi).ratio <= 1.0) lo = hi;
    for (int k = 0; k < 60 && hi - lo > 1e-3 * lo; ++k) {
        const double mid = std::sqrt(lo * hi);
        (usage(mid).ratio <= 1.0 ? lo : hi) = mid;
    }
    if (use != nullptr) *use = usage(lo);
    return scaled(lo);
}

PayloadLog excitePayload(const Model& plant_model, const Model& controller_model, const Trajectory& trajectory,
                         const PayloadExcitationOptions& options) {
    checkForceNoise(options.force_noise);  // before the run, not after it
    if (plant_model.task_dimension != controller_model.task_dimension ||
        plant_model.actuators != controller_model.actuators)
        throw Error("excitation: the controller's model and the plant differ in structure");
    const int d = plant_model.task_dimension;
    const double dt = 1.0 / options.loop.rate, w = 2.0 * std::numbers::pi * options.loop.natural_frequency;
    const double kp = w * w, kd = 2.0 * w;
    const auto ticks = static_cast<std::size_t>(std::llround(options.duration * options.loop.rate));
    const auto fail = [](double t, const Status& status, const Model& model, const char* what) {
        throw Error(text::sampleTime(t) + ": " + what + ": " + describe(status, model));
    };
    TaskVector p_d, dp_d, ddp_d, p_next, dp_next, ddp_next, p(d), dp(d), cmd(d), ddp(d);
    trajectory.evaluate(0.0, p_d, dp_d, ddp_d);
    Simulator plant(plant_model, options.loop.simulator);
    if (const Status status = plant.reset(p_d, dp_d); !status) fail(0.0, status, plant_model, "the excitation's start");
    Data controller(controller_model), sensor(plant_model);
    PayloadLog log;
    for (auto* v : {&log.p, &log.dp, &log.ddp}) v->reserve(ticks);
    log.t.reserve(ticks);
    log.tau.reserve(ticks);
    for (std::size_t k = 0; k < ticks; ++k) {
        const double t = static_cast<double>(k) * dt;
        if (options.loop.progress) options.loop.progress(t);
        trajectory.evaluate(t, p_d, dp_d, ddp_d);
        trajectory.evaluate(t + dt, p_next, dp_next, ddp_next);
        p = plant.pose();
        dp = plant.poseRate();
        // computed torque on the robot alone (the payload unknown), as LoopOptions::mid_hold
        cmd = (dp_next - dp_d) / dt + kd * (dp_d - dp) + kp * (p_d - p);
        TaskVector p_c = p, dp_c = dp;
        if (options.loop.mid_hold) {
            p_c += (0.5 * dt) * dp + (0.125 * dt * dt) * cmd;
            dp_c += (0.5 * dt) * cmd;
        }
        if (const Status status = inverseDynamics(controller_model, controller, p_c, dp_c, cmd); !status)
            fail(t, status, controller_model, "the controller");
        const ActuatorVector tau = controller.tau;
        // what the table measures: the state, its acceleration under the held forces, the forces
        if (const Status status = forwardDynamics(plant_model, sensor, p, dp, tau, ddp); !status)
            fail(t, status, plant_model, "the plant");
        log.t.push_back(t);
        log.p.push_back(p);
        log.dp.push_back(dp);
        log.ddp.push_back(ddp);
        log.tau.push_back(tau);
        plant.setForces(nocdyn::ActuatorVector(tau));
        if (const Status status = plant.advance(dt); !status) fail(plant.time(), status, plant_model, "the plant");
    }
    return withForceNoise(std::move(log), options.force_noise, options.seed);
}

PayloadLog withForceNoise(PayloadLog log, double sigma, unsigned seed) {
    checkForceNoise(sigma);
    if (sigma == 0.0) return log;
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma);
    for (ActuatorVector& tau : log.tau) {
        for (Eigen::Index a = 0; a < tau.size(); ++a) tau(a) += noise(rng);
    }
    return log;
}

SpatialPayloadEstimate identifySpatialPayload(const Model& model, const PayloadLog& log) {
    if (model.task_dimension != 6) throw Error(model.name + ": a six-DOF robot (motion: full) is needed");
    const std::size_t samples = log.p.size();
    if (samples < 2 || log.dp.size() != samples || log.ddp.size() != samples || log.tau.size() != samples)
        throw Error("payload log: at least 2 samples of p, dp, ddp and tau are needed");
    const int n = model.actuators;
    const auto rows = static_cast<Eigen::Index>(samples) * n;
    Eigen::MatrixXd A(rows, kPayloadParameters);
    Eigen::VectorXd b(rows);
    Data data(model);
    PayloadRegressor Y(n, kPayloadParameters);
    for (std::size_t s = 0; s < samples; ++s) {
        if (log.tau[s].size() != n || !log.tau[s].allFinite())
            throw Error("payload log: sample " + std::to_string(s + 1) + ": the forces are not " + std::to_string(n) +
                        " finite values");
        const Status status = payloadRegressor(model, data, log.p[s], log.dp[s], log.ddp[s], Y);
        if (!status) throw Error("payload log: sample " + std::to_string(s + 1) + ": " + describe(status, model));
        const auto row = static_cast<Eigen::Index>(s) * n;
        A.middleRows(row, n) = Y;
        b.segment(row, n) = log.tau[s] - data.tau;
    }
    // column-scaled least squares by QR
    PayloadVector scale;
    for (int j = 0; j < kPayloadParameters; ++j) scale(j) = A.col(j).norm() > 0.0 ? A.col(j).norm() : 1.0;
    const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(As);
    const PayloadCovariance Rq = qr.matrixQR().topRows<kPayloadParameters>().triangularView<Eigen::Upper>();
    const Eigen::JacobiSVD<PayloadCovariance> svd(Rq);
    const double smallest = svd.singularValues()(kPayloadParameters - 1);
    SpatialPayloadEstimate out;
    out.condition = smallest > 0.0 ? svd.singularValues()(0) / smallest : std::numeric_limits<double>::infinity();
    if (!(out.condition <= 1e8)) {
        throw Error("payload: the excitation does not determine the 10 parameters (condition " +
                    text::number(out.condition) + " of the column-scaled regressor)");
    }
    const PayloadVector z = qr.solve(b).head<kPayloadParameters>();
    out.parameters = z.cwiseQuotient(scale);
    out.samples = static_cast<int>(samples);
    const Eigen::VectorXd residual = b - A * out.parameters;
    const double dof = static_cast<double>(rows - kPayloadParameters);
    out.residual_rms = std::sqrt(residual.squaredNorm() / std::max(1.0, dof));
    // s^2 (A^T A)^-1 = s^2 D^-1 (R^T R)^-1 D^-1
    const PayloadCovariance Rinv = Rq.triangularView<Eigen::Upper>().solve(PayloadCovariance::Identity());
    const PayloadCovariance N_inv = Rinv * Rinv.transpose();
    out.covariance = out.residual_rms * out.residual_rms *
                     (scale.cwiseInverse().asDiagonal() * N_inv * scale.cwiseInverse().asDiagonal());
    out.parameters_sd = out.covariance.diagonal().cwiseSqrt();
    out.payload = payloadOf(out.parameters);
    // first-order map pi -> (m, c, I_c entries): J (10 x 10)
    const double m = out.parameters(0);
    const Eigen::Vector3d h = out.parameters.segment<3>(1);
    PayloadCovariance J = PayloadCovariance::Zero();
    J(0, 0) = 1.0;
    J.block<3, 1>(1, 0) = -h / (m * m);
    J.block<3, 3>(1, 1) = Eigen::Matrix3d::Identity() / m;
    // I_c = I_P - S(h) / m
    J.block<6, 6>(4, 4).setIdentity();
    J.block<6, 1>(4, 0) = entries(shift(h)) / (m * m);
    for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
        const Eigen::Matrix3d dS = 2.0 * h(k) * Eigen::Matrix3d::Identity() - e * h.transpose() - h * e.transpose();
        J.block<6, 1>(4, 1 + k) = -entries(dS) / m;
    }
    const PayloadVector sd = (J * out.covariance * J.transpose()).diagonal().cwiseSqrt();
    out.mass_sd = sd(0);
    out.com_sd = sd.segment<3>(1);
    out.inertia_sd = tensor(sd.tail<6>());
    return out;
}

}  // namespace nocdyn::spatial
