// The shake-table loop linearised, and its frequency response (closed_loop.hpp).
#include "nocdyn/sim/closed_loop.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <Eigen/LU>
#include <unsupported/Eigen/MatrixFunctions>

#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

namespace {

// the columns of z = [s; w]: state s (24), input w (12)
constexpr int kStates = 24, kInputs = 12, kAll = kStates + kInputs;
enum Slot : int {
    P = 0,
    DP = 3,
    RB = 6,
    Y = 9,
    PH = 12,
    VH = 15,
    CORR = 18,
    CP = 21,
    AR = 24,
    DPD = 27,
    PD = 30,
    E = 33
};

using Rows = Eigen::Matrix<double, 3, kAll>;

Rows pick(Slot slot) {
    Rows r = Rows::Zero();
    r.middleCols<3>(slot).setIdentity();
    return r;
}

/// d2p/dt2 = f(p, dp, tau) by forwardDynamics; throws naming the plant.
Twist plantAcceleration(const Model& model, Data& data, const Pose& p, const Twist& dp, const ActuatorVector& tau) {
    if (const Status status = forwardDynamics(model, data, p, dp, tau); !status) {
        throw Error("shake loop: plant: " + describe(status, model));
    }
    return data.t_M_dot;
}

/// The plant's A and B (linearization.hpp) at rest by central differences of f.
StateSpace differencedPlant(const Model& model, Data& data, const Pose& p, const ActuatorVector& tau, double h) {
    const int n = model.actuators;
    StateSpace out;
    out.output = LinearOutput::platform_acceleration;
    out.inputs.assign(static_cast<std::size_t>(n), LinearInput::force);
    out.A = Eigen::MatrixXd::Zero(6, 6);
    out.A.topRightCorner<3, 3>().setIdentity();
    out.B = Eigen::MatrixXd::Zero(6, n);
    for (int i = 0; i < 3; ++i) {
        const Vector3 e = Vector3::Unit(i) * h;
        out.A.block<3, 1>(3, i) = (plantAcceleration(model, data, p + e, Twist::Zero(), tau) -
                                   plantAcceleration(model, data, p - e, Twist::Zero(), tau)) /
                                  (2.0 * h);
        out.A.block<3, 1>(3, 3 + i) =
            (plantAcceleration(model, data, p, e, tau) - plantAcceleration(model, data, p, -e, tau)) / (2.0 * h);
    }
    for (int a = 0; a < n; ++a) {
        const double ha = h * std::max(1.0, std::abs(tau(a)));
        ActuatorVector plus = tau, minus = tau;
        plus(a) += ha;
        minus(a) -= ha;
        out.B.block<3, 1>(3, a) = (plantAcceleration(model, data, p, Twist::Zero(), plus) -
                                   plantAcceleration(model, data, p, Twist::Zero(), minus)) /
                                  (2.0 * ha);
    }
    out.C = out.A.bottomRows<3>();
    out.D = out.B.bottomRows<3>();
    return out;
}

/// tau = ID(p, dp, ddp) by inverseDynamics; throws naming the controller.
ActuatorVector lawForces(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp) {
    if (const Status status = inverseDynamics(model, data, p, dp, ddp); !status) {
        throw Error("shake loop: controller: " + describe(status, model));
    }
    return data.tau;
}

/// d tau / d(p, dp, ddp) at rest by central differences of the inverse dynamics.
InverseDynamicsDerivatives differencedLaw(const Model& model, Data& data, const Pose& p, double h) {
    const int n = model.actuators;
    InverseDynamicsDerivatives out;
    out.tau = lawForces(model, data, p, Twist::Zero(), Twist::Zero());
    out.d_p.resize(n, 3);
    out.d_dp.resize(n, 3);
    out.d_ddp.resize(n, 3);
    const Twist zero = Twist::Zero();
    for (int i = 0; i < 3; ++i) {
        const Vector3 e = Vector3::Unit(i) * h;
        out.d_p.col(i) =
            (lawForces(model, data, p + e, zero, zero) - lawForces(model, data, p - e, zero, zero)) / (2.0 * h);
        out.d_dp.col(i) = (lawForces(model, data, p, e, zero) - lawForces(model, data, p, -e, zero)) / (2.0 * h);
        out.d_ddp.col(i) = (lawForces(model, data, p, zero, e) - lawForces(model, data, p, zero, -e)) / (2.0 * h);
    }
    return out;
}

}  // namespace

ShakeLoopLinearization linearizeShakeLoop(const Model& model, const Model& plant_model, const Pose& p,
                                          const ShakeLoopOptions& options, LoopDerivatives derivatives, double step) {
    const TableSensors& sensors = options.sensors;
    if (!(options.rate > 0.0) || !std::isfinite(options.rate)) throw Error("shake loop: the rate must be positive");
    const double T = 1.0 / options.rate;
    const int n = model.actuators;
    if (plant_model.actuators != n) throw Error("shake loop: the plant and the controller's model differ in actuators");
    if (!(step > 0.0 && step < 1e-2)) throw Error("shake loop: the difference step must be in (0, 0.01)");

    // the plant at rest at p, held by its own forces, discretised exactly under a zero-order hold
    Data plant_data(plant_model);
    if (const Status status = inverseDynamics(plant_model, plant_data, p, Twist::Zero(), Twist::Zero()); !status) {
        throw Error("shake loop: plant: " + describe(status, plant_model));
    }
    const ActuatorVector tau_plant = plant_data.tau;
    StateSpace plant;
    if (derivatives == LoopDerivatives::exact) {
        if (const Status status = linearize(plant_model, plant_data, p, Twist::Zero(), tau_plant,
                                            LinearOutput::platform_acceleration, plant);
            !status) {
            throw Error("shake loop: plant: " + describe(status, plant_model));
        }
    } else {
        plant = differencedPlant(plant_model, plant_data, p, tau_plant, step);
    }
    Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(6 + n, 6 + n);
    augmented.topLeftCorner(6, 6) = plant.A * T;
    augmented.topRightCorner(6, n) = plant.B * T;
    const Eigen::MatrixXd exponential = augmented.exp();
    const Eigen::MatrixXd Phi = exponential.topLeftCorner(6, 6), Gamma = exponential.topRightCorner(6, n);

    // the control law tau = ID(p^, v^, demand) of the controller's model, to first order
    Data data(model);
    InverseDynamicsDerivatives law;
    if (derivatives == LoopDerivatives::exact) {
        if (const Status status = inverseDynamicsDerivatives(model, data, p, Twist::Zero(), Twist::Zero(), law);
            !status) {
            throw Error("shake loop: controller: " + describe(status, model));
        }
    } else {
        law = differencedLaw(model, data, p, step);
    }

    // the estimator's steady-state gains and the sensors, as runShakeLoop sets them
    const Vector3 sigma_q = encoderPoseNoise(model, p, sensors.encoder_noise);
    const Vector3 sigma_y = sensors.accelerometer ? accelerometerNoise(sensors) : Vector3::Constant(1e3);
    const PoseEstimator estimator(T, sigma_q, sigma_y);
    Vector3 Kq, Kv;
    for (int i = 0; i < 3; ++i) {
        Kq(i) = estimator.gain(i)(0);
        Kv(i) = estimator.gain(i)(1);
    }
    const double beta = 1.0 - std::exp(-2.0 * std::numbers::pi * sensors.accel_bandwidth * T);
    const double g = sensors.accelerometer ? options.acceleration_gain : 0.0;
    const TaskGains gains = taskCriticallyDamped(options.natural_frequency);

    // one tick, in runShakeLoop's order; every quantity is a linear map of z = [s; w]
    // accelerometers: y = y + beta ((dp - dp_(k-1)) / T - y)
    const Rows y = sensors.accelerometer ? Rows(pick(Y) + beta * ((pick(DP) - pick(RB)) / T - pick(Y))) : pick(Y);
    // estimator: predict x = F x + G y, correct with the encoder pose q_m = p
    const Rows p_pred = pick(PH) + T * pick(VH) + 0.5 * T * T * y;
    const Rows v_pred = pick(VH) + T * y;
    const Rows innovation = pick(P) - p_pred;
    const Rows p_hat = p_pred + Kq.asDiagonal() * innovation;
    const Rows v_hat = v_pred + Kv.asDiagonal() * innovation;
    // correction c = c + g (ddp_cmd,(k-1) - c_(k-1) - y): commanded holds ddp_cmd - c
    const Rows correction = pick(CORR) + g * (pick(CP) - y);
    // ddp_cmd = a_r + K_p (p_d - p^) + K_d (dp_d - v^), the demand ddp_cmd + c (+ e)
    const Rows commanded =
        pick(AR) + gains.kp.asDiagonal() * (pick(PD) - p_hat) + gains.kd.asDiagonal() * (pick(DPD) - v_hat);
    const Rows demand = commanded + correction + pick(E);
    const Eigen::MatrixXd tau =
        Eigen::MatrixXd(law.d_p) * p_hat + Eigen::MatrixXd(law.d_dp) * v_hat + Eigen::MatrixXd(law.d_ddp) * demand;
    // the plant over the tick under the held forces
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(6, kAll);
    x.topRows<3>() = pick(P);
    x.bottomRows<3>() = pick(DP);
    const Eigen::MatrixXd x_next = Phi * x + Gamma * tau;

    Eigen::MatrixXd next(kStates, kAll);
    next << x_next, pick(DP), y, p_hat, v_hat, correction, commanded;
    const Eigen::MatrixXd achieved = (x_next.bottomRows<3>() - pick(DP)) / T;

    ShakeLoopLinearization out;
    out.dt = T;
    out.F = next.leftCols<kStates>();
    out.G = next.rightCols<kInputs>();
    out.C = achieved.leftCols<kStates>();
    out.D = achieved.rightCols<kInputs>();
    out.demand_s = demand.leftCols<kStates>();
    out.demand_w = demand.rightCols<kInputs>();
    return out;
}

ShakeLoopResponse shakeLoopResponse(const ShakeLoopLinearization& loop, double frequency) {
    using Complex = std::complex<double>;
    const double T = loop.dt;
    if (!(frequency > 0.0 && frequency < 0.5 / T)) {
        throw Error("shake loop: the frequency must be in (0, rate / 2): " + text::format("%f", frequency) + " Hz");
    }
    const double w = 2.0 * std::numbers::pi * frequency;
    const Complex z = std::exp(Complex(0.0, w * T));
    const Eigen::MatrixXcd Gc = loop.G.cast<Complex>();
    const auto lu = (z * Eigen::MatrixXcd::Identity(kStates, kStates) - loop.F.cast<Complex>()).partialPivLu();
    // inputs per unit of each axis: the reference (columns 0-2) and the injection (3-5)
    Eigen::MatrixXcd W = Eigen::MatrixXcd::Zero(kInputs, 6);
    for (int i = 0; i < 3; ++i) {
        const Complex dp_d = T / (z - 1.0);
        W(AR - kStates + i, i) = 1.0;
        W(DPD - kStates + i, i) = dp_d;
        W(PD - kStates + i, i) = dp_d / Complex(0.0, w);
        W(E - kStates + i, 3 + i) = 1.0;
    }
    const Eigen::MatrixXcd S = lu.solve(Gc * W);
    ShakeLoopResponse r;
    r.closed_loop = (loop.C.cast<Complex>() * S.leftCols<3>() + loop.D.cast<Complex>() * W.leftCols<3>());
    const Eigen::MatrixXcd demand =
        loop.demand_s.cast<Complex>() * S.rightCols<3>() + loop.demand_w.cast<Complex>() * W.rightCols<3>();
    // what returns to the break point is the demand less the injection
    for (int i = 0; i < 3; ++i) r.loop(i) = -(demand(i, i) - 1.0) / demand(i, i);
    return r;
}

double shakeLoopSpectralRadius(const ShakeLoopLinearization& loop) {
    const Eigen::Index n = loop.F.rows();
    if (n == 0) return 0.0;
    const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(loop.F, false).eigenvalues();
    const double scale = std::max({1.0, loop.F.norm(), loop.G.norm()});
    double radius = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
        const double r = std::abs(lambda(i));
        // a state the loop only holds (|lambda| = 1) that no input reaches, by the PBH test
        // rank [lambda I - F, G] < n (the acceleration correction's sum at gain 0, with the last
        // command it feeds): it stays at rest and is no mode of the response
        if (std::abs(r - 1.0) < 1e-9) {
            Eigen::MatrixXcd pbh(n, n + loop.G.cols());
            pbh << lambda(i) * Eigen::MatrixXcd::Identity(n, n) - loop.F.cast<std::complex<double>>(),
                loop.G.cast<std::complex<double>>();
            const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(pbh);
            if (svd.singularValues()(n - 1) <= 1e-9 * scale) continue;
        }
        radius = std::max(radius, r);
    }
    return radius;
}

ShakeLoopFrequencyResponse shakeLoopFrequencyResponse(const ShakeLoopLinearization& loop,
                                                      const std::vector<double>& frequencies) {
    ShakeLoopFrequencyResponse r;
    r.frequency = frequencies;
    const auto rows = static_cast<Eigen::Index>(frequencies.size());
    for (auto* m : {&r.magnitude_db, &r.phase_deg, &r.loop_magnitude_db, &r.loop_phase_deg}) m->resize(rows, 3);
    const auto unwrap = [](double phase, double previous) {
        return phase + 360.0 * std::round((previous - phase) / 360.0);
    };
    for (Eigen::Index k = 0; k < rows; ++k) {
        const double f = frequencies[static_cast<std::size_t>(k)];
        if (k > 0 && !(f > frequencies[static_cast<std::size_t>(k - 1)])) {
            throw Error("shake loop: the frequencies must be increasing");
        }
        const ShakeLoopResponse h = shakeLoopResponse(loop, f);
        for (int i = 0; i < 3; ++i) {
            const double deg = 180.0 / std::numbers::pi;
            r.magnitude_db(k, i) = 20.0 * std::log10(std::abs(h.closed_loop(i, i)));
            r.phase_deg(k, i) = std::arg(h.closed_loop(i, i)) * deg;
            r.loop_magnitude_db(k, i) = 20.0 * std::log10(std::abs(h.loop(i)));
            r.loop_phase_deg(k, i) = std::arg(h.loop(i)) * deg;
            if (k > 0) {
                r.phase_deg(k, i) = unwrap(r.phase_deg(k, i), r.phase_deg(k - 1, i));
                r.loop_phase_deg(k, i) = unwrap(r.loop_phase_deg(k, i), r.loop_phase_deg(k - 1, i));
            }
        }
    }
    FrequencyResponse diagonal;
    diagonal.frequency = frequencies;
    diagonal.magnitude_db = r.magnitude_db;
    diagonal.phase_deg = r.phase_deg;
    diagonal.outputs = 1;
    diagonal.inputs = 3;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int i = 0; i < 3; ++i) {
        r.bandwidth(i) = bandwidth3dB(diagonal, 0, i);
        r.crossover(i) = nan;
        r.phase_margin(i) = nan;
        // the first grid interval where |L| falls through 1, refined by bisection in log f
        for (Eigen::Index k = 1; k < rows; ++k) {
            if (!(r.loop_magnitude_db(k - 1, i) >= 0.0 && r.loop_magnitude_db(k, i) < 0.0)) continue;
            double a = std::log(frequencies[static_cast<std::size_t>(k - 1)]);
            double b = std::log(frequencies[static_cast<std::size_t>(k)]);
            for (int it = 0; it < 60; ++it) {
                const double m = 0.5 * (a + b);
                (std::abs(shakeLoopResponse(loop, std::exp(m)).loop(i)) >= 1.0 ? a : b) = m;
            }
            const double fc = std::exp(0.5 * (a + b));
            const double phase = unwrap(std::arg(shakeLoopResponse(loop, fc).loop(i)) * 180.0 / std::numbers::pi,
                                        r.loop_phase_deg(k - 1, i));
            r.crossover(i) = fc;
            const double margin = 180.0 + phase;
            r.phase_margin(i) = margin - 360.0 * std::round(margin / 360.0);
            break;
        }
    }
    return r;
}

}  // namespace nocdyn
