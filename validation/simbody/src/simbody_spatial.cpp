// Independent Simbody model of a spatial parallel robot. See the header for the model and the
// force balance. Nothing from nocdyn's kinematics or dynamics is used: the model is built from
// the home posture of the description, where every limb body's frame coincides with Ground's.
#include "nocdyn/validation/simbody_spatial.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Dense>
#include <Simbody.h>

#include "nocdyn/error.hpp"

namespace nocdyn::validation {
namespace {

// Constraint errors are lengths [m] (or angles): far below the 1e-9 relative accuracy asked.
constexpr double kProjectAccuracy = 1e-14;
// Largest change of a passive coordinate between the extrapolated seed and the solution
// accepted as the continuation of the same branch; a larger step is subdivided.
constexpr double kMaxJump = 0.05;
constexpr int kMaxHalvings = 8;

SimTK::Vec3 vec3(const ::Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// A body given by its mass, c.o.m. and central inertia tensor in the body frame.
SimTK::Body::Rigid rigidBody(const SpatialBodyDescription& body, const ::Eigen::Vector3d& com,
                             const ::Eigen::Matrix3d& I) {
    using namespace SimTK;
    const Vec3 c = vec3(com);
    const Inertia central(I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
    return Body::Rigid(MassProperties(body.mass, c, central.shiftFromMassCenter(-c, body.mass)));
}

/// The prescribed values of one mobilizer's coordinates: pose entries `index` (nocdyn's pose
/// order) of the arrays it points to, set from outside before each realization.
class PoseMotion final : public SimTK::Motion::Custom::Implementation {
public:
    PoseMotion(const std::array<double, 6>* q, const std::array<double, 6>* qd, const std::array<double, 6>* qdd,
               std::vector<int> index)
        : q_(q), qd_(qd), qdd_(qdd), index_(std::move(index)) {}
    SimTK::Motion::Level getLevel(const SimTK::State&) const override { return SimTK::Motion::Position; }
    void calcPrescribedPosition(const SimTK::State&, int nq, SimTK::Real* out) const override { fill(*q_, nq, out); }
    void calcPrescribedPositionDot(const SimTK::State&, int nq, SimTK::Real* out) const override {
        fill(*qd_, nq, out);
    }
    void calcPrescribedPositionDotDot(const SimTK::State&, int nq, SimTK::Real* out) const override {
        fill(*qdd_, nq, out);
    }

private:
    void fill(const std::array<double, 6>& v, int nq, SimTK::Real* out) const {
        for (int i = 0; i < nq && i < static_cast<int>(index_.size()); ++i)
            out[i] = v[static_cast<std::size_t>(index_[static_cast<std::size_t>(i)])];
    }
    const std::array<double, 6>* q_;
    const std::array<double, 6>* qd_;
    const std::array<double, 6>* qdd_;
    std::vector<int> index_;
};

::Eigen::VectorXd toEigen(const SimTK::Vector& v) {
    ::Eigen::VectorXd out(v.size());
    for (int i = 0; i < v.size(); ++i) out[i] = v[i];
    return out;
}

double conditionNumber(const ::Eigen::MatrixXd& A) {
    Eigen::JacobiSVD<::Eigen::MatrixXd> svd(A);
    const auto& s = svd.singularValues();
    if (s.size() == 0) return 0.0;
    const double smin = s(s.size() - 1);
    return smin > 0.0 ? s(0) / smin : std::numeric_limits<double>::infinity();
}

}  // namespace

class SimbodySpatialMechanism::Impl {
public:
    explicit Impl(const SpatialRobotDescription& description);

    /// One R or P joint of a limb's tree: its mobilizer and generalized speed.
    struct Joint {
        const SpatialJointDescription* joint = nullptr;
        SimTK::MobilizedBody mobilizer;
        int v = -1;
    };

    SpatialRobotDescription robot;
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter;
    SimTK::GeneralForceSubsystem forces;
    SimTK::State state;
    SimTK::Vector q_home;  // the assembled home posture, where every call's path starts
    std::array<double, 6> pose{}, pose_rate{}, pose_acc{};  // the prescribed values, nocdyn's order

    std::vector<SimTK::MobilizedBody> platform_chain;  // Translation, yaw, pitch, roll (= the platform)
    std::vector<SimTK::MobilizedBody> limb_mobilizers;
    std::vector<Joint> joints;    // every R and P joint of the trees
    std::vector<int> actuated_v;  // per actuator (file order): its generalized speed
    std::vector<int> task_v;      // the prescribed speeds, pose order
    std::vector<int> free_v;      // every other speed
    int task = 6;

    bool tryAssemble(const ::Eigen::VectorXd& p, const ::Eigen::VectorXd& seed);
    void assemble(std::size_t sample, const ::Eigen::VectorXd& p, const ::Eigen::VectorXd& seed,
                  const ::Eigen::VectorXd& p_from, const ::Eigen::VectorXd& q_from);
    /// "<file>: " or nothing, to begin a message.
    [[nodiscard]] std::string origin() const { return robot.source.empty() ? std::string() : robot.source + ": "; }
    void setPose(const ::Eigen::VectorXd& p) {
        for (int i = 0; i < task; ++i) pose[static_cast<std::size_t>(i)] = p[i];
    }
};

SimbodySpatialMechanism::Impl::Impl(const SpatialRobotDescription& description)
    : robot(description), matter(system), forces(system) {
    using namespace SimTK;
    const bool full = robot.motion == PlatformMotion::full;
    task = full ? 6 : 3;

    // The platform: Translation [x, y, z] from Ground, then Pins about z (yaw), y (pitch) and
    // x (roll) of the body before; its frame is the platform frame (c.o.m. and inertia as given).
    const Rotation z_to_y(UnitVec3(0, 1, 0), ZAxis), z_to_x(UnitVec3(1, 0, 0), ZAxis);
    MobilizedBody::Translation translation(matter.Ground(), Transform(), Body::Massless(), Transform());
    MobilizedBody::Pin yaw(translation, Transform(), Body::Massless(), Transform());
    MobilizedBody::Pin pitch(yaw, Transform(z_to_y), Body::Massless(), Transform(z_to_y));
    MobilizedBody::Pin roll(pitch, Transform(z_to_x),
                            rigidBody(robot.platform, robot.platform.com, robot.platform.inertia), Transform(z_to_x));
    platform_chain = {translation, yaw, pitch, roll};
    // nocdyn's pose order [x, y, z, roll, pitch, yaw]
    Motion::Custom(translation, new PoseMotion(&pose, &pose_rate, &pose_acc, {0, 1, 2}));
    if (full) {
        Motion::Custom(yaw, new PoseMotion(&pose, &pose_rate, &pose_acc, {5}));
        Motion::Custom(pitch, new PoseMotion(&pose, &pose_rate, &pose_acc, {4}));
        Motion::Custom(roll, new PoseMotion(&pose, &pose_rate, &pose_acc, {3}));
    }
    const ::Eigen::Matrix3d R_home = (::Eigen::AngleAxisd(robot.home(5), ::Eigen::Vector3d::UnitZ()) *
                                      ::Eigen::AngleAxisd(robot.home(4), ::Eigen::Vector3d::UnitY()) *
                                      ::Eigen::AngleAxisd(robot.home(3), ::Eigen::Vector3d::UnitX()))
                                         .toRotationMatrix();
    const ::Eigen::Vector3d c_home = robot.home.head<3>();
    auto inPlatform = [&](const ::Eigen::Vector3d& x) { return vec3(R_home.transpose() * (x - c_home)); };
    auto inPlatformDirection = [&](const ::Eigen::Vector3d& a) { return vec3(R_home.transpose() * a); };

    std::vector<MobilizedBody> actuated;  // per actuated joint (file order): its mobilizer
    for (const SpatialLimbDescription& limb : robot.limbs) {
        MobilizedBody parent = matter.Ground();
        const std::size_t last = limb.joints.size() - 1;
        for (std::size_t k = 0; k < last; ++k) {
            const SpatialJointDescription& joint = limb.joints[k];
            const SpatialBodyDescription& body = limb.bodies[k];
            const Body::Rigid info = rigidBody(body, body.com, body.inertia);
            // a Pin about `axis` through `point` from `from` to a body `to` (frames at Ground's at home)
            auto pin = [&](MobilizedBody& from, const ::Eigen::Vector3d& axis, const ::Eigen::Vector3d& point,
                           const Body& to) {
                const Transform X(Rotation(UnitVec3(vec3(axis)), ZAxis), vec3(point));
                MobilizedBody::Pin mob(from, X, to, X);
                limb_mobilizers.push_back(mob);
                return MobilizedBody(mob);
            };
            switch (joint.type) {
                case SpatialJointType::revolute:
                    parent = pin(parent, joint.axis, joint.point, info);
                    joints.push_back({&joint, parent, -1});
                    if (joint.actuated) actuated.push_back(parent);
                    break;
                case SpatialJointType::prismatic: {
                    // Simbody's Slider moves along its F frame's x
                    const Transform X(Rotation(UnitVec3(vec3(joint.direction)), XAxis), Vec3(0));
                    MobilizedBody::Slider mob(parent, X, info, X);
                    limb_mobilizers.push_back(mob);
                    parent = mob;
                    joints.push_back({&joint, parent, -1});
                    if (joint.actuated) actuated.push_back(parent);
                    break;
                }
                case SpatialJointType::universal: {
                    MobilizedBody cross = pin(parent, joint.axis1, joint.point, Body::Massless());
                    parent = pin(cross, joint.axis2, joint.point, info);
                    break;
                }
                case SpatialJointType::spherical: {
                    MobilizedBody a = pin(parent, ::Eigen::Vector3d::UnitX(), joint.point, Body::Massless());
                    MobilizedBody b = pin(a, ::Eigen::Vector3d::UnitY(), joint.point, Body::Massless());
                    parent = pin(b, ::Eigen::Vector3d::UnitZ(), joint.point, info);
                    break;
                }
            }
        }
        const SpatialJointDescription& closing = limb.joints[last];
        switch (closing.type) {
            case SpatialJointType::spherical:
                Constraint::Ball(parent, vec3(closing.point), roll, inPlatform(closing.point));
                break;
            case SpatialJointType::universal: {
                Constraint::Ball(parent, vec3(closing.point), roll, inPlatform(closing.point));
                const double angle = std::acos(std::clamp(closing.axis1.dot(closing.axis2), -1.0, 1.0));
                Constraint::ConstantAngle(parent, UnitVec3(vec3(closing.axis1)), roll,
                                          UnitVec3(inPlatformDirection(closing.axis2)), angle);
                break;
            }
            default:
                throw Error(origin() + "limb " + limb.name +
                            ": the Simbody model closes a limb at an S or U joint only, not at an R or P");
        }
    }
    Force::UniformGravity(forces, matter, vec3(robot.gravity));

    system.realizeTopology();
    state = system.getDefaultState();
    system.realize(state, Stage::Instance);
    if (state.getNQ() != state.getNU()) throw Error("Simbody spatial model: nq != nu");

    for (const MobilizedBody& mob : actuated) actuated_v.push_back(mob.getFirstUIndex(state));
    for (Joint& joint : joints) joint.v = joint.mobilizer.getFirstUIndex(state);
    for (const MobilizedBody& m : limb_mobilizers) {
        if (m.getFirstQIndex(state) != m.getFirstUIndex(state)) throw Error("Simbody spatial model: q/u order");
    }
    for (const MobilizedBody& m : platform_chain) {
        if (m.getFirstQIndex(state) != m.getFirstUIndex(state)) throw Error("Simbody spatial model: q/u order");
    }
    const int t0 = translation.getFirstUIndex(state);
    task_v = {t0, t0 + 1, t0 + 2};
    if (full) {
        task_v.push_back(roll.getFirstUIndex(state));
        task_v.push_back(pitch.getFirstUIndex(state));
        task_v.push_back(yaw.getFirstUIndex(state));
    }
    for (int i = 0; i < state.getNU(); ++i) {
        if (std::find(task_v.begin(), task_v.end(), i) == task_v.end()) free_v.push_back(i);
    }

    // Home is assembled with every limb coordinate 0 and the platform at `home`.
    ::Eigen::VectorXd home = robot.home.head(task);
    setPose(home);
    state.invalidateAll(Stage::Time);
    system.realize(state, Stage::Time);
    system.prescribeQ(state);
    if (!full) {
        state.updQ()[yaw.getFirstQIndex(state)] = 0.0;
        state.updQ()[pitch.getFirstQIndex(state)] = 0.0;
        state.updQ()[roll.getFirstQIndex(state)] = 0.0;
    }
    system.realize(state, Stage::Position);
    const double err = state.getQErr().size() > 0 ? SimTK::max(SimTK::abs(state.getQErr())) : 0.0;
    if (!(err < 1e-9)) {
        std::ostringstream msg;
        msg << origin() << "Simbody spatial model: the home posture is not assembled (loop error " << err << ")";
        throw Error(msg.str());
    }
    q_home = state.getQ();
}

bool SimbodySpatialMechanism::Impl::tryAssemble(const ::Eigen::VectorXd& p, const ::Eigen::VectorXd& seed) {
    using namespace SimTK;
    setPose(p);
    // the prescribed q are evaluated when the Time stage is realized
    state.invalidateAll(Stage::Time);
    for (int i = 0; i < seed.size(); ++i) state.updQ()[i] = seed[i];
    try {
        ProjectOptions options(kProjectAccuracy);
        options.setOption(ProjectOptions::ForceFullNewton);
        ProjectOptions forced(options);
        forced.setOption(ProjectOptions::ForceProjection);
        Vector no_error_estimate;
        ProjectResults results;
        system.realize(state, Stage::Time);
        system.prescribeQ(state);
        system.realize(state, Stage::Position);
        system.projectQ(state, no_error_estimate, options, results);
        // one more full Newton step leaves the constraint errors at round-off level
        system.projectQ(state, no_error_estimate, forced, results);
    } catch (const std::exception&) {
        return false;
    }
    double jump = 0.0;
    for (int i : free_v) {
        const double qi = state.getQ()[i];
        if (!std::isfinite(qi)) return false;
        jump = std::max(jump, std::abs(qi - seed[i]));
    }
    const double err = SimTK::max(SimTK::abs(state.getQErr()));
    return jump <= kMaxJump && err < 1e-10;
}

void SimbodySpatialMechanism::Impl::assemble(std::size_t sample, const ::Eigen::VectorXd& p,
                                             const ::Eigen::VectorXd& seed, const ::Eigen::VectorXd& p_from,
                                             const ::Eigen::VectorXd& q_from) {
    if (tryAssemble(p, seed)) return;
    for (int halvings = 1; halvings <= kMaxHalvings; ++halvings) {
        const int pieces = 1 << halvings;
        ::Eigen::VectorXd q = q_from;
        bool ok = true;
        for (int s = 1; s <= pieces && ok; ++s) {
            ok = tryAssemble(p_from + (p - p_from) * (static_cast<double>(s) / pieces), q);
            if (ok) q = toEigen(state.getQ());
        }
        if (ok) return;
    }
    throw Error(origin() + "Simbody spatial model: cannot assemble sample " + std::to_string(sample) +
                " on the home branch");
}

SimbodySpatialMechanism::SimbodySpatialMechanism(const SpatialRobotDescription& robot)
    : impl_(std::make_unique<Impl>(robot)) {}
SimbodySpatialMechanism::~SimbodySpatialMechanism() = default;
SimbodySpatialMechanism::SimbodySpatialMechanism(SimbodySpatialMechanism&&) noexcept = default;
SimbodySpatialMechanism& SimbodySpatialMechanism::operator=(SimbodySpatialMechanism&&) noexcept = default;

int SimbodySpatialMechanism::actuatorCount() const { return static_cast<int>(impl_->actuated_v.size()); }

::Eigen::MatrixXd SimbodySpatialMechanism::actuatorForces(const std::vector<::Eigen::VectorXd>& p,
                                                          const std::vector<::Eigen::VectorXd>& dp,
                                                          const std::vector<::Eigen::VectorXd>& ddp) {
    using namespace SimTK;
    Impl& m = *impl_;
    const int task = m.task;
    const int nv = m.state.getNU();
    const int n = actuatorCount();
    if (dp.size() != p.size() || ddp.size() != p.size())
        throw Error("Simbody spatial model: p, dp and ddp differ in length");
    ::Eigen::MatrixXd tau(static_cast<::Eigen::Index>(p.size()), n);

    // continuation from home (not from where the previous call ended): the previous solution
    // extrapolated linearly in the sample
    m.state.updQ() = m.q_home;
    ::Eigen::VectorXd q_prev = toEigen(m.state.getQ()), step = ::Eigen::VectorXd::Zero(nv);
    ::Eigen::VectorXd p_prev = m.robot.home.head(task);
    Matrix G;
    Vector bias, h;
    for (std::size_t s = 0; s < p.size(); ++s) {
        if (p[s].size() != task || dp[s].size() != task || ddp[s].size() != task)
            throw Error("Simbody spatial model: sample " + std::to_string(s) + " is not of size " +
                        std::to_string(task));
        const ::Eigen::VectorXd seed = q_prev + step;
        for (int i = 0; i < task; ++i) {
            m.pose_rate[static_cast<std::size_t>(i)] = dp[s][i];
            m.pose_acc[static_cast<std::size_t>(i)] = ddp[s][i];
        }
        m.assemble(s, p[s], seed, p_prev, q_prev);
        if (task == 3) {
            // the limbs' U constraints, not a mobilizer, hold the platform's angles at 0
            for (std::size_t i = 1; i < 4; ++i) {
                const double angle = m.state.getQ()[m.platform_chain[i].getFirstQIndex(m.state)];
                if (!(std::abs(angle) < 1e-9)) {
                    std::ostringstream msg;
                    msg << m.origin() << "Simbody spatial model: the limbs turn the platform by " << angle
                        << " rad at sample " << s;
                    throw Error(msg.str());
                }
            }
        }

        // v = N dp: G_f v_f + G_p dp = 0
        m.matter.calcG(m.state, G);
        const int nc = G.nrow();
        const int nf = static_cast<int>(m.free_v.size());
        ::Eigen::MatrixXd Gf(nc, nf), Gp(nc, task);
        for (int r = 0; r < nc; ++r) {
            for (int c = 0; c < nf; ++c) Gf(r, c) = G(r, m.free_v[static_cast<std::size_t>(c)]);
            for (int c = 0; c < task; ++c) Gp(r, c) = G(r, m.task_v[static_cast<std::size_t>(c)]);
        }
        if (nc != nf) {
            throw Error("Simbody spatial model: " + std::to_string(nc) + " closure equations for " +
                        std::to_string(nf) + " passive speeds");
        }
        const double cond_G = conditionNumber(Gf);
        if (!(cond_G <= m.robot.max_condition)) {
            throw Error("Simbody spatial model: the loop closure is singular at sample " + std::to_string(s));
        }
        const auto lu = Gf.fullPivLu();
        ::Eigen::MatrixXd N = ::Eigen::MatrixXd::Zero(nv, task);
        const ::Eigen::MatrixXd X = lu.solve(-Gp);
        for (int r = 0; r < nf; ++r) N.row(m.free_v[static_cast<std::size_t>(r)]) = X.row(r);
        for (int c = 0; c < task; ++c) N(m.task_v[static_cast<std::size_t>(c)], c) = 1.0;
        const ::Eigen::VectorXd v = N * dp[s];
        for (int i = 0; i < nv; ++i) m.state.updU()[i] = v[i];
        m.system.realize(m.state, Stage::Velocity);

        // v': G v' + bias = 0 with the prescribed v' = ddp
        m.matter.calcBiasForAccelerationConstraints(m.state, bias);
        const ::Eigen::VectorXd vdot_f = lu.solve(-toEigen(bias) - Gp * ddp[s]);
        Vector vdot(nv, 0.0);
        for (int r = 0; r < nf; ++r) vdot[m.free_v[static_cast<std::size_t>(r)]] = vdot_f[r];
        for (int c = 0; c < task; ++c) vdot[m.task_v[static_cast<std::size_t>(c)]] = ddp[s][c];

        // h = M v' + c - Q_gravity, then the joint friction
        m.system.realize(m.state, Stage::Dynamics);
        m.matter.calcResidualForceIgnoringConstraints(m.state, m.system.getMobilityForces(m.state, Stage::Dynamics),
                                                      m.system.getRigidBodyForces(m.state, Stage::Dynamics), vdot, h);
        ::Eigen::VectorXd he = toEigen(h);
        for (const Impl::Joint& j : m.joints) {
            const double rate = v[j.v];
            const double sign = rate > 0.0 ? 1.0 : (rate < 0.0 ? -1.0 : 0.0);
            he[j.v] += j.joint->damping * rate + j.joint->friction * sign;  // h - Q_f
        }
        // N^T (h - Q_f) = A^T tau over the task coordinates
        ::Eigen::MatrixXd A(n, task);
        for (int a = 0; a < n; ++a) A.row(a) = N.row(m.actuated_v[static_cast<std::size_t>(a)]);
        const ::Eigen::VectorXd F = N.transpose() * he;
        ::Eigen::JacobiSVD<::Eigen::MatrixXd> svd(A.transpose(), ::Eigen::ComputeThinU | ::Eigen::ComputeThinV);
        const auto& sv = svd.singularValues();
        const double cond_A = sv(task - 1) > 0.0 ? sv(0) / sv(task - 1) : std::numeric_limits<double>::infinity();
        if (!(cond_A <= m.robot.max_condition)) {
            throw Error("Simbody spatial model: the actuation map is singular at sample " + std::to_string(s));
        }
        tau.row(static_cast<::Eigen::Index>(s)) = svd.solve(F).transpose();

        const ::Eigen::VectorXd q = toEigen(m.state.getQ());
        step = s == 0 ? ::Eigen::VectorXd::Zero(nv) : ::Eigen::VectorXd(q - q_prev);
        q_prev = q;
        p_prev = p[s];
    }
    return tau;
}

}  // namespace nocdyn::validation
