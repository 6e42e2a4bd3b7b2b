// Independent Simbody model of a general planar parallel robot. See the header for the model
// and nocdyn/validation/detail/mechanism_common.hpp for the tree layout and force balance.
//
// Nothing from nocdyn's kinematics or dynamics is used: the model is built from the home
// posture of the description, where every body frame coincides with Ground's.
#include "nocdyn/validation/simbody_mechanism.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Dense>
#include <Simbody.h>

#include "nocdyn/error.hpp"
#include "nocdyn/validation/detail/mechanism_common.hpp"
#include "plant_integration.hpp"

namespace nocdyn::validation {
namespace {

// Constraint errors are lengths [m]: far below the 1e-9 relative accuracy of the comparisons.
constexpr double kProjectAccuracy = 1e-14;
// Largest change of a passive coordinate [rad or m] between the extrapolated seed and the
// solution accepted as the continuation of the same branch; a larger step is subdivided.
constexpr double kMaxJump = 0.05;
// Subdivision of a failed step into up to 2^kMaxHalvings pieces in pose space.
constexpr int kMaxHalvings = 8;

SimTK::Vec3 toVec3(const ::Eigen::Vector2d& v) { return {v.x(), v.y(), 0.0}; }

/// Body whose frame coincides with Ground's at home: c.o.m. and central inertia given there.
SimTK::Body::Rigid rigidBody(double mass, double inertia, const ::Eigen::Vector2d& com) {
    using namespace SimTK;
    const Vec3 c = toVec3(com);
    return Body::Rigid(MassProperties(mass, c, Inertia(inertia).shiftFromMassCenter(-c, mass)));
}

/// The platform's Planar coordinates [theta, x, y] - home, prescribed (values set from outside).
class PlatformMotion final : public SimTK::Motion::Custom::Implementation {
public:
    ::Eigen::Vector3d q = ::Eigen::Vector3d::Zero();
    ::Eigen::Vector3d qdot = ::Eigen::Vector3d::Zero();
    ::Eigen::Vector3d qdotdot = ::Eigen::Vector3d::Zero();

    SimTK::Motion::Level getLevel(const SimTK::State&) const override { return SimTK::Motion::Position; }
    void calcPrescribedPosition(const SimTK::State&, int nq, SimTK::Real* out) const override {
        for (int i = 0; i < nq && i < 3; ++i) out[i] = q[i];
    }
    void calcPrescribedPositionDot(const SimTK::State&, int nq, SimTK::Real* out) const override {
        for (int i = 0; i < nq && i < 3; ++i) out[i] = qdot[i];
    }
    void calcPrescribedPositionDotDot(const SimTK::State&, int nq, SimTK::Real* out) const override {
        for (int i = 0; i < nq && i < 3; ++i) out[i] = qdotdot[i];
    }
};

/// Joint friction -(damping q' + friction sign q') of every joint as Simbody forces: a mobility
/// force on a tree joint's mobilizer (mobility = sign q), equal and opposite body torques on
/// the two links of a closure joint (q' = their relative angular velocity).
class JointFriction final : public SimTK::Force::Custom::Implementation {
public:
    struct Joint {
        const JointDescription* joint = nullptr;
        SimTK::MobilizedBody mobilizer;  // tree joint
        double sign = 1.0;
        SimTK::MobilizedBody inboard, outboard;  // closure joint
        bool closure = false;
    };
    std::vector<Joint> joints;

    /// Rate q' of a joint at a state realized to Velocity.
    static double rate(const Joint& j, const SimTK::State& s) {
        if (!j.closure) return j.sign * j.mobilizer.getOneU(s, SimTK::MobilizerUIndex(0));
        return j.outboard.getBodyAngularVelocity(s)[2] - j.inboard.getBodyAngularVelocity(s)[2];
    }
    /// Power lost in friction at a state realized to Velocity [W].
    double dissipation(const SimTK::State& s) const {
        double P = 0.0;
        for (const Joint& j : joints) {
            const double qd = rate(j, s);
            P += qd * detail::jointFriction(*j.joint, qd);
        }
        return -P;
    }
    void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>& body_forces, SimTK::Vector_<SimTK::Vec3>&,
                   SimTK::Vector& mobility_forces) const override {
        for (const Joint& j : joints) {
            const double f = detail::jointFriction(*j.joint, rate(j, s));
            if (f == 0.0) continue;
            if (!j.closure) {
                j.mobilizer.applyOneMobilityForce(s, 0, j.sign * f, mobility_forces);
            } else {
                j.outboard.applyBodyTorque(s, SimTK::Vec3(0, 0, f), body_forces);
                j.inboard.applyBodyTorque(s, SimTK::Vec3(0, 0, -f), body_forces);
            }
        }
    }
    SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0.0; }
};

::Eigen::VectorXd toEigen(const SimTK::Vector& v) {
    ::Eigen::VectorXd out(v.size());
    for (int i = 0; i < v.size(); ++i) out[i] = v[i];
    return out;
}

}  // namespace

class SimbodyMechanism::Impl {
public:
    explicit Impl(const RobotDescription& description);

    RobotDescription robot;
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter;
    SimTK::GeneralForceSubsystem forces;
    SimTK::Force::DiscreteForces actuation;  // the plant's actuator forces (held in its State)
    SimTK::MobilizedBody::Planar platform;
    JointFriction* friction = nullptr;  // owned by the force subsystem
    PlatformMotion* motion = nullptr;   // owned by motion_handle
    SimTK::Motion::Custom motion_handle;
    SimTK::State state;

    std::vector<int> closure;
    std::vector<std::array<SimTK::MobilizedBody, 4>> links;       // per limb: ground, body 1, body 2, platform
    std::vector<std::array<SimTK::MobilizedBody, 3>> mobilizers;  // per limb and tree joint
    std::vector<SimTK::Constraint::PointOnLine> closures;         // per limb: its loop closure
    detail::TreeIndices tree;
    ::Eigen::MatrixXd rows;   // joint rate rows (3 L x nu)
    std::vector<int> free_q;  // the passive tree coordinates
    double potential_home = 0.0;

    // forward-dynamics plant
    SimTK::State plant;                 // the platform's Motion disabled
    std::vector<std::size_t> actuated;  // per actuator (file order): its joint 3 j + k
    std::unique_ptr<SimTK::RungeKuttaMersonIntegrator> integrator;
    detail::PlantIntegration run;
    SimTK::Vector mobility_forces;                  // setActuatorForces' workspace
    SimTK::Vector_<SimTK::SpatialVec> body_forces;  // setActuatorForces' workspace

    /// The plant's current state (the integrator's while it runs).
    [[nodiscard]] const SimTK::State& current() const;
    /// Actuator a's joint rate row applied to the tree coordinates or rates x: u_a or du_a.
    [[nodiscard]] double actuatedRate(std::size_t a, const SimTK::Vector& x) const {
        const auto row = rows.row(static_cast<::Eigen::Index>(actuated[a]));
        double sum = 0.0;
        for (::Eigen::Index i = 0; i < row.size(); ++i) sum += row[i] * x[static_cast<int>(i)];
        return sum;
    }

    /// Newton projection of the passive coordinates from `seed` with the platform at pose p;
    /// true when it converged within kMaxJump of the seed.
    bool tryAssemble(const ::Eigen::Vector3d& p, const ::Eigen::VectorXd& seed);
    /// Assembles at pose p: from `seed`, else by subdividing the way from (p_from, q_from).
    void assemble(double t, const ::Eigen::Vector3d& p, const ::Eigen::VectorXd& seed, const ::Eigen::Vector3d& p_from,
                  const ::Eigen::VectorXd& q_from);
    /// Velocities with the platform's rate prescribed (the Motion's qdot), after assemble().
    void projectVelocities();
    /// Applies the actuator forces tau (file order) to `s` as the plant does: DiscreteForces.
    void applyActuatorForces(SimTK::State& s, const ::Eigen::VectorXd& tau);
    /// Every joint's reaction (MechanismSample::reactions) at the inverse-dynamics state realized
    /// to Acceleration with the actuator forces applied.
    [[nodiscard]] std::vector<::Eigen::Vector3d> jointReactions() const;
};

SimbodyMechanism::Impl::Impl(const RobotDescription& description)
    : robot(description), matter(system), forces(system), actuation(forces, matter) {
    using namespace SimTK;
    validate(robot);
    const ::Eigen::Vector3d& home = robot.home;
    const ::Eigen::Vector2d C(home[1], home[2]);
    const ::Eigen::Matrix2d Rh = ::Eigen::Rotation2Dd(home[0]).toRotationMatrix();
    const Vec3 c_home(home[1], home[2], 0.0);
    platform = MobilizedBody::Planar(
        matter.Ground(), Transform(c_home),
        rigidBody(robot.platform.mass, robot.platform.inertia, C + Rh * robot.platform.com), Transform(c_home));

    const int L = static_cast<int>(robot.limbs.size());
    friction = new JointFriction();
    links.resize(static_cast<std::size_t>(L));
    mobilizers.resize(static_cast<std::size_t>(L));
    for (int j = 0; j < L; ++j) {
        const LimbDescription& limb = robot.limbs[static_cast<std::size_t>(j)];
        const int c = detail::closureJoint(robot, j, true);
        closure.push_back(c);
        auto& link = links[static_cast<std::size_t>(j)];
        link[0] = matter.Ground();
        link[3] = platform;
        // A mobilizer for joint k between `parent` and the new link `child_index`.
        auto mobilize = [&](int k, MobilizedBody& parent, int child_index) {
            const JointDescription& joint = limb.joints[static_cast<std::size_t>(k)];
            const BodyDescription& body = limb.bodies[static_cast<std::size_t>(child_index - 1)];
            const Body::Rigid info = rigidBody(body.mass, body.inertia, body.com);
            MobilizedBody mob;
            if (joint.type == JointType::revolute) {
                const Transform X(toVec3(joint.point));
                mob = MobilizedBody::Pin(parent, X, info, X);
            } else {
                const double angle = std::atan2(joint.direction.y(), joint.direction.x());
                const Transform X(Rotation(angle, ZAxis), toVec3(joint.point));
                mob = MobilizedBody::Slider(parent, X, info, X);
            }
            link[static_cast<std::size_t>(child_index)] = mob;
            mobilizers[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)] = mob;
        };
        for (int k = 0; k < c; ++k) mobilize(k, link[static_cast<std::size_t>(k)], k + 1);
        for (int k = 2; k > c; --k) mobilize(k, link[static_cast<std::size_t>(k + 1)], k);
        const Vec3 axis = toVec3(limb.joints[static_cast<std::size_t>(c)].point);
        closures.push_back(Constraint::PointOnLine(link[static_cast<std::size_t>(c)], UnitVec3(ZAxis), axis,
                                                   link[static_cast<std::size_t>(c + 1)], axis));
        for (int k = 0; k < 3; ++k) {
            JointFriction::Joint f;
            f.joint = &robot.limbs[static_cast<std::size_t>(j)].joints[static_cast<std::size_t>(k)];
            if (k == c) {
                f.closure = true;
                f.inboard = link[static_cast<std::size_t>(c)];
                f.outboard = link[static_cast<std::size_t>(c + 1)];
            } else {
                f.mobilizer = mobilizers[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
                f.sign = k < c ? 1.0 : -1.0;
            }
            friction->joints.push_back(f);
        }
    }
    Force::UniformGravity(forces, matter, Vec3(robot.gravity.x(), robot.gravity.y(), 0.0));
    Force::Custom(forces, friction);

    motion = new PlatformMotion();
    motion_handle = Motion::Custom(platform, motion);

    system.realizeTopology();
    state = system.getDefaultState();
    system.realize(state, Stage::Instance);
    if (state.getNQ() != state.getNU()) throw Error("Simbody model: nq != nu");

    tree.nv = state.getNU();
    for (int i = 0; i < 3; ++i) tree.platform_v[static_cast<std::size_t>(i)] = platform.getFirstUIndex(state) + i;
    if (platform.getFirstQIndex(state) != platform.getFirstUIndex(state)) throw Error("Simbody model: q/u order");
    for (int j = 0; j < L; ++j) {
        std::array<int, 3> v{-1, -1, -1};
        for (int k = 0; k < 3; ++k) {
            if (k == closure[static_cast<std::size_t>(j)]) continue;
            const MobilizedBody& mob = mobilizers[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
            v[static_cast<std::size_t>(k)] = mob.getFirstUIndex(state);
            if (mob.getFirstQIndex(state) != v[static_cast<std::size_t>(k)]) throw Error("Simbody model: q/u order");
            free_q.push_back(v[static_cast<std::size_t>(k)]);
        }
        tree.joint_v.push_back(v);
    }
    rows = detail::jointRateRows(robot, closure, tree);

    // Home is assembled with every coordinate 0.
    system.realize(state, Stage::Position);
    const double err = state.getQErr().size() > 0 ? SimTK::max(SimTK::abs(state.getQErr())) : 0.0;
    if (!(err < 1e-12)) {
        std::ostringstream msg;
        msg << where(robot, 0) << "Simbody model: the home posture is not assembled (loop error " << err << " m)";
        throw Error(msg.str());
    }
    potential_home = system.calcPotentialEnergy(state);

    plant = system.getDefaultState();
    motion_handle.disable(plant);
    system.realize(plant, Stage::Instance);
    for (int j = 0; j < L; ++j) {
        for (int k = 0; k < 3; ++k) {
            if (robot.limbs[static_cast<std::size_t>(j)].joints[static_cast<std::size_t>(k)].actuated)
                actuated.push_back(static_cast<std::size_t>(3 * j + k));
        }
    }
    integrator = std::make_unique<RungeKuttaMersonIntegrator>(system);
    mobility_forces.resize(plant.getNU());
    body_forces.resize(matter.getNumBodies());
}

bool SimbodyMechanism::Impl::tryAssemble(const ::Eigen::Vector3d& p, const ::Eigen::VectorXd& seed) {
    using namespace SimTK;
    motion->q = p - robot.home;
    // The prescribed q are evaluated when the Time stage is realized: invalidate it, since
    // the pose changed behind the state's back.
    state.invalidateAll(SimTK::Stage::Time);
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
        // One more full Newton step leaves the constraint errors at round-off level.
        system.projectQ(state, no_error_estimate, forced, results);
    } catch (const std::exception&) {
        return false;
    }
    double jump = 0.0;
    for (int i : free_q) {
        const double qi = state.getQ()[i];
        if (!std::isfinite(qi)) return false;
        jump = std::max(jump, std::abs(qi - seed[i]));
    }
    const double err = SimTK::max(SimTK::abs(state.getQErr()));
    return jump <= kMaxJump && err < 1e-10;
}

void SimbodyMechanism::Impl::assemble(double t, const ::Eigen::Vector3d& p, const ::Eigen::VectorXd& seed,
                                      const ::Eigen::Vector3d& p_from, const ::Eigen::VectorXd& q_from) {
    if (tryAssemble(p, seed)) return;
    for (int halvings = 1; halvings <= kMaxHalvings; ++halvings) {
        const int pieces = 1 << halvings;
        ::Eigen::VectorXd q = q_from;
        bool ok = true;
        for (int s = 1; s <= pieces && ok; ++s) {
            const ::Eigen::Vector3d ps = p_from + (p - p_from) * (static_cast<double>(s) / pieces);
            ok = tryAssemble(ps, q);
            if (ok) q = toEigen(state.getQ());
        }
        if (ok) return;
    }
    std::ostringstream msg;
    msg << "Simbody model: cannot assemble the pose [theta=" << p[0] << " rad, x=" << p[1] << " m, y=" << p[2]
        << " m] at t=" << t << " s on the home branch (out of reach or singular)";
    throw Error(msg.str());
}

void SimbodyMechanism::Impl::projectVelocities() {
    using namespace SimTK;
    ProjectOptions forced(kProjectAccuracy);
    forced.setOption(ProjectOptions::ForceFullNewton);
    forced.setOption(ProjectOptions::ForceProjection);
    Vector no_error_estimate;
    ProjectResults results;
    system.prescribeU(state);
    system.realize(state, Stage::Velocity);
    // The velocity constraints are linear in u: one full Newton step solves them.
    system.projectU(state, no_error_estimate, forced, results);
}

void SimbodyMechanism::Impl::applyActuatorForces(SimTK::State& s, const ::Eigen::VectorXd& tau) {
    using namespace SimTK;
    // a mobility force along a tree joint's mobility (sign: reversed joints), equal and opposite
    // torques across a closure joint, as the joint friction
    mobility_forces = 0.0;
    body_forces = SpatialVec(Vec3(0), Vec3(0));
    for (std::size_t a = 0; a < actuated.size(); ++a) {
        const JointFriction::Joint& j = friction->joints[actuated[a]];
        const double f = tau[static_cast<::Eigen::Index>(a)];
        if (!j.closure) {
            j.mobilizer.applyOneMobilityForce(s, 0, j.sign * f, mobility_forces);
        } else {
            j.outboard.applyBodyTorque(s, Vec3(0, 0, f), body_forces);
            j.inboard.applyBodyTorque(s, Vec3(0, 0, -f), body_forces);
        }
    }
    actuation.setAllMobilityForces(s, mobility_forces);
    actuation.setAllBodyForces(s, body_forces);
}

std::vector<::Eigen::Vector3d> SimbodyMechanism::Impl::jointReactions() const {
    using namespace SimTK;
    Vector_<SpatialVec> at_M;  // on each mobilized body from its parent, at its M origin, in Ground
    matter.calcMobilizerReactionForces(state, at_M);
    std::vector<::Eigen::Vector3d> out;
    for (std::size_t j = 0; j < robot.limbs.size(); ++j) {
        const LimbDescription& limb = robot.limbs[j];
        const auto c = static_cast<std::size_t>(closure[j]);
        for (std::size_t k = 0; k < 3; ++k) {
            const JointDescription& joint = limb.joints[k];
            const MobilizedBody& outboard = links[j][k + 1];
            Vec3 n_O, f;  // F_k: the inboard link's wrench on the outboard link, about O, in Ground
            if (k == c) {
                // the closure: minus the constraint's body force (Simbody's constraint forces
                // have the sign of the left-hand side) on the follower, the outboard link
                const Constraint::PointOnLine& con = closures[j];
                const Vector_<SpatialVec> forces = con.getConstrainedBodyForcesAsVector(state);
                for (ConstrainedBodyIndex b(0); b < con.getNumConstrainedBodies(); ++b) {
                    const MobilizedBody& body = con.getMobilizedBodyFromConstrainedBody(b);
                    if (body.getMobilizedBodyIndex() != outboard.getMobilizedBodyIndex()) continue;
                    f = -forces[b][1];
                    n_O = -forces[b][0] + body.getBodyOriginLocation(state) % f;
                }
            } else {
                const MobilizedBody& mob = mobilizers[j][k];
                const SpatialVec& R = at_M[mob.getMobilizedBodyIndex()];
                // M's origin is at the joint's point on the child (the frames coincide at home)
                const Vec3 p_M = mob.findStationLocationInGround(state, Vec3(joint.point.x(), joint.point.y(), 0.0));
                // forward (k < c): the child is the outboard link; reversed: the inboard one
                const double sign = k < c ? 1.0 : -1.0;
                f = sign * R[1];
                n_O = sign * (R[0] + p_M % R[1]);
            }
            if (joint.type == JointType::revolute) {
                out.emplace_back(f[0], f[1], 0.0);
            } else {
                // the slider's axis, fixed in both links, and the outboard link's mass centre
                const Vec3 d = outboard.getBodyRotation(state) * Vec3(joint.direction.x(), joint.direction.y(), 0.0);
                const Vec3 x = outboard.findMassCenterLocationInGround(state);
                const Vec3 normal = f - (~d * f) * d;
                out.emplace_back(normal[0], normal[1], n_O[2] - (x % f)[2]);
            }
        }
    }
    return out;
}

SimbodyMechanism::SimbodyMechanism(const RobotDescription& robot) : impl_(std::make_unique<Impl>(robot)) {}
SimbodyMechanism::~SimbodyMechanism() = default;
SimbodyMechanism::SimbodyMechanism(SimbodyMechanism&&) noexcept = default;
SimbodyMechanism& SimbodyMechanism::operator=(SimbodyMechanism&&) noexcept = default;

int SimbodyMechanism::actuatorCount() const { return impl_->robot.actuatorCount(); }

std::vector<MechanismSample> SimbodyMechanism::inverseDynamics(const PoseTrajectory& trajectory,
                                                               const std::vector<double>& times) {
    using namespace SimTK;
    Impl& m = *impl_;
    const int nv = m.tree.nv;
    const int n = m.robot.actuatorCount();
    std::vector<MechanismSample> out;
    out.reserve(times.size());

    // Continuation from home: the previous solution, extrapolated to second order in time.
    ::Eigen::VectorXd q_prev = ::Eigen::VectorXd::Zero(nv), u_prev = q_prev, a_prev = q_prev;
    ::Eigen::Vector3d p_prev = m.robot.home;
    double t_prev = 0.0;
    bool have_prev = false;
    Matrix G;
    Vector h;
    for (const double t : times) {
        Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        ::Eigen::VectorXd seed = q_prev;
        if (have_prev) {
            const double dt = t - t_prev;
            seed += dt * u_prev + 0.5 * dt * dt * a_prev;
        }
        // Simbody evaluates the Motion's rate at the Position stage and its acceleration at
        // the Velocity stage: both are set before the assembly realizes them.
        m.motion->qdot = dp;
        m.motion->qdotdot = ddp;
        m.state.setTime(t);
        m.assemble(t, p, seed, p_prev, q_prev);

        // Velocities and accelerations with the platform's rate and acceleration prescribed.
        m.projectVelocities();
        m.system.realize(m.state, Stage::Acceleration);

        const ::Eigen::VectorXd q = toEigen(m.state.getQ());
        const ::Eigen::VectorXd u = toEigen(m.state.getU());
        const ::Eigen::VectorXd udot = toEigen(m.state.getUDot());
        // h = M u' + c - Q_applied (gravity and joint friction); G the closure Jacobian.
        m.matter.calcResidualForceIgnoringConstraints(m.state, m.system.getMobilityForces(m.state, Stage::Dynamics),
                                                      m.system.getRigidBodyForces(m.state, Stage::Dynamics),
                                                      m.state.getUDot(), h);
        m.matter.calcG(m.state, G);
        ::Eigen::MatrixXd Ge(G.nrow(), G.ncol());
        for (int r = 0; r < G.nrow(); ++r)
            for (int c = 0; c < G.ncol(); ++c) Ge(r, c) = G(r, c);
        const detail::ForceDistribution forces = detail::distributeForces(m.robot, m.tree, Ge, m.rows, u, toEigen(h), t,
                                                                          "Simbody", detail::Friction::inApplied);

        MechanismSample s;
        s.t = t;
        s.pose =
            ::Eigen::Vector3d(q[m.tree.platform_v[0]], q[m.tree.platform_v[1]], q[m.tree.platform_v[2]]) + m.robot.home;
        s.u.resize(n);
        s.du.resize(n);
        s.ddu.resize(n);
        int a = 0;
        for (std::size_t j = 0; j < m.robot.limbs.size(); ++j) {
            for (std::size_t k = 0; k < 3; ++k) {
                if (!m.robot.limbs[j].joints[k].actuated) continue;
                const auto row = m.rows.row(static_cast<::Eigen::Index>(3 * j + k));
                s.u[a] = row.dot(q);
                s.du[a] = row.dot(u);
                s.ddu[a] = row.dot(udot);
                ++a;
            }
        }
        s.tau = forces.tau;
        s.dissipation = m.friction->dissipation(m.state);
        s.condition = forces.condition;
        s.kinetic = m.matter.calcKineticEnergy(m.state);
        s.potential = m.system.calcPotentialEnergy(m.state) - m.potential_home;
        // the reactions with the actuators driving: tau applied, the platform's prescribed
        // motion then takes no force (to rounding), the loops' constraints carry the rest
        m.applyActuatorForces(m.state, s.tau);
        m.system.realize(m.state, Stage::Acceleration);
        s.reactions = m.jointReactions();
        m.actuation.clearAllForces(m.state);
        out.push_back(std::move(s));

        q_prev = q;
        u_prev = u;
        a_prev = udot;
        p_prev = p;
        t_prev = t;
        have_prev = true;
    }
    return out;
}

}  // namespace nocdyn::validation

namespace nocdyn::validation {

void SimbodyMechanism::resetPlant(const ::Eigen::Vector3d& pose, const ::Eigen::Vector3d& pose_rate, double t) {
    using namespace SimTK;
    Impl& m = *impl_;
    if (m.robot.motion == ::nocdyn::PlatformMotion::translation)
        throw Error(where(m.robot, 0) +
                    "the forward-dynamics plant does not take a two-DOF robot (motion: translation): its point tool's "
                    "free angle has no inertia");
    // assembled with the platform prescribed (the inverse-dynamics State), then copied over
    m.motion->qdot = pose_rate;
    m.motion->qdotdot.setZero();
    m.state.setTime(t);
    const ::Eigen::VectorXd home_q = ::Eigen::VectorXd::Zero(m.tree.nv);
    m.assemble(t, pose, home_q, m.robot.home, home_q);
    m.projectVelocities();
    m.plant.setTime(t);
    m.plant.updQ() = m.state.getQ();
    m.plant.updU() = m.state.getU();
    m.actuation.clearAllForces(m.plant);
    m.run.reset();
    m.system.realize(m.plant, Stage::Velocity);
}

void SimbodyMechanism::setActuatorForces(const ::Eigen::VectorXd& tau) {
    using namespace SimTK;
    Impl& m = *impl_;
    if (tau.size() != static_cast<::Eigen::Index>(m.actuated.size())) {
        throw Error("Simbody plant: " + std::to_string(tau.size()) + " actuator forces for " +
                    std::to_string(m.actuated.size()) + " actuators");
    }
    // the same application as the joint friction's: a mobility force along a tree joint's
    // mobility (sign: reversed joints), equal and opposite torques across a closure joint
    State& s = m.run.forceState(*m.integrator, m.plant);
    m.mobility_forces = 0.0;
    m.body_forces = SpatialVec(Vec3(0), Vec3(0));
    for (std::size_t a = 0; a < m.actuated.size(); ++a) {
        const JointFriction::Joint& j = m.friction->joints[m.actuated[a]];
        const double f = tau[static_cast<::Eigen::Index>(a)];
        if (!j.closure) {
            j.mobilizer.applyOneMobilityForce(s, 0, j.sign * f, m.mobility_forces);
        } else {
            j.outboard.applyBodyTorque(s, Vec3(0, 0, f), m.body_forces);
            j.inboard.applyBodyTorque(s, Vec3(0, 0, -f), m.body_forces);
        }
    }
    m.actuation.setAllMobilityForces(s, m.mobility_forces);
    m.actuation.setAllBodyForces(s, m.body_forces);
    m.run.forcesChanged(*m.integrator);
}

void SimbodyMechanism::setIntegratorAccuracy(double accuracy) {
    impl_->run.setAccuracy(accuracy, *impl_->integrator, impl_->plant);
}

void SimbodyMechanism::advance(double dt) {
    Impl& m = *impl_;
    detail::advancePlant(*m.integrator, m.plant, m.run, dt);
}

const SimTK::State& SimbodyMechanism::Impl::current() const { return run.current(*integrator, plant); }

double SimbodyMechanism::time() const { return impl_->current().getTime(); }

::Eigen::VectorXd SimbodyMechanism::u() const {
    const SimTK::Vector& q = impl_->current().getQ();
    ::Eigen::VectorXd out(static_cast<::Eigen::Index>(impl_->actuated.size()));
    for (std::size_t a = 0; a < impl_->actuated.size(); ++a)
        out[static_cast<::Eigen::Index>(a)] = impl_->actuatedRate(a, q);
    return out;
}

::Eigen::VectorXd SimbodyMechanism::du() const {
    const SimTK::Vector& v = impl_->current().getU();
    ::Eigen::VectorXd out(static_cast<::Eigen::Index>(impl_->actuated.size()));
    for (std::size_t a = 0; a < impl_->actuated.size(); ++a)
        out[static_cast<::Eigen::Index>(a)] = impl_->actuatedRate(a, v);
    return out;
}

::Eigen::Vector3d SimbodyMechanism::pose() const {
    const auto& i = impl_->tree.platform_v;
    const SimTK::Vector& q = impl_->current().getQ();
    return ::Eigen::Vector3d(q[i[0]], q[i[1]], q[i[2]]) + impl_->robot.home;
}

::Eigen::Vector3d SimbodyMechanism::poseRate() const {
    const auto& i = impl_->tree.platform_v;
    const SimTK::Vector& u = impl_->current().getU();
    return {u[i[0]], u[i[1]], u[i[2]]};
}

double SimbodyMechanism::kineticEnergy() const {
    const SimTK::State& s = impl_->current();
    impl_->system.realize(s, SimTK::Stage::Velocity);
    return impl_->matter.calcKineticEnergy(s);
}

double SimbodyMechanism::potentialEnergy() const {
    const SimTK::State& s = impl_->current();
    impl_->system.realize(s, SimTK::Stage::Dynamics);
    return impl_->system.calcPotentialEnergy(s) - impl_->potential_home;
}

long SimbodyMechanism::plantSteps() const { return impl_->run.steps(*impl_->integrator); }

}  // namespace nocdyn::validation
