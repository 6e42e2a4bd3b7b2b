// Excitation design (excitation.hpp), the problem: Fourier shapes scaled to the robot's limits,
// the condition number of the stacked regressor and its exact gradient; minimised by random
// search, then Nelder-Mead or BFGS on that gradient (minimize.hpp).
#include "nocdyn/sim/excitation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <utility>

#include <Eigen/Eigenvalues>

#include "nocdyn/detail/eigen_instances.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/base_parameters.hpp"
#include "nocdyn/sim/regressor.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/status.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/detail/index.hpp"

#include "../core/limb_lanes.hpp"
#include "minimize.hpp"

namespace nocdyn {

double ExcitationLimitUse::worst() const { return std::max({range, velocity, effort, condition}); }

namespace {

constexpr double kInfeasible = std::numeric_limits<double>::infinity();
/// Geometric bisection passes on the scale: (1e4)^(2^-14), a step of 0.06 %.
constexpr int kScalePasses = 14;
constexpr double kScaleBracket = 1e-4;

using detail::at;
using detail::bfgs;
using detail::nelderMead;

/// Samples of the pose excursion from home, its rate and acceleration (at scale 1).
struct UnitMotion {
    std::vector<Twist> p, dp, ddp;
};

UnitMotion sampleTrajectory(const Model& model, const PoseTrajectory& trajectory, double period, int samples) {
    UnitMotion m;
    for (int i = 0; i < samples; ++i) {
        Pose p, dp, ddp;
        trajectory.evaluate(period * i / samples, p, dp, ddp);
        m.p.push_back(p - model.home);
        m.dp.push_back(dp);
        m.ddp.push_back(ddp);
    }
    return m;
}

/// Limit use and the stacked regressor's normal matrix along sampled motions (see the header).
class Judge {
public:
    Judge(const Model& model, const ExcitationOptions& options, std::vector<int> columns)
        : model_(model), options_(options), columns_(std::move(columns)), data_(model) {
        if (const Status status = inverseDisplacement(model, data_, model.home); !status) {
            throw Error("excitation: the home posture is not valid: " + describe(status, model));
        }
        for (int j = 0; j < model.limbs; ++j) q_home_[at(j)] = data_.limb[at(j)].q;
        allowed_ = 1.0 - options.margin;
    }

    /// Worst limit use over the samples of excursion m at scale s (infinite when a sample
    /// cannot be computed); stops at the first sample beyond 1 when `early`. With `detail`,
    /// fills the use per limit, the binding one and the failure.
    double use(const UnitMotion& m, double s, bool early, ExcitationAssessment* detail = nullptr) {
        double worst = 0.0;
        for (std::size_t i = 0; i < m.p.size(); ++i) {
            const Status status = inverseDynamics(model_, data_, model_.home + s * m.p[i], s * m.dp[i], s * m.ddp[i]);
            if (!status) {
                if (detail) detail->failure = describe(status, model_);
                return kInfeasible;
            }
            worst = std::max(worst, sampleUse(detail ? &detail->use : nullptr));
            if (early && worst > 1.0) return worst;
        }
        return worst;
    }

    /// Condition number of the column-scaled stacked regressor of m at scale s.
    double condition(const UnitMotion& m, double s) {
        const auto k = static_cast<Eigen::Index>(columns_.size());
        Eigen::MatrixXd N = Eigen::MatrixXd::Zero(k, k);
        for (std::size_t i = 0; i < m.p.size(); ++i) {
            if (!inverseDynamicsRegressor(model_, data_, model_.home + s * m.p[i], s * m.dp[i], s * m.ddp[i], Y_))
                return kInfeasible;
            for (Eigen::Index a = 0; a < k; ++a) {
                for (Eigen::Index b = 0; b <= a; ++b)
                    N(a, b) += Y_.col(columns_[at(static_cast<int>(a))]).dot(Y_.col(columns_[at(static_cast<int>(b))]));
            }
        }
        const Eigen::VectorXd d = N.diagonal();
        if (!(d.minCoeff() > 1e-24 * d.maxCoeff())) return kInfeasible;
        const Eigen::VectorXd inv = d.cwiseSqrt().cwiseInverse();
        const Eigen::MatrixXd full = N.selfadjointView<Eigen::Lower>();
        const Eigen::MatrixXd S = inv.asDiagonal() * full * inv.asDiagonal();
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(S, Eigen::EigenvaluesOnly);
        const double lo = eigen.eigenvalues()(0), hi = eigen.eigenvalues()(k - 1);
        return lo > 0.0 ? std::sqrt(hi / lo) : kInfeasible;
    }

    /// Largest scale in (0, cap] within the limits (0: none from kScaleBracket cap up).
    double largestScale(const UnitMotion& m, double cap) {
        if (use(m, cap, true) <= 1.0) return cap;
        double lo = kScaleBracket * cap, hi = cap;
        if (!(use(m, lo, true) <= 1.0)) return 0.0;
        for (int pass = 0; pass < kScalePasses; ++pass) {
            const double mid = std::sqrt(lo * hi);
            (use(m, mid, true) <= 1.0 ? lo : hi) = mid;
        }
        return lo;
    }

private:
    /// Use of the limits at the computed sample (data_), the largest returned.
    double sampleUse(ExcitationLimitUse* detail) {
        double worst = 0.0;
        for (int j = 0; j < model_.limbs; ++j) {
            const LimbModel& limb = model_.limb[at(j)];
            const LimbData& ld = data_.limb[at(j)];
            for (int k = 0; k < 3; ++k) {
                const JointLimits& lim = limb.limits[at(k)];
                const double q = ld.q(k), q0 = q_home_[at(j)](k);
                // range: the distance from home towards the limit met, of the allowed part
                const double room = q >= q0 ? lim.upper - q0 : q0 - lim.lower;
                if (std::isfinite(room)) {
                    const double r = room > 0.0 ? std::abs(q - q0) / (allowed_ * room) : kInfeasible;
                    note(detail, &ExcitationLimitUse::range, r, worst, "range of " + model_.limbName(j), k);
                }
                if (std::isfinite(lim.velocity)) {
                    note(detail, &ExcitationLimitUse::velocity, std::abs(ld.gamma_dot(k)) / (allowed_ * lim.velocity),
                         worst, "velocity of " + model_.limbName(j), k);
                }
            }
            note(detail, &ExcitationLimitUse::condition, ld.cond / options_.max_condition, worst,
                 "condition number of the Jacobian of " + model_.limbName(j), -1);
        }
        for (int a = 0; a < model_.actuators; ++a) {
            const double effort =
                model_.limb[at(model_.actuator_limb[at(a)])].limits[at(model_.actuator_joint[at(a)])].effort;
            if (std::isfinite(effort)) {
                note(detail, &ExcitationLimitUse::effort, std::abs(data_.tau(a)) / (allowed_ * effort), worst,
                     "effort of actuator " + std::to_string(a + 1) + " (" +
                         model_.limbName(model_.actuator_limb[at(a)]) + ")",
                     -1);
            }
        }
        note(detail, &ExcitationLimitUse::condition, data_.cond_A / options_.max_condition, worst,
             "condition number of the actuation (A)", -1);
        return worst;
    }

    /// Keeps the largest use; names it in `detail` (only then is the name built).
    template <typename Name>
    static void note(ExcitationLimitUse* detail, double ExcitationLimitUse::*field, double value, double& worst,
                     const Name& name, int joint) {
        worst = std::max(worst, value);
        if (!detail) return;
        if (value > detail->worst()) {
            detail->binding = name;
            if (joint >= 0) detail->binding += ", joint " + std::to_string(joint + 1);
        }
        detail->*field = std::max(detail->*field, value);
    }

    const Model& model_;
    const ExcitationOptions& options_;
    std::vector<int> columns_;
    Data data_;
    RegressorMatrix Y_;
    std::array<Vector3, kMaxLimbs> q_home_{};
    double allowed_ = 1.0;
};

/// Free Fourier coefficients (see the header) per axis: a_2..a_H, then b_3..b_H.
int freePerAxis(int H) { return 2 * H - 3; }

/// The coefficients a_k, b_k (k = 1..H) of axis `axis` from the free ones, in the axis's unit
/// (theta: rad; x, y: the model's length scale), tied so that q(0) = home, dq(0) = ddq(0) = 0.
void coefficients(const Eigen::VectorXd& z, int axis, int H, double unit, std::vector<double>& a,
                  std::vector<double>& b) {
    const int F = freePerAxis(H);
    a.assign(at(H + 1), 0.0);
    b.assign(at(H + 1), 0.0);
    double ka = 0.0, s0 = 0.0, s2 = 0.0;
    for (int k = 2; k <= H; ++k) {
        a[at(k)] = unit * z(axis * F + k - 2);
        ka += k * a[at(k)];
    }
    for (int k = 3; k <= H; ++k) {
        b[at(k)] = unit * z(axis * F + (H - 1) + k - 3);
        s0 += b[at(k)];
        s2 += k * k * b[at(k)];
    }
    a[1] = -ka;              // sum k a_k = 0
    b[2] = (s0 - s2) / 3.0;  // b_1 + b_2 = -s0, b_1 + 4 b_2 = -s2
    b[1] = -s0 - b[2];
}

/// The shape z as a trajectory at scale s: offsets at home, harmonics k f0 as a sin(. + phase).
PoseTrajectory trajectoryOf(const Model& model, const Eigen::VectorXd& z, double s, const ExcitationOptions& options,
                            double duration) {
    PoseTrajectory trajectory;
    trajectory.name = "excitation";
    trajectory.duration = duration;
    AxisMotion* axes[3] = {&trajectory.theta, &trajectory.x, &trajectory.y};
    std::vector<double> a, b;
    for (int axis = 0; axis < 3; ++axis) {
        axes[axis]->offset = model.home(axis);
        // a two-DOF robot: theta is no coordinate, it stays at home (its coefficients are inert)
        if (axis == 0 && model.task_dimension == 2) continue;
        coefficients(z, axis, options.harmonics, axis == 0 ? 1.0 : model.length_scale, a, b);
        for (int k = 1; k <= options.harmonics; ++k) {
            const double amplitude = s * std::hypot(a[at(k)], b[at(k)]);
            if (amplitude == 0.0) continue;
            // a sin x + b cos x = sqrt(a^2 + b^2) sin(x + atan2(b, a))
            axes[axis]->harmonics.push_back({amplitude, k * options.base_frequency, std::atan2(b[at(k)], a[at(k)])});
        }
    }
    return trajectory;
}

/// Peak excursion of a unit motion in the axes' units (rad, length scale).
double peakExcursion(const Model& model, const UnitMotion& m) {
    double peak = 0.0;
    for (const Twist& p : m.p)
        peak =
            std::max({peak, std::abs(p(0)), std::abs(p(1)) / model.length_scale, std::abs(p(2)) / model.length_scale});
    return peak;
}

void checkOptions(const ExcitationOptions& o, double duration) {
    const auto require = [](bool ok, const std::string& what) {
        if (!ok) throw Error("excitation: " + what);
    };
    require(o.base_frequency >= 1e-3 && o.base_frequency <= 1e3, "the base frequency must be in [0.001, 1000] Hz");
    require(o.harmonics >= 3 && o.harmonics <= 20, "the number of harmonics per axis must be in [3, 20]");
    require(o.margin >= 0.0 && o.margin <= 0.9, "the margin must be in [0, 0.9]");
    require(o.max_condition > 1.0 && o.max_condition <= 1e8, "the largest condition number must be in (1, 1e8]");
    require(o.samples == 0 || (o.samples >= 8 * o.harmonics && o.samples <= 100000),
            "the design samples per period must be 0 (automatic) or in [8 harmonics, 100000]");
    require(o.check_samples >= 8 * o.harmonics && o.check_samples <= 1000000,
            "the check samples per period must be in [8 harmonics, 1000000]");
    require(o.evaluations >= 1 && o.evaluations <= 1000000, "the evaluations must be in [1, 1000000]");
    require(o.random_shapes >= 1 && o.random_shapes <= o.evaluations,
            "the random shapes must be at least 1 and at most the evaluations");
    require(std::isfinite(duration) && duration > 0.0 && duration <= 1e6, "the duration must be in (0, 1e6] s");
    const double periods = duration * o.base_frequency;
    require(periods >= 1.0 - 1e-9 && std::abs(periods - std::round(periods)) <= 1e-6 * std::max(1.0, periods),
            "the duration " + text::format("%.9g", duration) + " s is not a whole number of base periods (" +
                text::format("%.9g", 1.0 / o.base_frequency) + " s at " + text::format("%.9g", o.base_frequency) +
                " Hz)");
}

/// Robots whose inverse dynamics give the regressor's columns and their derivatives: tau is
/// linear in pi, so with parameters pi_b (model b) tau_b = Y pi_b, and column k of Y is
/// sum_b C(k, b) tau_b whenever sum_b C(k, b) pi_b = e_k. Per body (L: the length scale), the
/// robots with only that body's parameters, [m, m c_x, m c_y, I_O] =
///   A: m 1, c 0 -> [1 0 0 0];  B: m 1, c (L, 0) -> [1 L 0 L^2];  Cy: m 1, c (0, L) -> [1 0 L L^2];
///   D: I 1 -> [0 0 0 1];
/// so e_m = A, e_I = D, e_mcx = (B - A - L^2 D) / L, e_mcy = (Cy - A - L^2 D) / L. A joint's
/// damping (Coulomb friction) column is the robot with only that damping (friction) 1: the
/// Coulomb column J_j^-T e_k sign q'_k varies with the pose through J_j^-T, its sign frozen.
class ColumnRobots {
public:
    ColumnRobots(const Model& model, const std::vector<int>& columns) {
        const auto K = static_cast<Eigen::Index>(columns.size());
        std::vector<std::pair<int, int>> body_first;  // body -> index of its robot A
        std::vector<Eigen::VectorXd> rows(at(static_cast<int>(K)));
        const double L = model.length_scale;
        for (Eigen::Index k = 0; k < K; ++k) {
            const int c = columns[at(static_cast<int>(k))];
            if (c < kBodyParameters * model.bodies) {
                const int body = c / kBodyParameters, which = c % kBodyParameters;
                int first = -1;
                for (const auto& [b, i] : body_first) {
                    if (b == body) first = i;
                }
                if (first < 0) {
                    first = static_cast<int>(models_.size());
                    body_first.emplace_back(body, first);
                    models_.push_back(bodyRobot(model, body, 1.0, Vector2::Zero(), 0.0));
                    models_.push_back(bodyRobot(model, body, 1.0, Vector2(L, 0.0), 0.0));
                    models_.push_back(bodyRobot(model, body, 1.0, Vector2(0.0, L), 0.0));
                    models_.push_back(bodyRobot(model, body, 0.0, Vector2::Zero(), 1.0));
                }
                std::vector<std::pair<int, double>> weights;
                if (which == 0) weights = {{first, 1.0}};
                if (which == 1) weights = {{first + 1, 1.0 / L}, {first, -1.0 / L}, {first + 3, -L}};
                if (which == 2) weights = {{first + 2, 1.0 / L}, {first, -1.0 / L}, {first + 3, -L}};
                if (which == 3) weights = {{first + 3, 1.0}};
                weights_.push_back(weights);
                continue;
            }
            std::vector<std::pair<int, double>> weights;
            for (int j = 0; j < model.limbs; ++j) {
                for (int joint = 0; joint < 3; ++joint) {
                    const int index = jointParameterIndex(model, j, joint);
                    if (c != index && c != index + 1) continue;
                    Model robot = emptyRobot(model);
                    (c == index ? robot.limb[at(j)].damping : robot.limb[at(j)].friction)[at(joint)] = 1.0;
                    robot.limb[at(j)].frictionless = false;
                    weights = {{static_cast<int>(models_.size()), 1.0}};
                    models_.push_back(std::move(robot));
                }
            }
            weights_.push_back(weights);
        }
        C_ = Eigen::MatrixXd::Zero(K, static_cast<Eigen::Index>(models_.size()));
        for (Eigen::Index k = 0; k < K; ++k) {
            for (const auto& [b, w] : weights_[at(static_cast<int>(k))]) C_(k, b) += w;
        }
    }

    [[nodiscard]] const std::vector<Model>& robots() const { return models_; }
    /// K x robots: column k of Y = sum_b C(k, b) tau_b.
    [[nodiscard]] const Eigen::MatrixXd& combination() const { return C_; }

private:
    /// The robot with every inertial and friction parameter zero (the geometry unchanged).
    static Model emptyRobot(const Model& model) {
        Model robot = model;
        for (int j = 0; j < model.limbs; ++j) {
            LimbModel& limb = robot.limb[at(j)];
            limb.M = {};
            limb.damping = {};
            limb.friction = {};
            limb.frictionless = true;
        }
        robot.platform_M = {};
        // the lanes keep the file's inertia; the per-limb path reads the above
        detail::ModelKernel::setLimbsInLanes(robot, false);
        return robot;
    }

    /// Only body `body` with mass m, c.o.m. c in its frame and inertia I about the c.o.m.
    static Model bodyRobot(const Model& model, int body, double m, const Vector2& c, double inertia) {
        Model robot = emptyRobot(model);
        if (body == model.platformBody()) {
            robot.platform_M = {inertia, m};
            robot.platform_com = c;
            robot.platform_com_home = Vector2(model.cos_home * c.x() - model.sin_home * c.y(),
                                              model.sin_home * c.x() + model.cos_home * c.y());
        } else {
            LimbModel& limb = robot.limb[at(body % model.limbs)];
            limb.M[at(body / model.limbs)] = {inertia, m};
            limb.com_home[at(body / model.limbs)] = c;
        }
        return robot;
    }

    std::vector<Model> models_;
    std::vector<std::vector<std::pair<int, double>>> weights_;
    Eigen::MatrixXd C_;
};

/// log cond of the column-scaled stacked regressor of a shape at a fixed scale, and its exact
/// gradient with respect to the shape (excitation.hpp, excitationConditionGradient).
class ConditionGradient {
public:
    ConditionGradient(const Model& model, const ExcitationOptions& options, std::vector<int> columns)
        : model_(model), options_(options), columns_(std::move(columns)), robots_(model, columns_), data_(model) {
        const int H = options.harmonics;
        samples_ = options.samples > 0 ? options.samples : 25 * H;
        period_ = 1.0 / options.base_frequency;
        if (const Status status = inverseDisplacement(model, data_, model.home); !status)
            throw Error("excitation: the home posture is not valid: " + describe(status, model));
        for (int j = 0; j < model.limbs; ++j) q_home_[at(j)] = data_.limb[at(j)].q;
        const auto d = static_cast<Eigen::Index>(3) * freePerAxis(H);
        // the samples are linear in the shape: those of the unit shapes e_j
        for (Eigen::Index j = 0; j < d; ++j) {
            const PoseTrajectory unit = trajectoryOf(model, Eigen::VectorXd::Unit(d, j), 1.0, options, period_);
            basis_.push_back(atRestFirst(sampleTrajectory(model, unit, period_, samples_)));
        }
    }

    /// log cond at the fixed scale s and its gradient s d log cond / d c (c = s z). With
    /// `with_scale`, the gradient of the design objective f(z) = log cond at the largest scale
    /// s(z) instead, s the scale f found: s grad_c F + (grad_c F . z) grad s(z) (scaleGradient);
    /// `scaled` tells whether the binding limit allowed it (else the fixed-scale gradient).
    double operator()(const Eigen::VectorXd& z, double s, Eigen::VectorXd& gradient, bool with_scale = false,
                      bool* scaled = nullptr) {
        const double value = fixedScale(z, s, gradient);
        if (scaled) *scaled = false;
        if (!with_scale || !std::isfinite(value)) return value;
        Eigen::VectorXd grad_s;
        if (!scaleGradient(z, s, grad_s)) return value;
        gradient += (gradient.dot(z) / s) * grad_s;
        if (scaled) *scaled = true;
        return value;
    }

    /// grad s(z) of the largest scale within the limits, from the limit that binds at the design
    /// samples at scale s: its use g(s z) = 1, so grad s = -s grad_c g / (grad_c g . z). For a
    /// joint's range (dq/dp = J_j^-1 S(c)), a joint's rate (d gamma_dot / d dp = J_j^-1 S(c),
    /// d gamma_dot / d p_e = J_j^-1 (dS_e dp - dJ_j gamma_dot) with dJ_j's columns
    /// ds_k = [xi_(k-1), s_k] for dp = e) or an actuator's effort (derivatives.hpp); false when a condition number
    /// binds (its scaled 1-norm is not differentiated) or a sample fails.
    bool scaleGradient(const Eigen::VectorXd& z, double s, Eigen::VectorXd& grad_s) {
        const UnitMotion m =
            atRestFirst(sampleTrajectory(model_, trajectoryOf(model_, z, 1.0, options_, period_), period_, samples_));
        const double allowed = 1.0 - options_.margin;
        // the binding use: kind (0 range, 1 rate, 2 effort, 3 condition), sample, limb/actuator, joint
        double worst = -1.0;
        int kind = -1, sample = -1, who = -1, joint = -1;
        double sign = 1.0;
        const auto keep = [&](double use, int k, int i, int w, int jt, double sg) {
            if (use > worst) {
                worst = use;
                kind = k;
                sample = i;
                who = w;
                joint = jt;
                sign = sg;
            }
        };
        for (std::size_t i = 0; i < m.p.size(); ++i) {
            if (!inverseDynamics(model_, data_, model_.home + s * m.p[i], s * m.dp[i], s * m.ddp[i])) return false;
            const int ii = static_cast<int>(i);
            for (int j = 0; j < model_.limbs; ++j) {
                const LimbModel& limb = model_.limb[at(j)];
                const LimbData& ld = data_.limb[at(j)];
                for (int k = 0; k < 3; ++k) {
                    const JointLimits& lim = limb.limits[at(k)];
                    const double q = ld.q(k), q0 = q_home_[at(j)](k);
                    const double room = q >= q0 ? lim.upper - q0 : q0 - lim.lower;
                    if (std::isfinite(room) && room > 0.0)
                        keep(std::abs(q - q0) / (allowed * room), 0, ii, j, k,
                             q >= q0 ? 1.0 / (allowed * room) : -1.0 / (allowed * room));
                    if (std::isfinite(lim.velocity))
                        keep(std::abs(ld.gamma_dot(k)) / (allowed * lim.velocity), 1, ii, j, k,
                             (ld.gamma_dot(k) >= 0.0 ? 1.0 : -1.0) / (allowed * lim.velocity));
                }
                keep(ld.cond / options_.max_condition, 3, ii, j, -1, 0.0);
            }
            for (int a = 0; a < model_.actuators; ++a) {
                const double effort =
                    model_.limb[at(model_.actuator_limb[at(a)])].limits[at(model_.actuator_joint[at(a)])].effort;
                if (std::isfinite(effort))
                    keep(std::abs(data_.tau(a)) / (allowed * effort), 2, ii, a, -1,
                         (data_.tau(a) >= 0.0 ? 1.0 : -1.0) / (allowed * effort));
            }
            keep(data_.cond_A / options_.max_condition, 3, ii, -1, -1, 0.0);
        }
        if (kind < 0 || kind == 3) return false;
        // d g / d x at the binding sample, x = (p, dp, ddp)
        const auto i = at(sample);
        const Pose p = model_.home + s * m.p[i];
        const Twist dp = s * m.dp[i], ddp = s * m.ddp[i];
        Eigen::Matrix<double, 9, 1> dg = Eigen::Matrix<double, 9, 1>::Zero();
        if (kind == 2) {
            InverseDynamicsDerivatives derivative;
            if (!inverseDynamicsDerivatives(model_, data_, p, dp, ddp, derivative)) return false;
            dg.segment<3>(0) = sign * derivative.d_p.row(who).transpose();
            dg.segment<3>(3) = sign * derivative.d_dp.row(who).transpose();
            dg.segment<3>(6) = sign * derivative.d_ddp.row(who).transpose();
        } else {
            if (!inverseDynamics(model_, data_, p, dp, ddp)) return false;
            const LimbData& ld = data_.limb[at(who)];
            const Vector2 c = p.tail<2>();
            for (int e = 0; e < 3; ++e) {
                const Twist t = platformTwistOfPoseRate(c, Twist::Unit(e));
                const Vector3 rate = ld.J_inv * t;  // joint rates for dp = e: dq / dp_e
                if (kind == 0) {
                    dg(e) = sign * rate(joint);
                } else {
                    // dJ_j along p_e: columns [0, [xi_0, s_1], [xi_1, s_2]] of this motion
                    const Twist xi0 = ld.s[0] * rate(0), xi1 = xi0 + ld.s[1] * rate(1);
                    Matrix3 dJ = Matrix3::Zero();
                    dJ.col(1) = bracket(xi0, ld.s[1]);
                    dJ.col(2) = bracket(xi1, ld.s[2]);
                    // and xi_P = S(c) dp along c: d xi_P / d c_x = [0; 0; -omega], / d c_y = [0; omega; 0]
                    Twist dxi = Twist::Zero();
                    if (e == 1) dxi(2) = -dp(0);
                    if (e == 2) dxi(1) = dp(0);
                    dg(e) = sign * (ld.J_inv * (dxi - dJ * ld.gamma_dot))(joint);
                    dg(3 + e) = sign * rate(joint);
                }
            }
        }
        const auto d = z.size();
        Eigen::VectorXd grad_g(d);
        for (Eigen::Index j = 0; j < d; ++j) {
            const UnitMotion& e = basis_[at(static_cast<int>(j))];
            grad_g(j) = dg.segment<3>(0).dot(e.p[i]) + dg.segment<3>(3).dot(e.dp[i]) + dg.segment<3>(6).dot(e.ddp[i]);
        }
        const double along = grad_g.dot(z);
        if (!(along > 0.0)) return false;
        grad_s = (-s / along) * grad_g;
        return true;
    }

private:
    double fixedScale(const Eigen::VectorXd& z, double s, Eigen::VectorXd& gradient) {
        const auto d = z.size();
        const auto K = static_cast<Eigen::Index>(columns_.size());
        const int n = model_.actuators;
        gradient = Eigen::VectorXd::Zero(d);
        const UnitMotion m =
            atRestFirst(sampleTrajectory(model_, trajectoryOf(model_, z, 1.0, options_, period_), period_, samples_));
        // N = sum_i Y_i^T Y_i over the excited columns
        Yc_.resize(m.p.size());
        Eigen::MatrixXd N = Eigen::MatrixXd::Zero(K, K);
        for (std::size_t i = 0; i < m.p.size(); ++i) {
            if (!inverseDynamicsRegressor(model_, data_, model_.home + s * m.p[i], s * m.dp[i], s * m.ddp[i], Y_))
                return kInfeasible;
            Yc_[i].resize(n, K);
            for (Eigen::Index k = 0; k < K; ++k) Yc_[i].col(k) = Y_.col(columns_[at(static_cast<int>(k))]);
            N.noalias() += Yc_[i].transpose() * Yc_[i];
        }
        const Eigen::VectorXd D = N.diagonal();
        if (!(D.minCoeff() > 1e-24 * D.maxCoeff())) return kInfeasible;
        const Eigen::VectorXd inv = D.cwiseSqrt().cwiseInverse();
        const Eigen::MatrixXd S = inv.asDiagonal() * N * inv.asDiagonal();
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(S);
        const double lo = eigen.eigenvalues()(0), hi = eigen.eigenvalues()(K - 1);
        if (!(lo > 0.0)) return kInfeasible;
        // Gamma = d log cond / d N (symmetric): G(lambda, v) = u u^T - lambda diag(v_a^2 / N_aa)
        const auto G = [&](Eigen::Index e) {
            const Eigen::VectorXd v = eigen.eigenvectors().col(e);
            const Eigen::VectorXd u = inv.cwiseProduct(v);
            Eigen::MatrixXd g = u * u.transpose();
            g.diagonal() -= eigen.eigenvalues()(e) * v.cwiseAbs2().cwiseQuotient(D);
            return g;
        };
        const Eigen::MatrixXd Gamma = 0.5 * (G(K - 1) / hi - G(0) / lo);
        // d log cond = sum_i <2 Y_i Gamma, dY_i>, dY_i = sum_b C(., b) d tau_b
        const Eigen::MatrixXd& C = robots_.combination();
        InverseDynamicsDerivatives derivative;
        for (std::size_t i = 0; i < m.p.size(); ++i) {
            const Pose p = model_.home + s * m.p[i];
            const Twist dp = s * m.dp[i], ddp = s * m.ddp[i];
            const Eigen::MatrixXd Omega = 2.0 * Yc_[i] * Gamma * C;  // n x robots
            Eigen::Matrix<double, 9, 1> g = Eigen::Matrix<double, 9, 1>::Zero();
            for (std::size_t b = 0; b < robots_.robots().size(); ++b) {
                const auto bb = static_cast<Eigen::Index>(b);
                if (!inverseDynamicsDerivatives(robots_.robots()[b], data_, p, dp, ddp, derivative)) return kInfeasible;
                for (int a = 0; a < n; ++a) {
                    const double w = Omega(a, bb);
                    g.segment<3>(0) += w * derivative.d_p.row(a).transpose();
                    g.segment<3>(3) += w * derivative.d_dp.row(a).transpose();
                    g.segment<3>(6) += w * derivative.d_ddp.row(a).transpose();
                }
            }
            // x_i = s (sum_j z_j x_i(e_j)) about home
            for (Eigen::Index j = 0; j < d; ++j) {
                const UnitMotion& e = basis_[at(static_cast<int>(j))];
                gradient(j) +=
                    s * (g.segment<3>(0).dot(e.p[i]) + g.segment<3>(3).dot(e.dp[i]) + g.segment<3>(6).dot(e.ddp[i]));
            }
        }
        return 0.5 * std::log(hi / lo);
    }

    /// The first sample (t = 0) exactly at home at rest, as the ties make it: rounded, its joint
    /// rates would be +-1e-17 and the Coulomb columns sign q' would flip with the shape.
    static UnitMotion atRestFirst(UnitMotion m) {
        m.p.front().setZero();
        m.dp.front().setZero();
        m.ddp.front().setZero();
        return m;
    }

    const Model& model_;
    const ExcitationOptions& options_;
    std::vector<int> columns_;
    ColumnRobots robots_;
    Data data_;
    RegressorMatrix Y_;
    std::vector<Eigen::MatrixXd> Yc_;
    std::vector<UnitMotion> basis_;
    std::array<Vector3, kMaxLimbs> q_home_{};
    int samples_ = 0;
    double period_ = 1.0;
};

}  // namespace

std::string optimizerName(ExcitationOptimizer optimizer) { return std::string(nameOf(optimizer)); }

ExcitationOptimizer parseOptimizer(const std::string& name) {
    if (const std::optional<ExcitationOptimizer> optimizer = choiceNamed<ExcitationOptimizer>(name)) return *optimizer;
    std::string message = "excitation: unknown optimizer '";
    message.append(name).append("' (").append(choiceList<ExcitationOptimizer>()).append(")");
    throw Error(message);
}

PoseTrajectory excitationTrajectory(const Model& model, const Eigen::VectorXd& shape, double scale,
                                    const ExcitationOptions& options, double duration) {
    if (shape.size() != 3 * static_cast<Eigen::Index>(freePerAxis(options.harmonics)))
        throw Error("excitation: the shape has " + std::to_string(shape.size()) +
                    " coefficients, not 3 (2 H - 3) = " + std::to_string(3 * freePerAxis(options.harmonics)));
    return trajectoryOf(model, shape, scale, options, duration);
}

bool excitationScaleGradient(const Model& model, const Eigen::VectorXd& shape, double scale,
                             const ExcitationOptions& options, Eigen::VectorXd& gradient) {
    checkOptions(options, 1.0 / options.base_frequency);
    if (shape.size() != 3 * static_cast<Eigen::Index>(freePerAxis(options.harmonics)))
        throw Error("excitation: the shape has " + std::to_string(shape.size()) +
                    " coefficients, not 3 (2 H - 3) = " + std::to_string(3 * freePerAxis(options.harmonics)));
    ConditionGradient condition(model, options, excitedColumns(model, options));
    return condition.scaleGradient(shape, scale, gradient);
}

double excitationConditionGradient(const Model& model, const Eigen::VectorXd& shape, double scale,
                                   const ExcitationOptions& options, Eigen::VectorXd& gradient) {
    checkOptions(options, 1.0 / options.base_frequency);
    if (shape.size() != 3 * static_cast<Eigen::Index>(freePerAxis(options.harmonics)))
        throw Error("excitation: the shape has " + std::to_string(shape.size()) +
                    " coefficients, not 3 (2 H - 3) = " + std::to_string(3 * freePerAxis(options.harmonics)));
    ConditionGradient condition(model, options, excitedColumns(model, options));
    return condition(shape, scale, gradient);
}

std::vector<int> excitedColumns(const Model& model, const ExcitationOptions& options) {
    std::vector<int> columns;
    if (options.parameters == ExcitedParameters::base) {
        return baseParameters(model).independent;
    }
    const int platform = bodyParameterIndex(model.platformBody());
    columns.reserve(static_cast<std::size_t>(kBodyParameters) + 2 * static_cast<std::size_t>(model.actuators));
    // a two-DOF robot's payload is a point mass at the tool point: its mass only (identifyPayload)
    const int inertial = model.task_dimension == 2 ? 1 : kBodyParameters;
    for (int c = 0; c < inertial; ++c) columns.push_back(platform + c);
    if (options.friction) {
        for (int a = 0; a < model.actuators; ++a) {
            const int index = jointParameterIndex(model, model.actuator_limb[at(a)], model.actuator_joint[at(a)]);
            columns.push_back(index);
            columns.push_back(index + 1);
        }
    }
    return columns;
}

ExcitationAssessment assessExcitation(const Model& model, const PoseTrajectory& trajectory, double period, int samples,
                                      const ExcitationOptions& options) {
    if (!(period > 0.0 && std::isfinite(period)) || samples < 1 || samples > 10000000)
        throw Error("excitation: the period must be positive and the samples in [1, 1e7]");
    Judge judge(model, options, excitedColumns(model, options));
    const UnitMotion m = sampleTrajectory(model, trajectory, period, samples);
    ExcitationAssessment result;
    const double worst = judge.use(m, 1.0, false, &result);
    result.feasible = worst <= 1.0;
    if (!result.feasible && result.failure.empty()) {
        result.failure = result.use.binding + " at " + text::format("%.3g", 100.0 * worst) + " % of its allowed value";
    }
    result.condition = std::isfinite(worst) ? judge.condition(m, 1.0) : kInfeasible;
    return result;
}

ExcitationResult designExcitation(const Model& model, double duration, const ExcitationOptions& options) {
    checkOptions(options, duration);
    const int H = options.harmonics;
    const int samples = options.samples > 0 ? options.samples : 25 * H;
    const double period = 1.0 / options.base_frequency;
    Judge judge(model, options, excitedColumns(model, options));
    {
        // the robot at rest at home must be within the limits
        ExcitationAssessment home;
        UnitMotion rest{{Twist::Zero()}, {Twist::Zero()}, {Twist::Zero()}};
        if (!(judge.use(rest, 0.0, false, &home) <= 1.0)) {
            throw Error("excitation: at rest at home the robot already uses " +
                        text::format("%.3g", 100.0 * home.use.worst()) + " % of the allowed " + home.use.binding +
                        (home.failure.empty() ? "" : " (" + home.failure + ")"));
        }
    }
    const auto d = static_cast<Eigen::Index>(3) * freePerAxis(H);
    // objective: log of the condition number at the largest scale within the limits
    double best_scale = 0.0;
    const auto objective = [&](const Eigen::VectorXd& z, double* scale, int check) {
        const PoseTrajectory unit = trajectoryOf(model, z, 1.0, options, duration);
        const UnitMotion m = sampleTrajectory(model, unit, period, check);
        const double peak = peakExcursion(model, m);
        if (!(peak > 0.0)) return kInfeasible;
        const double s = judge.largestScale(m, 1.0 / peak);
        if (scale) *scale = s;
        if (!(s > 0.0)) return kInfeasible;
        return std::log(judge.condition(m, s));
    };
    int calls = 0;
    const auto f = [&](const Eigen::VectorXd& z) {
        if (options.progress) options.progress(calls);  // may throw: the design stops
        ++calls;
        return objective(z, nullptr, samples);
    };
    std::mt19937 rng(options.seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Eigen::VectorXd best_z(d);
    double best_f = kInfeasible;
    int used = 0;
    for (; used < options.random_shapes; ++used) {
        Eigen::VectorXd z(d);
        for (Eigen::Index i = 0; i < d; ++i) z(i) = unit(rng);
        const double fz = f(z);
        if (fz < best_f || used == 0) {
            best_f = fz;
            best_z = z;
        }
    }
    int gradients = 0;
    if (used < options.evaluations && std::isfinite(best_f)) {
        std::pair<Eigen::VectorXd, double> refined;
        if (options.optimizer == ExcitationOptimizer::gradient) {
            // the gradient at the scale of the last shape f judged (the current one's)
            double scale = 0.0;
            const auto f_scaled = [&](const Eigen::VectorXd& z) {
                if (options.progress) options.progress(calls);
                ++calls;
                return objective(z, &scale, samples);
            };
            (void)f_scaled(best_z);
            ++used;
            ConditionGradient condition(model, options, excitedColumns(model, options));
            const auto grad = [&](const Eigen::VectorXd& z, Eigen::VectorXd& g) {
                if (options.progress) options.progress(calls);
                ++calls;
                return condition(z, scale, g, true);
            };
            refined = bfgs(f_scaled, grad, best_z, best_f, options.evaluations, used, gradients);
            // stopped at a kink (where the binding limit changes, s(z) is a minimum of smooth
            // functions) with evaluations left: Nelder-Mead from there spends the rest
            if (used < options.evaluations) {
                auto [z, fz] = nelderMead(f, refined.first, refined.second, 0.25, options.evaluations, used);
                if (fz < refined.second) refined = {z, fz};
            }
        } else {
            refined = nelderMead(f, best_z, best_f, 0.25, options.evaluations, used);
        }
        if (refined.second < best_f) {
            best_z = refined.first;
            best_f = refined.second;
        }
    }
    if (!std::isfinite(best_f)) {
        throw Error("excitation: none of the " + std::to_string(used) +
                    " shapes tried stays within the limits with a usable regressor (raise the evaluations, "
                    "lower the base frequency or the margin)");
    }
    // the final scale from the finely sampled period (peaks between the design samples)
    (void)objective(best_z, &best_scale, options.check_samples);
    if (!(best_scale > 0.0)) throw Error("excitation: the designed shape leaves the limits between design samples");
    ExcitationResult result;
    result.trajectory = trajectoryOf(model, best_z, best_scale * (1.0 - 1e-6), options, duration);
    result.assessment = assessExcitation(model, result.trajectory, period, options.check_samples, options);
    result.evaluations = used;
    result.gradients = gradients;
    return result;
}

PoseTrajectory aboutHome(const Model& model, PoseTrajectory trajectory) {
    trajectory.theta.offset += model.home(0);
    trajectory.x.offset += model.home(1);
    trajectory.y.offset += model.home(2);
    return trajectory;
}

}  // namespace nocdyn
