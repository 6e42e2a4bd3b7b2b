#include "nocdyn/spatial_direct_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>

#include "nocdyn/error.hpp"
#include "spatial_chain.hpp"

namespace nocdyn::spatial {

namespace {

constexpr int kTrackerIterations = 20;
constexpr double kTrackerTolerance = 1e-13;  ///< on max |u(p) - u|, times (1 + max |u|)
constexpr double kAccept = 1e-9;             ///< a mode's u_error at most this [m or rad]
constexpr double kSame = 1e-7;               ///< two modes closer than this are one [m, and R's entries]
constexpr double kPi = std::numbers::pi;

/// The platform's displacement from home at pose p.
chain::Move displacement(const Model& model, const TaskVector& p) {
    chain::Move D;
    D.R = (model.task_dimension == 6 ? rotation(p(3), p(4), p(5)) : Eigen::Matrix3d::Identity()) *
          model.home_rotation.transpose();
    D.t = p.head<3>() - D.R * model.home.head<3>();
    return D;
}

double wrap(double a) {
    a = std::remainder(a, 2.0 * kPi);
    return a <= -kPi ? a + 2.0 * kPi : a;
}

/// Limb closure at D from q by Gauss-Newton on the error twist and, when `pin`, on
/// q_(k_a) - u_a with the actuated freedom k_a started at u_a. True when they vanish.
bool closeFrom(const Limb& limb, const chain::Move& D, int k_a, double u_a, bool pin, FreedomVector& q) {
    const int n = limb.size();
    if (pin) q(k_a) = u_a;
    Eigen::Matrix<double, 7, Eigen::Dynamic, 0, 7, kMaxFreedoms> J(7, n);
    Eigen::Matrix<double, 7, 1> r;
    const double tolerance = 1e-13 * (1.0 + D.t.cwiseAbs().maxCoeff());
    for (int iteration = 0; iteration < 60; ++iteration) {
        chain::Move g;
        J.setZero();
        for (int k = 0; k < n; ++k) {
            J.block<6, 1>(0, k) = chain::carriedScrew(limb.freedoms[static_cast<std::size_t>(k)], g);
            g = g.then(chain::freedomMove(limb.freedoms[static_cast<std::size_t>(k)], q(k)));
        }
        J(6, k_a) = pin ? 1.0 : 0.0;
        const Eigen::AngleAxisd rotation_error(D.R * g.R.transpose());
        r.head<3>() = rotation_error.angle() * rotation_error.axis();
        r.segment<3>(3) = D.t - g.t - r.head<3>().cross(g.t);
        r(6) = pin ? u_a - q(k_a) : 0.0;
        const double residual = r.cwiseAbs().maxCoeff();
        if (!std::isfinite(residual)) return false;
        if (residual <= tolerance) return true;
        const FreedomVector step = J.colPivHouseholderQr().solve(r);
        if (!step.allFinite()) return false;
        q += step;
    }
    return false;
}

/// Every limb closed at p (data's limbs marked closed there), from the home branch's variables
/// and passive turns of 0, pi/2, -pi/2 and pi: with its actuated freedom held at u_a (`pin`),
/// or on the branch whose actuated variable is nearest u_a. False when some limb cannot.
bool closeLimbs(const Model& model, Data& data, const ActuatorVector& u, const TaskVector& p, bool pin) {
    const chain::Move D = displacement(model, p);
    // the home branches' variables as a first start, where inverse kinematics reaches p
    Data home(model);
    const bool reached = inverseKinematics(model, home, p).code != StatusCode::unreachable;
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        int k_a = -1;
        double u_a = 0.0;
        for (int a = 0; a < model.actuators; ++a) {
            if (model.actuator[static_cast<std::size_t>(a)].first == j) {
                k_a = model.actuator[static_cast<std::size_t>(a)].second;
                u_a = u(a);
            }
        }
        bool closed = false;
        double nearest = std::numeric_limits<double>::infinity();
        for (int start = 0; start < 5 && !(pin && closed); ++start) {
            FreedomVector q = FreedomVector::Zero(limb.size());
            if (start == 0) {
                const LimbData& h = home.limb[static_cast<std::size_t>(j)];
                if (!reached || !h.closed) continue;
                q = h.q;
            } else {
                // passive revolute freedoms turned by 0, pi/2, -pi/2, pi
                const double turn =
                    std::array<double, 4>{0.0, kPi / 2, -kPi / 2, kPi}[static_cast<std::size_t>(start - 1)];
                for (int k = 0; k < limb.size(); ++k)
                    q(k) = limb.freedoms[static_cast<std::size_t>(k)].revolute ? turn : 0.0;
            }
            if (k_a < 0) {  // an unactuated limb: inverse kinematics closes it
                ld.q = q;
                closed = true;
                break;
            }
            if (closeFrom(limb, D, k_a, u_a, pin, q) && std::abs(q(k_a) - u_a) < nearest) {
                nearest = pin ? 0.0 : std::abs(q(k_a) - u_a);
                ld.q = q;
                closed = true;
            }
        }
        if (!closed) return false;
        ld.closed = true;
    }
    return true;
}

/// A pose's distance from home: the position's [m] plus the rotation's angle [rad].
double fromHome(const Model& model, const TaskVector& p) {
    double d = (p.head<3>() - model.home.head<3>()).norm();
    if (model.task_dimension == 6) {
        d += Eigen::AngleAxisd(rotation(p(3), p(4), p(5)) * model.home_rotation.transpose()).angle();
    }
    return d;
}

bool samePose(const Model& model, const TaskVector& a, const TaskVector& b) {
    if ((a.head<3>() - b.head<3>()).cwiseAbs().maxCoeff() > kSame) return false;
    if (model.task_dimension == 3) return true;
    return (rotation(a(3), a(4), a(5)) - rotation(b(3), b(4), b(5))).cwiseAbs().maxCoeff() <= kSame;
}

/// Newton on u(p) - u from p, at most `iterations` steps; it gives up when the residual grows
/// tenfold over the first (a step towards another branch).
Status newton(const Model& model, Data& data, const ActuatorVector& u, TaskVector& p, int iterations) {
    const int d = model.task_dimension, n = model.actuators;
    if (u.size() != n || p.size() != d || !u.allFinite() || !p.allFinite()) {
        return {StatusCode::not_finite, -1, u.sum() + p.sum()};
    }
    const double tolerance = kTrackerTolerance * (1.0 + u.cwiseAbs().maxCoeff());
    TaskVector x = p;
    double residual = std::numeric_limits<double>::infinity();
    double first = -1.0;
    for (int iteration = 0; iteration < iterations; ++iteration) {
        if (const Status status = inverseKinematics(model, data, x); !status) return status;
        residual = (data.u - u).cwiseAbs().maxCoeff();
        if (residual <= tolerance) {
            p = x;
            return {};
        }
        if (first < 0.0) first = residual;
        if (residual > 10.0 * first) break;
        // du/dp = A_task diag(I, E): w = E [roll'; pitch'; yaw']
        ActuationMatrix J = data.A_task;
        if (d == 6) {
            const double cp = std::cos(x(4)), sp = std::sin(x(4)), cy = std::cos(x(5)), sy = std::sin(x(5));
            Eigen::Matrix3d E;
            E << cy * cp, -sy, 0.0, sy * cp, cy, 0.0, -sp, 0.0, 1.0;
            J.rightCols<3>() = data.A_task.rightCols<3>() * E;
        }
        const TaskVector step = Eigen::HouseholderQR<ActuationMatrix>(J).solve(ActuatorVector(u - data.u));
        if (!step.allFinite()) {
            conditionNumbers(model, data);
            return {StatusCode::singular_actuation, -1, data.actuation_condition};
        }
        x += step;
    }
    return {StatusCode::assembly_mode_lost, -1, residual};
}

/// Continuation in u from data's pose x (actuator values data.u) to u: the tracker on
/// u(t) = u_0 + t (u - u_0), the step in t doubled after a success and halved after a failure
/// (the limbs put back as they were). True when t reaches 1.
bool continuation(const Model& model, Data& data, const ActuatorVector& u, TaskVector& x) {
    const ActuatorVector u0 = data.u;
    std::vector<FreedomVector> saved(static_cast<std::size_t>(model.limbs()));
    double t = 0.0, h = 0.125;
    for (int step = 0; step < 200 && t < 1.0; ++step) {
        for (int j = 0; j < model.limbs(); ++j)
            saved[static_cast<std::size_t>(j)] = data.limb[static_cast<std::size_t>(j)].q;
        h = std::min(h, 1.0 - t);
        const double next = t + h >= 1.0 - 1e-12 ? 1.0 : t + h;
        const ActuatorVector target = u0 + next * (u - u0);
        TaskVector y = x;
        if (newton(model, data, target, y, 8)) {
            x = y;
            t = next;
            h = std::min(2.0 * h, 0.25);
            continue;
        }
        for (int j = 0; j < model.limbs(); ++j) {
            data.limb[static_cast<std::size_t>(j)].q = saved[static_cast<std::size_t>(j)];
            data.limb[static_cast<std::size_t>(j)].closed = true;
        }
        h *= 0.5;
        if (h < 1e-3) return false;
    }
    return t >= 1.0;
}

/// Deterministic seed poses: home, home mirrored about the plane of the base points' mean
/// height (z -> 2 z_b - z, R -> M R M with M = diag(1, 1, -1)), then poses spread about both.
std::vector<TaskVector> seeds(const Model& model, const ManyStarts& bounds) {
    const int d = model.task_dimension;
    double z_base = 0.0;
    for (const Limb& limb : model.limb) z_base += limb.freedoms.front().point.z() / model.limbs();
    Eigen::Vector3d base_centre = Eigen::Vector3d::Zero();
    for (const Limb& limb : model.limb) base_centre += limb.freedoms.front().point / model.limbs();
    const double length = std::max(0.05, (model.home.head<3>() - base_centre).norm());
    const auto mirrored = [&](TaskVector p) {
        p(2) = 2.0 * z_base - p(2);
        if (d == 6) {
            const Eigen::Matrix3d M = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
            const Eigen::Matrix3d R = M * rotation(p(3), p(4), p(5)) * M;
            // Euler angles of R = Rz(yaw) Ry(pitch) Rx(roll)
            p(4) = -std::asin(std::clamp(R(2, 0), -1.0, 1.0));
            p(3) = std::atan2(R(2, 1), R(2, 2));
            p(5) = std::atan2(R(1, 0), R(0, 0));
        }
        return p;
    };
    std::vector<TaskVector> out{model.home, mirrored(model.home)};
    std::mt19937 rng(bounds.seed);
    const auto uniform = [&rng]() { return 2.0 * static_cast<double>(rng()) / 4294967296.0 - 1.0; };  // [-1, 1)
    while (static_cast<int>(out.size()) < bounds.starts) {
        TaskVector p = model.home;
        for (int i = 0; i < 3; ++i) p(i) += 0.5 * length * uniform();
        if (d == 6) {
            p(3) += 0.8 * uniform();
            p(4) += 0.8 * uniform();
            p(5) += 1.5 * uniform();
        }
        out.push_back(out.size() % 2 == 1 ? mirrored(p) : p);
    }
    out.resize(static_cast<std::size_t>(std::max(1, bounds.starts)));
    return out;
}

}  // namespace

Status directKinematics(const Model& model, Data& data, const ActuatorVector& u, TaskVector& p) {
    return newton(model, data, u, p, kTrackerIterations);
}

std::string describeDirect(const Status& status, const Model& model) {
    if (status.code == StatusCode::assembly_mode_lost) {
        return "the direct kinematics' Newton did not converge (max |u(p) - u| = " + std::to_string(status.value) +
               "): the actuator values moved too far from the previous pose's, or out of reach";
    }
    if (status.code == StatusCode::not_finite)
        return "an actuator value or the starting pose is not finite, or of the wrong size";
    return describe(status, model);
}

std::optional<ThreeSpheres> threeSpheres(const Model& model, std::string& why) {
    if (model.task_dimension != 3) {
        why = "motion full: the platform turns";
        return std::nullopt;
    }
    if (model.limbs() != 3 || model.actuators != 3) {
        why = std::to_string(model.limbs()) + " limbs and " + std::to_string(model.actuators) +
              " actuators, not three R-U-U limbs with the R actuated";
        return std::nullopt;
    }
    ThreeSpheres s;
    for (int j = 0; j < 3; ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const std::string name = "limb " + std::to_string(j + 1) + " (" + limb.name + ")";
        const auto& f = limb.freedoms;
        const bool shape = limb.size() == 5 &&
                           std::all_of(f.begin(), f.end(), [](const Freedom& x) { return x.revolute; }) &&
                           f[0].joint == 0 && f[1].joint == 1 && f[2].joint == 1 && f[3].joint == 2 && f[4].joint == 2;
        if (!shape) {
            why = name + " is not R-U-U";
            return std::nullopt;
        }
        if (f[0].actuator < 0) {
            why = name + ": its R joint is not the actuated one";
            return std::nullopt;
        }
        s.actuator[static_cast<std::size_t>(j)] = f[0].actuator;
        s.axis[static_cast<std::size_t>(j)] = f[0].axis;
        s.base[static_cast<std::size_t>(j)] = f[0].point;
        s.elbow[static_cast<std::size_t>(j)] = f[1].point;
        s.platform[static_cast<std::size_t>(j)] = f[3].point;
        s.forearm[static_cast<std::size_t>(j)] = (f[3].point - f[1].point).norm();
    }
    return s;
}

int threeSpheresPoints(const ThreeSpheres& s, const Eigen::Vector3d& home, const ActuatorVector& u,
                       std::array<Eigen::Vector3d, 2>& points, double& gap) {
    std::array<Eigen::Vector3d, 3> c;
    for (std::size_t j = 0; j < 3; ++j) {
        const Eigen::Vector3d elbow =
            s.base[j] + Eigen::AngleAxisd(u(s.actuator[j]), s.axis[j]) * (s.elbow[j] - s.base[j]);
        c[j] = elbow - (s.platform[j] - home);
    }
    // the frame of the centres: e_x along c_1 c_2, e_y in their plane, e_z its normal
    const Eigen::Vector3d d12 = c[1] - c[0], d13 = c[2] - c[0];
    const double d = d12.norm();
    const Eigen::Vector3d ex = d12 / d;
    const double i = ex.dot(d13);
    const Eigen::Vector3d ey_raw = d13 - i * ex;
    const double jj = ey_raw.norm();
    if (!(d > 1e-12 && jj > 1e-9 * std::max(1.0, d13.norm()))) {
        throw Error("the three spheres' centres (the elbows shifted by the platform's joints) are on one line");
    }
    const Eigen::Vector3d ey = ey_raw / jj, ez = ex.cross(ey);
    const double r1 = s.forearm[0], r2 = s.forearm[1], r3 = s.forearm[2];
    const double x = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    const double y = (r1 * r1 - r3 * r3 + i * i + jj * jj - 2.0 * i * x) / (2.0 * jj);
    const double z2 = r1 * r1 - x * x - y * y;
    if (!(z2 >= 0.0)) {
        gap = -z2;
        return 0;
    }
    gap = 0.0;
    const Eigen::Vector3d foot = c[0] + x * ex + y * ey;
    points[0] = foot - std::sqrt(z2) * ez;
    points[1] = foot + std::sqrt(z2) * ez;
    return 2;
}

TaskVector canonicalPose(const TaskVector& p) {
    TaskVector q = p;
    if (q.size() != 6) return q;
    double roll = wrap(q(3)), pitch = wrap(q(4)), yaw = wrap(q(5));
    if (std::abs(pitch) > kPi / 2) {  // (roll + pi, pi - pitch, yaw + pi) is the same rotation
        pitch = wrap(kPi - pitch);
        roll = wrap(roll + kPi);
        yaw = wrap(yaw + kPi);
    }
    q(3) = roll, q(4) = pitch, q(5) = yaw;
    return q;
}

std::optional<AssemblyMode> verifyMode(const Model& model, const ActuatorVector& u, const TaskVector& p) {
    Data data(model);
    if (!p.allFinite() || !closeLimbs(model, data, u, p, true)) return std::nullopt;
    AssemblyMode mode;
    TaskVector x = p;
    const Status status = directKinematics(model, data, u, x);
    if (status) {
        mode.u_error = (data.u - u).cwiseAbs().maxCoeff();
        conditionNumbers(model, data);
        mode.condition = data.actuation_condition;
        for (const LimbData& ld : data.limb) mode.condition = std::max(mode.condition, ld.condition);
    } else if (status.code == StatusCode::singular_limb || status.code == StatusCode::singular_actuation) {
        // singular at p: the closures with the actuated variables held at u stand for the round trip
        Data pinned(model);
        if (!closeLimbs(model, pinned, u, p, true)) return std::nullopt;
        mode.u_error = 0.0;
        mode.condition = status.value;
        x = p;
    } else {
        return std::nullopt;
    }
    if (!(mode.u_error <= kAccept)) return std::nullopt;
    mode.p = canonicalPose(x);
    Data home(model);
    mode.home_branches = inverseKinematics(model, home, mode.p) && (home.u - u).cwiseAbs().maxCoeff() <= kAccept;
    return mode;
}

AssemblyModes assemblyModes(const Model& model, const ActuatorVector& u, const ManyStarts& bounds) {
    if (u.size() != model.actuators) {
        throw Error("u: " + std::to_string(u.size()) + " values for the robot's " + std::to_string(model.actuators) +
                    " actuators");
    }
    if (!u.allFinite()) throw Error("u: a value is not finite");
    AssemblyModes out;
    std::vector<TaskVector> candidates;
    std::string why;
    if (const std::optional<ThreeSpheres> spheres = threeSpheres(model, why)) {
        out.method = DirectMethod::three_spheres;
        out.complete = true;
        std::array<Eigen::Vector3d, 2> points;
        if (threeSpheresPoints(*spheres, model.home.head<3>(), u, points, out.gap) == 2) {
            for (const Eigen::Vector3d& point : points) candidates.emplace_back(TaskVector(point));
        }
    } else {
        for (const TaskVector& seed : seeds(model, bounds)) {
            // the limbs on their home branches at even seeds, on the branches nearest u at odd
            // ones (the mirrored seeds: a leg pointing down rather than through its base joint)
            Data data(model);
            if (out.starts++ % 2 == 1 && !closeLimbs(model, data, u, seed, false)) continue;
            if (!inverseKinematics(model, data, seed)) continue;
            TaskVector x = seed;
            if (continuation(model, data, u, x)) candidates.push_back(x);
        }
    }
    for (const TaskVector& candidate : candidates) {
        std::optional<AssemblyMode> mode = verifyMode(model, u, candidate);
        if (!mode) continue;
        const bool known = std::any_of(out.modes.begin(), out.modes.end(),
                                       [&](const AssemblyMode& m) { return samePose(model, m.p, mode->p); });
        if (!known) out.modes.push_back(*mode);
    }
    std::stable_sort(out.modes.begin(), out.modes.end(), [&](const AssemblyMode& a, const AssemblyMode& b) {
        return fromHome(model, a.p) < fromHome(model, b.p);
    });
    for (AssemblyMode& mode : out.modes) {
        if (mode.home_branches) {
            mode.working = true;  // the nearest home of those on the home branches
            break;
        }
    }
    return out;
}

}  // namespace nocdyn::spatial
