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

#include "nocdyn/detail/eigen_instances.hpp"
#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

namespace {

// the columns of z = [s; w]: state s (24, and 6 more for the lumped plant's [p_r, dp_r]),
// input w (12, after the states)
constexpr int kBaseStates = 24, kInputs = 12;
enum Slot : int { P = 0, DP = 3, RB = 6, Y = 9, PH = 12, VH = 15, CORR = 18, CP = 21, PR = 24, DPR = 27 };
// the inputs' offsets within w
enum InputSlot : int { AR = 0, DPD = 3, PD = 6, E = 9 };

using Rows = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// Where each quantity sits in z = [s; w] for a loop of `states` states.
struct Layout {
    int states = kBaseStates;
    [[nodiscard]] int all() const { return states + kInputs; }
    [[nodiscard]] Rows pick(int column) const {
        Rows r = Rows::Zero(3, all());
        r.middleCols<3>(column).setIdentity();
        return r;
    }
    [[nodiscard]] Rows state(Slot slot) const { return pick(slot); }
    [[nodiscard]] Rows input(InputSlot slot) const { return pick(states + slot); }
};

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

/// The lumped compliant plant driven through its drives' set points (closed_loop.hpp): state
/// [p, dp, p_r, dp_r], input tau. Without a drive of stiffness, the lumped model itself
/// (its inputs are all forces).
StateSpace lumpedLoopPlant(const Model& plant_model, Data& data, const Pose& p, const ActuatorVector& tau,
                           const StateSpace& rigid) {
    const StiffnessModel compliance(plant_model);
    if (!compliance.any) {
        throw Error(
            "shake loop: the lumped plant needs compliance in the robot file (joint or drive stiffness, "
            "elastic links)");
    }
    StateSpace lumped, image;
    if (const Status status = linearizeCompliant(plant_model, compliance, data, p, Twist::Zero(), tau,
                                                 LinearOutput::platform_acceleration, lumped);
        !status) {
        throw Error("shake loop: plant: " + describe(status, plant_model));
    }
    const bool positions = std::any_of(lumped.inputs.begin(), lumped.inputs.end(),
                                       [](LinearInput input) { return input == LinearInput::commanded_position; });
    if (!positions) return lumped;
    // u_c = A_p S p_r: the set points of the rigid image (linearize's "actuators" output C)
    if (const Status status =
            linearize(plant_model, data, p, Twist::Zero(), tau, LinearOutput::actuator_variables, image);
        !status) {
        throw Error("shake loop: plant: " + describe(status, plant_model));
    }
    const Eigen::Index n = lumped.B.cols();
    Eigen::MatrixXd position_inputs = Eigen::MatrixXd::Zero(n, n), force_inputs = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index a = 0; a < n; ++a) {
        (lumped.inputs[static_cast<std::size_t>(a)] == LinearInput::commanded_position ? position_inputs
                                                                                       : force_inputs)(a, a) = 1.0;
    }
    StateSpace out;
    out.output = LinearOutput::platform_acceleration;
    out.inputs.assign(static_cast<std::size_t>(n), LinearInput::force);
    out.A = Eigen::MatrixXd::Zero(12, 12);
    out.A.topLeftCorner<6, 6>() = lumped.A;
    out.A.block(0, 6, 6, 6) = lumped.B * position_inputs * image.C;
    out.A.bottomRightCorner<6, 6>() = rigid.A;
    out.B = Eigen::MatrixXd::Zero(12, n);
    out.B.topRows<6>() = lumped.B * force_inputs;
    out.B.bottomRows<6>() = rigid.B;
    return out;
}

}  // namespace

ShakeLoopLinearization linearizeShakeLoop(const Model& model, const Model& plant_model, const Pose& p,
                                          const ShakeLoopOptions& options, LoopDerivatives derivatives, double step,
                                          LoopPlant plant_kind) {
    const TableSensors& sensors = options.sensors;
    if (!(options.rate > 0.0) || !std::isfinite(options.rate)) throw Error("shake loop: the rate must be positive");
    const double T = 1.0 / options.rate;
    const int n = model.actuators;
    if (plant_model.actuators != n) throw Error("shake loop: the plant and the controller's model differ in actuators");
    if (!(step > 0.0 && step < 1e-2)) throw Error("shake loop: the difference step must be in (0, 0.01)");
    if (plant_kind == LoopPlant::lumped && derivatives != LoopDerivatives::exact) {
        throw Error("shake loop: the lumped plant is linearised by exact derivatives only");
    }

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
    if (plant_kind == LoopPlant::lumped) plant = lumpedLoopPlant(plant_model, plant_data, p, tau_plant, plant);
    const auto m = static_cast<int>(plant.A.rows());  // the plant's states: 6 or 12
    Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(m + n, m + n);
    augmented.topLeftCorner(m, m) = plant.A * T;
    augmented.topRightCorner(m, n) = plant.B * T;
    const Eigen::MatrixXd exponential = augmented.exp();
    const Eigen::MatrixXd Phi = exponential.topLeftCorner(m, m), Gamma = exponential.topRightCorner(m, n);
    const Layout layout{kBaseStates + (m - 6)};
    const auto pick = [&](Slot slot) { return layout.state(slot); };
    const auto input = [&](InputSlot slot) { return layout.input(slot); };

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
    const Vector3 sigma_q = encoderPoseNoise(model, p, sensors.noise_u);
    const Vector3 sigma_y = sensors.accelerometer() ? accelerometerNoise(sensors) : Vector3::Constant(1e3);
    const PoseEstimator estimator(T, sigma_q, sigma_y);
    Vector3 Kq, Kv;
    for (int i = 0; i < 3; ++i) {
        Kq(i) = estimator.gain(i)(0);
        Kv(i) = estimator.gain(i)(1);
    }
    const double beta = 1.0 - std::exp(-2.0 * std::numbers::pi * sensors.accel_bandwidth * T);
    const double g = sensors.accelerometer() ? options.acceleration_gain : 0.0;
    const TaskGains gains = taskCriticallyDamped(options.natural_frequency);

    // one tick, in runShakeLoop's order; every quantity is a linear map of z = [s; w]
    // accelerometers: y = y + beta ((dp - dp_(k-1)) / T - y)
    const Rows y = sensors.accelerometer() ? Rows(pick(Y) + beta * ((pick(DP) - pick(RB)) / T - pick(Y))) : pick(Y);
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
        input(AR) + gains.kp.asDiagonal() * (input(PD) - p_hat) + gains.kd.asDiagonal() * (input(DPD) - v_hat);
    const Rows demand = commanded + correction + input(E);
    const Eigen::MatrixXd tau =
        Eigen::MatrixXd(law.d_p) * p_hat + Eigen::MatrixXd(law.d_dp) * v_hat + Eigen::MatrixXd(law.d_ddp) * demand;
    // the plant over the tick under the held forces
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(m, layout.all());
    x.topRows<3>() = pick(P);
    x.middleRows<3>(3) = pick(DP);
    if (m == 12) {
        x.middleRows<3>(6) = pick(PR);
        x.middleRows<3>(9) = pick(DPR);
    }
    const Eigen::MatrixXd x_next = Phi * x + Gamma * tau;

    Eigen::MatrixXd next(layout.states, layout.all());
    next.topRows(kBaseStates) << x_next.topRows<6>(), pick(DP), y, p_hat, v_hat, correction, commanded;
    if (m == 12) next.bottomRows<6>() = x_next.bottomRows<6>();
    const Eigen::MatrixXd achieved = (x_next.middleRows<3>(3) - pick(DP)) / T;

    ShakeLoopLinearization out;
    out.dt = T;
    out.F = next.leftCols(layout.states);
    out.G = next.rightCols<kInputs>();
    out.C = achieved.leftCols(layout.states);
    out.D = achieved.rightCols<kInputs>();
    out.demand_s = demand.leftCols(layout.states);
    out.demand_w = demand.rightCols<kInputs>();
    out.plant_states = m;
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
    const Eigen::Index states = loop.F.rows();
    const auto lu = (z * Eigen::MatrixXcd::Identity(states, states) - loop.F.cast<Complex>()).partialPivLu();
    // inputs per unit of each axis: the reference (columns 0-2) and the injection (3-5)
    Eigen::MatrixXcd W = Eigen::MatrixXcd::Zero(kInputs, 6);
    for (int i = 0; i < 3; ++i) {
        const Complex dp_d = T / (z - 1.0);
        W(AR + i, i) = 1.0;
        W(DPD + i, i) = dp_d;
        W(PD + i, i) = dp_d / Complex(0.0, w);
        W(E + i, 3 + i) = 1.0;
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
            // padded to a square with zero rows, whose singular values are those of the PBH
            // matrix and m zeros after them: no QR preconditioner is compiled for the rectangle
            const Eigen::Index m = loop.G.cols();
            Eigen::MatrixXcd pbh = Eigen::MatrixXcd::Zero(n + m, n + m);
            pbh.topRows(n) << lambda(i) * Eigen::MatrixXcd::Identity(n, n) - loop.F.cast<std::complex<double>>(),
                loop.G.cast<std::complex<double>>();
            const Eigen::JacobiSVD<Eigen::MatrixXcd, Eigen::NoQRPreconditioner> svd(pbh);
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
            if (k == 0) {
                r.phase_deg(k, i) = anchoredPhase(r.phase_deg(k, i));
                r.loop_phase_deg(k, i) = anchoredPhase(r.loop_phase_deg(k, i));
            } else {
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

ShakeLoopBand shakeLoopBand(const ShakeLoopLinearization& loop, const ShakeLoopFrequencyResponse& response,
                            double amplification) {
    if (!(amplification > 1.0) || !std::isfinite(amplification)) {
        throw Error("shake loop: the amplification limit must be above 1");
    }
    ShakeLoopBand out;
    out.amplification = amplification;
    const std::vector<double>& f = response.frequency;
    const auto rows = static_cast<Eigen::Index>(f.size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out.end.setConstant(nan);
    out.peak_db.setConstant(nan);
    out.peak_frequency.setConstant(nan);
    if (rows == 0) return out;
    const double limit_db = 20.0 * std::log10(amplification);
    for (int i = 0; i < 3; ++i) {
        Eigen::Index peak = 0;
        response.magnitude_db.col(i).maxCoeff(&peak);
        out.peak_db(i) = response.magnitude_db(peak, i);
        out.peak_frequency(i) = f[static_cast<std::size_t>(peak)];
        const auto outside = [&](double gain) { return gain > amplification || gain < 1.0 / amplification; };
        for (Eigen::Index k = 0; k < rows; ++k) {
            if (!(std::abs(response.magnitude_db(k, i)) > limit_db)) continue;
            if (k == 0) {
                out.end(i) = 0.0;
                break;
            }
            // the crossing between grid points k - 1 (inside) and k (outside), by bisection in log f
            double below = std::log(f[static_cast<std::size_t>(k - 1)]),
                   above = std::log(f[static_cast<std::size_t>(k)]);
            for (int it = 0; it < 60; ++it) {
                const double mid = 0.5 * (below + above);
                (outside(std::abs(shakeLoopResponse(loop, std::exp(mid)).closed_loop(i, i))) ? above : below) = mid;
            }
            out.end(i) = std::exp(below);
            break;
        }
    }
    return out;
}

}  // namespace nocdyn
