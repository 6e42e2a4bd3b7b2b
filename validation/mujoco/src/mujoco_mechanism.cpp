// MuJoCo model of a general planar parallel robot and its rigid inverse dynamics (see
// mujoco_mechanism.hpp and nocdyn/validation/detail/mechanism_common.hpp).
//
// Only the description's home data and PoseTrajectory are taken from nocdyn; every posture,
// velocity and acceleration of the joints, and every force, comes from MuJoCo.
#include "nocdyn/validation/mujoco_mechanism.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstring>
#include <iomanip>
#include <numbers>
#include <sstream>

#include <Eigen/Dense>

#include "nocdyn/error.hpp"
#include "nocdyn/validation/detail/mechanism_common.hpp"

namespace nocdyn::validation {

namespace {

constexpr int kNewtonMaxIter = 30;
// Largest change of a passive joint [rad or m] between the predicted seed and the solution
// accepted as the continuation of the same branch; a larger step is subdivided.
constexpr double kMaxJump = 0.05;
constexpr int kMaxHalvings = 8;
// Out-of-plane principal inertias never enter planar motion; they only make the tensor
// physical (positive, triangle inequality).
constexpr double kOutOfPlaneInertia = 1e-6;
// MuJoCo rejects a moving body without rotational inertia (a slider's, given as 0): it gets
// this token value, whose torque (1e-12 times an angular acceleration) is far below the
// accuracy of any comparison.
constexpr double kMinInertia = 1e-12;

std::string bodyName(int limb, int link) { return "limb" + std::to_string(limb + 1) + "_body" + std::to_string(link); }
std::string jointName(int limb, int joint) {
    return "limb" + std::to_string(limb + 1) + "_joint" + std::to_string(joint + 1);
}

void writeInertial(std::ostringstream& x, const std::string& indent, double mass, double inertia,
                   const Eigen::Vector2d& com) {
    const double side = std::max(kOutOfPlaneInertia, inertia);
    x << indent << "<inertial pos=\"" << com.x() << " " << com.y() << " 0\" mass=\"" << mass << "\" diaginertia=\""
      << side << " " << side << " " << std::max(kMinInertia, inertia) << "\"/>\n";
}

void writeJoint(std::ostringstream& x, const std::string& indent, const std::string& name,
                const JointDescription& joint) {
    // a joint spring (drive or flexure): MuJoCo's joint stiffness, at rest at home (springref 0)
    std::ostringstream spring;
    spring << std::setprecision(17);
    if (joint.stiffness && *joint.stiffness > 0.0) spring << " stiffness=\"" << *joint.stiffness << "\"";
    if (joint.type == JointType::revolute) {
        x << indent << "<joint name=\"" << name << "\" type=\"hinge\" pos=\"" << joint.point.x() << " "
          << joint.point.y() << " 0\" axis=\"0 0 1\"" << spring.str() << "/>\n";
    } else {
        x << indent << "<joint name=\"" << name << "\" type=\"slide\" axis=\"" << joint.direction.x() << " "
          << joint.direction.y() << " 0\"" << spring.str() << "/>\n";
    }
}

std::string anchorSite(int limb, bool outboard) {
    return "limb" + std::to_string(limb + 1) + (outboard ? "_closure_out" : "_closure_in");
}

/// One limb body (link 1 or 2) with its joint, nesting the next body of the chain.
void writeChain(std::ostringstream& x, const RobotDescription& robot, int j, int c,
                const std::vector<int>& links_in_order, const std::string& indent, std::size_t i) {
    if (i == links_in_order.size()) return;
    const LimbDescription& limb = robot.limbs[static_cast<std::size_t>(j)];
    const int link = links_in_order[i];
    // Forward link k is carried by joint k-1; reversed link k by joint k (0-based joints).
    const int joint = link <= c ? link - 1 : link;
    const BodyDescription& body = limb.bodies[static_cast<std::size_t>(link - 1)];
    const JointDescription& jd = limb.joints[static_cast<std::size_t>(joint)];
    x << indent << "<body name=\"" << bodyName(j, link) << "\" pos=\"0 0 0\">\n";
    writeJoint(x, indent + "  ", jointName(j, joint), jd);
    writeInertial(x, indent + "  ", body.mass, body.inertia, body.com);
    const Eigen::Vector2d& p = limb.joints[static_cast<std::size_t>(c)].point;
    if (link == c)
        x << indent << "  <site name=\"" << anchorSite(j, false) << "\" pos=\"" << p.x() << " " << p.y() << " 0\"/>\n";
    if (link == c + 1)
        x << indent << "  <site name=\"" << anchorSite(j, true) << "\" pos=\"" << p.x() << " " << p.y() << " 0\"/>\n";
    writeChain(x, robot, j, c, links_in_order, indent + "  ", i + 1);
    x << indent << "</body>\n";
}

std::string buildMjcf(const RobotDescription& robot, const std::vector<int>& closure) {
    const int L = static_cast<int>(robot.limbs.size());
    const Eigen::Vector3d& home = robot.home;
    const Eigen::Vector2d C(home[1], home[2]);
    const Eigen::Vector2d com = C + Eigen::Rotation2Dd(home[0]).toRotationMatrix() * robot.platform.com;
    const bool gravity = robot.gravity.squaredNorm() > 0.0;
    std::ostringstream x;
    x << std::setprecision(17);
    x << "<mujoco model=\"nocdyn-"
      << "mechanism"
      << "\">\n"
      << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
      << "  <option gravity=\"" << robot.gravity.x() << " " << robot.gravity.y()
      << " 0\" timestep=\"0.0001\" jacobian=\"dense\" integrator=\"Euler\">\n"
      << "    <flag contact=\"disable\" frictionloss=\"disable\" limit=\"disable\""
      << (gravity ? "" : " gravity=\"disable\"") << "/>\n"
      << "  </option>\n"
      << "  <default>\n"
      << "    <joint damping=\"0\" armature=\"0\" frictionloss=\"0\" limited=\"false\"/>\n"
      << "  </default>\n"
      << "  <worldbody>\n";
    for (int j = 0; j < L; ++j) {
        const int c = closure[static_cast<std::size_t>(j)];
        const Eigen::Vector2d& p = robot.limbs[static_cast<std::size_t>(j)].joints[static_cast<std::size_t>(c)].point;
        if (c == 0)
            x << "    <site name=\"" << anchorSite(j, false) << "\" pos=\"" << p.x() << " " << p.y() << " 0\"/>\n";
        std::vector<int> forward;  // links 1..c from the world
        for (int k = 1; k <= c; ++k) forward.push_back(k);
        writeChain(x, robot, j, c, forward, "    ", 0);
    }
    x << "    <body name=\"platform\" pos=\"0 0 0\">\n"
      << "      <joint name=\"platform_x\" type=\"slide\" axis=\"1 0 0\"/>\n"
      << "      <joint name=\"platform_y\" type=\"slide\" axis=\"0 1 0\"/>\n"
      << "      <joint name=\"platform_theta\" type=\"hinge\" pos=\"" << C.x() << " " << C.y()
      << " 0\" axis=\"0 0 1\"/>\n";
    writeInertial(x, "      ", robot.platform.mass, robot.platform.inertia, com);
    for (int j = 0; j < L; ++j) {
        const int c = closure[static_cast<std::size_t>(j)];
        const Eigen::Vector2d& p = robot.limbs[static_cast<std::size_t>(j)].joints[static_cast<std::size_t>(c)].point;
        if (c == 2)
            x << "      <site name=\"" << anchorSite(j, true) << "\" pos=\"" << p.x() << " " << p.y() << " 0\"/>\n";
        std::vector<int> reversed;  // links 2..c+1 from the platform
        for (int k = 2; k >= c + 1; --k) reversed.push_back(k);
        writeChain(x, robot, j, c, reversed, "      ", 0);
    }
    x << "    </body>\n"
      << "  </worldbody>\n"
      << "  <equality>\n";
    for (int j = 0; j < L; ++j) {
        const int c = closure[static_cast<std::size_t>(j)];
        const Eigen::Vector2d& p = robot.limbs[static_cast<std::size_t>(j)].joints[static_cast<std::size_t>(c)].point;
        const std::string out = c == 2 ? std::string("platform") : bodyName(j, c + 1);
        x << "    <connect name=\"loop" << j + 1 << "\" body1=\"" << out << "\"";
        if (c > 0) x << " body2=\"" << bodyName(j, c) << "\"";
        x << " anchor=\"" << p.x() << " " << p.y() << " 0\"/>\n";
    }
    x << "  </equality>\n"
      << "</mujoco>\n";
    return x.str();
}

mjModel* compileFromMemory(const std::string& xml, const std::string& robot_name) {
    // MuJoCo 2.2.2 loads from a virtual file system: one in-memory file, no disk access.
    auto vfs = std::make_unique<mjVFS>();  // ~2 MB: keep it off the stack
    mj_defaultVFS(vfs.get());
    const char* filename = "nocdyn_mechanism.xml";
    if (mj_makeEmptyFileVFS(vfs.get(), filename, static_cast<int>(xml.size())) != 0) {
        throw Error("MuJoCo model of robot '" + robot_name + "': cannot create the in-memory file");
    }
    const int id = mj_findFileVFS(vfs.get(), filename);
    if (id < 0) {
        mj_deleteVFS(vfs.get());
        throw Error("MuJoCo model of robot '" + robot_name + "': in-memory file not found");
    }
    std::memcpy(vfs->filedata[id], xml.data(), xml.size());
    std::array<char, 1024> err{};
    mjModel* m = mj_loadXML(filename, vfs.get(), err.data(), static_cast<int>(err.size()));
    mj_deleteVFS(vfs.get());
    if (m == nullptr) {
        throw Error("MuJoCo could not compile the model of robot '" + robot_name + "': " + std::string(err.data()));
    }
    return m;
}

}  // namespace

struct MujocoMechanism::Impl {
    RobotDescription robot;
    std::vector<int> closure;
    std::string xml;
    mjModel* m = nullptr;
    mjData* d = nullptr;

    detail::TreeIndices tree;
    Eigen::MatrixXd rows;
    std::vector<int> free_v;                 // passive dofs (= qpos addresses)
    std::vector<int> eq_row;                 // first efc row of connect j
    std::vector<std::array<int, 2>> anchor;  // sites: inboard, outboard
    double tol = 0.0;
    double potential_home = 0.0;
    long plant_steps = 0;

    ~Impl() {
        if (d != nullptr) mj_deleteData(d);
        if (m != nullptr) mj_deleteModel(m);
    }

    int id(mjtObj type, const std::string& name) const {
        const int i = mj_name2id(m, type, name.c_str());
        if (i < 0) throw Error("MuJoCo model: '" + name + "' missing");
        return i;
    }
    int dof(const std::string& joint) const {
        const int jid = id(mjOBJ_JOINT, joint);
        if (m->jnt_qposadr[jid] != m->jnt_dofadr[jid]) throw Error("MuJoCo model: qpos/dof order");
        return m->jnt_dofadr[jid];
    }

    void init() {
        const int L = static_cast<int>(robot.limbs.size());
        if (m->nq != m->nv || m->neq != L) throw Error("MuJoCo model: unexpected sizes");
        tree.nv = m->nv;
        tree.platform_v = {dof("platform_theta"), dof("platform_x"), dof("platform_y")};
        for (int j = 0; j < L; ++j) {
            std::array<int, 3> v{-1, -1, -1};
            for (int k = 0; k < 3; ++k) {
                if (k == closure[static_cast<std::size_t>(j)]) continue;
                v[static_cast<std::size_t>(k)] = dof(jointName(j, k));
            }
            tree.joint_v.push_back(v);
            anchor.push_back({id(mjOBJ_SITE, anchorSite(j, false)), id(mjOBJ_SITE, anchorSite(j, true))});
        }
        for (int i = 0; i < m->nv; ++i) {
            if (i != tree.platform_v[0] && i != tree.platform_v[1] && i != tree.platform_v[2]) free_v.push_back(i);
        }
        rows = detail::jointRateRows(robot, closure, tree);
        double scale = 1.0;
        for (const auto& limb : robot.limbs)
            for (const auto& joint : limb.joints) scale = std::max(scale, joint.point.cwiseAbs().maxCoeff());
        tol = 1e-14 * scale;

        mj_resetData(m, d);
        positionStage();
        if (d->nefc != 3 * L) throw Error("MuJoCo model: expected " + std::to_string(3 * L) + " constraint rows");
        eq_row.assign(static_cast<std::size_t>(L), -1);
        for (int i = 0; i < d->nefc; ++i) {
            if (d->efc_type[i] != mjCNSTR_EQUALITY) throw Error("MuJoCo model: non-equality constraint");
            auto& row = eq_row[static_cast<std::size_t>(d->efc_id[i])];
            if (row < 0) row = i;
        }
        const double r0 = residual().cwiseAbs().maxCoeff();
        if (!(r0 < 1e-12)) {
            std::ostringstream msg;
            msg << where(robot, 0) << "MuJoCo model: the home posture is not assembled (loop error " << r0 << " m)";
            throw Error(msg.str());
        }
        potential_home = potential();
    }

    void positionStage() {
        mj_kinematics(m, d);
        mj_comPos(m, d);
        mj_makeConstraint(m, d);
    }
    // x, y rows of every connect: residual and Jacobian (dense efc_J).
    Eigen::VectorXd residual() const {
        const int L = static_cast<int>(eq_row.size());
        Eigen::VectorXd r(2 * L);
        for (int j = 0; j < L; ++j) {
            r(2 * j) = d->efc_pos[eq_row[static_cast<std::size_t>(j)]];
            r(2 * j + 1) = d->efc_pos[eq_row[static_cast<std::size_t>(j)] + 1];
        }
        return r;
    }
    Eigen::MatrixXd jacobian() const {
        const int L = static_cast<int>(eq_row.size());
        Eigen::MatrixXd G(2 * L, m->nv);
        for (int j = 0; j < L; ++j) {
            for (int c = 0; c < 2; ++c) {
                const mjtNum* row =
                    d->efc_J + static_cast<std::ptrdiff_t>(eq_row[static_cast<std::size_t>(j)] + c) * m->nv;
                for (int i = 0; i < m->nv; ++i) G(2 * j + c, i) = row[i];
            }
        }
        return G;
    }
    Eigen::MatrixXd freeColumns(const Eigen::MatrixXd& G) const {
        Eigen::MatrixXd Gf(G.rows(), static_cast<Eigen::Index>(free_v.size()));
        for (std::size_t c = 0; c < free_v.size(); ++c) Gf.col(static_cast<Eigen::Index>(c)) = G.col(free_v[c]);
        return Gf;
    }
    Eigen::MatrixXd platformColumns(const Eigen::MatrixXd& G) const {
        Eigen::MatrixXd Gp(G.rows(), 3);
        for (int c = 0; c < 3; ++c) Gp.col(c) = G.col(tree.platform_v[static_cast<std::size_t>(c)]);
        return Gp;
    }
    Eigen::VectorXd qpos() const { return Eigen::Map<const Eigen::VectorXd>(d->qpos, m->nq); }
    void setPose(const Eigen::Vector3d& p) {
        const Eigen::Vector3d q = p - robot.home;
        for (int i = 0; i < 3; ++i) d->qpos[tree.platform_v[static_cast<std::size_t>(i)]] = q[i];
    }
    double potential() const {
        // -sum m g . c over the bodies (world excluded), from MuJoCo's body c.o.m. positions.
        double V = 0.0;
        for (int b = 1; b < m->nbody; ++b) {
            V -= m->body_mass[b] * (robot.gravity.x() * d->xipos[3 * b] + robot.gravity.y() * d->xipos[3 * b + 1]);
        }
        return V;
    }

    /// Newton for the passive joints at pose p from `seed` (qpos); true when converged within
    /// kMaxJump of the seed. Leaves the position stage evaluated at the solution.
    bool newton(const Eigen::Vector3d& p, const Eigen::VectorXd& seed) {
        for (int i = 0; i < m->nq; ++i) d->qpos[i] = seed[i];
        setPose(p);
        for (int it = 0; it < kNewtonMaxIter; ++it) {
            positionStage();
            const Eigen::VectorXd r = residual();
            if (!r.allFinite()) return false;
            if (r.cwiseAbs().maxCoeff() <= tol) {
                double jump = 0.0;
                for (int i : free_v) jump = std::max(jump, std::abs(d->qpos[i] - seed[i]));
                return jump <= kMaxJump;
            }
            const Eigen::VectorXd step = freeColumns(jacobian()).partialPivLu().solve(r);
            if (!step.allFinite()) return false;
            for (std::size_t c = 0; c < free_v.size(); ++c) d->qpos[free_v[c]] -= step[static_cast<Eigen::Index>(c)];
        }
        return false;
    }

    void assemble(double t, const Eigen::Vector3d& p, const Eigen::VectorXd& seed, const Eigen::Vector3d& p_from,
                  const Eigen::VectorXd& q_from) {
        if (newton(p, seed)) return;
        for (int halvings = 1; halvings <= kMaxHalvings; ++halvings) {
            const int pieces = 1 << halvings;
            Eigen::VectorXd q = q_from;
            bool ok = true;
            for (int s = 1; s <= pieces && ok; ++s) {
                ok = newton(p_from + (p - p_from) * (static_cast<double>(s) / pieces), q);
                if (ok) q = qpos();
            }
            if (ok) return;
        }
        std::ostringstream msg;
        msg << "MuJoCo model: cannot assemble the pose [theta=" << p[0] << " rad, x=" << p[1] << " m, y=" << p[2]
            << " m] at t=" << t << " s on the home branch (out of reach or singular)";
        throw Error(msg.str());
    }

    // Body accelerations at qacc = 0 without gravity (the velocity-product part only):
    // cacc_b = cacc_parent + sum cdof_dot qvel, the forward pass of mj_rnePostConstraint.
    void velocityProductAccelerations() {
        mju_zero(d->cacc, 6);
        for (int b = 1; b < m->nbody; ++b) {
            mjtNum* acc = d->cacc + 6 * b;
            mju_copy(acc, d->cacc + 6 * m->body_parentid[b], 6);
            const int adr = m->body_dofadr[b];
            for (int k = 0; k < m->body_dofnum[b]; ++k)
                mju_addToScl(acc, d->cdof_dot + 6 * (adr + k), d->qvel[adr + k], 6);
        }
    }
};

MujocoMechanism::MujocoMechanism(const RobotDescription& robot) : impl_(std::make_unique<Impl>()) {
    Impl& s = *impl_;
    s.robot = robot;
    validate(s.robot);
    for (int j = 0; j < static_cast<int>(s.robot.limbs.size()); ++j)
        s.closure.push_back(detail::closureJoint(s.robot, j, false));
    s.xml = buildMjcf(s.robot, s.closure);
    s.m = compileFromMemory(s.xml, s.robot.name);
    s.d = mj_makeData(s.m);
    if (s.d == nullptr) throw Error("MuJoCo: mj_makeData failed for robot '" + s.robot.name + "'");
    s.init();
}

MujocoMechanism::~MujocoMechanism() = default;
MujocoMechanism::MujocoMechanism(MujocoMechanism&&) noexcept = default;
MujocoMechanism& MujocoMechanism::operator=(MujocoMechanism&&) noexcept = default;

std::string MujocoMechanism::mjcf() const { return impl_->xml; }
int MujocoMechanism::actuatorCount() const { return impl_->robot.actuatorCount(); }

std::vector<MechanismSample> MujocoMechanism::inverseDynamics(const PoseTrajectory& trajectory,
                                                              const std::vector<double>& times) {
    Impl& s = *impl_;
    const mjModel* m = s.m;
    mjData* d = s.d;
    const int nv = m->nv;
    const int n = s.robot.actuatorCount();
    const int L = static_cast<int>(s.robot.limbs.size());
    std::vector<MechanismSample> out;
    out.reserve(times.size());

    // Continuation from home; the seed is the previous solution moved along the previous
    // velocity map S (qvel_free = S dp) to first order.
    Eigen::VectorXd q_prev = Eigen::VectorXd::Zero(nv);
    Eigen::Vector3d p_prev = s.robot.home;
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(s.free_v.size()), 3);
    Eigen::VectorXd h(nv), mv(nv);
    for (const double t : times) {
        Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        Eigen::VectorXd seed = q_prev;
        const Eigen::VectorXd step = S * (p - p_prev);
        for (std::size_t c = 0; c < s.free_v.size(); ++c) seed[s.free_v[c]] += step[static_cast<Eigen::Index>(c)];
        s.assemble(t, p, seed, p_prev, q_prev);
        // mjData holds the position stage at the solution.
        const Eigen::VectorXd q = s.qpos();
        const Eigen::MatrixXd G = s.jacobian();
        const Eigen::MatrixXd Gp = s.platformColumns(G);
        const Eigen::PartialPivLU<Eigen::MatrixXd> lu(s.freeColumns(G));
        S = lu.solve(-Gp);

        // Velocities: G qvel = 0 with the platform rates prescribed.
        const Eigen::VectorXd qvel_free = S * dp;
        for (std::size_t c = 0; c < s.free_v.size(); ++c)
            d->qvel[s.free_v[c]] = qvel_free[static_cast<Eigen::Index>(c)];
        for (int i = 0; i < 3; ++i) d->qvel[s.tree.platform_v[static_cast<std::size_t>(i)]] = dp[i];
        mj_comVel(m, d);

        // Accelerations: G qacc + dG/dt qvel = 0, the bias being the connect anchors' relative
        // acceleration at qacc = 0 (outboard minus inboard, as efc_pos).
        s.velocityProductAccelerations();
        Eigen::VectorXd bias(2 * L);
        for (int j = 0; j < L; ++j) {
            mjtNum a_in[6], a_out[6];
            mj_objectAcceleration(m, d, mjOBJ_SITE, s.anchor[static_cast<std::size_t>(j)][0], a_in, 0);
            mj_objectAcceleration(m, d, mjOBJ_SITE, s.anchor[static_cast<std::size_t>(j)][1], a_out, 0);
            bias(2 * j) = a_out[3] - a_in[3];
            bias(2 * j + 1) = a_out[4] - a_in[4];
        }
        const Eigen::VectorXd qacc_free = lu.solve(-(Gp * ddp) - bias);
        for (std::size_t c = 0; c < s.free_v.size(); ++c)
            d->qacc[s.free_v[c]] = qacc_free[static_cast<Eigen::Index>(c)];
        for (int i = 0; i < 3; ++i) d->qacc[s.tree.platform_v[static_cast<std::size_t>(i)]] = ddp[i];

        // h = M qacc + c - Q_gravity (mj_rne's bias includes gravity).
        mj_rne(m, d, 1, h.data());
        const Eigen::VectorXd qvel = Eigen::Map<const Eigen::VectorXd>(d->qvel, nv);
        const Eigen::VectorXd qacc = Eigen::Map<const Eigen::VectorXd>(d->qacc, nv);
        const detail::ForceDistribution forces =
            detail::distributeForces(s.robot, s.tree, G, s.rows, qvel, h, t, "MuJoCo", detail::Friction::fromRows);

        MechanismSample sample;
        sample.t = t;
        sample.pose =
            Eigen::Vector3d(q[s.tree.platform_v[0]], q[s.tree.platform_v[1]], q[s.tree.platform_v[2]]) + s.robot.home;
        sample.u.resize(n);
        sample.du.resize(n);
        sample.ddu.resize(n);
        int a = 0;
        for (std::size_t j = 0; j < s.robot.limbs.size(); ++j) {
            for (std::size_t k = 0; k < 3; ++k) {
                if (!s.robot.limbs[j].joints[k].actuated) continue;
                const auto row = s.rows.row(static_cast<Eigen::Index>(3 * j + k));
                sample.u[a] = row.dot(q);
                sample.du[a] = row.dot(qvel);
                sample.ddu[a] = row.dot(qacc);
                ++a;
            }
        }
        sample.tau = forces.tau;
        sample.dissipation = forces.dissipation;
        sample.condition = forces.condition;
        // 0.5 qvel^T M qvel with MuJoCo's joint-space inertia (mj_crb, mj_mulM).
        mj_crb(m, d);
        mj_mulM(m, d, mv.data(), d->qvel);
        sample.kinetic = 0.5 * qvel.dot(mv);
        sample.potential = s.potential() - s.potential_home;
        out.push_back(std::move(sample));

        q_prev = q;
        p_prev = p;
    }
    return out;
}

}  // namespace nocdyn::validation

namespace nocdyn::validation {

void MujocoMechanism::resetPlant(const Eigen::Vector3d& pose, const Eigen::Vector3d& pose_rate, double t) {
    Impl& s = *impl_;
    mjModel* m = s.m;
    mjData* d = s.d;
    if (s.robot.motion == PlatformMotion::translation)
        throw Error(where(s.robot, 0) +
                    "the forward-dynamics plant does not take a two-DOF robot (motion: translation): its point tool's "
                    "free angle has no inertia");
    for (std::size_t j = 0; j < s.robot.limbs.size(); ++j) {
        for (std::size_t k = 0; k < 3; ++k) {
            const JointDescription& joint = s.robot.limbs[j].joints[k];
            if (joint.damping != 0.0 || joint.friction != 0.0)
                throw Error(where(s.robot, 0) + "limb " + std::to_string(j + 1) + ", joint " + std::to_string(k + 1) +
                            ": the MuJoCo plant does not model joint friction");
        }
    }
    if (!pose.allFinite() || !pose_rate.allFinite() || !std::isfinite(t))
        throw Error("MuJoCo plant: the initial state is not finite");
    // the stiffest soft constraint MuJoCo recommends: time constant two steps, critically damped
    for (int i = 0; i < m->neq; ++i) {
        m->eq_solref[mjNREF * i] = 2.0 * m->opt.timestep;
        m->eq_solref[mjNREF * i + 1] = 1.0;
    }
    mj_resetData(m, d);
    s.assemble(t, pose, Eigen::VectorXd::Zero(m->nq), s.robot.home, Eigen::VectorXd::Zero(m->nq));
    // G qvel = 0 with the platform rates given
    const Eigen::MatrixXd G = s.jacobian();
    const Eigen::VectorXd qvel_free = s.freeColumns(G).partialPivLu().solve(-(s.platformColumns(G) * pose_rate));
    for (int i = 0; i < m->nv; ++i) d->qvel[i] = 0.0;
    for (std::size_t c = 0; c < s.free_v.size(); ++c) d->qvel[s.free_v[c]] = qvel_free[static_cast<Eigen::Index>(c)];
    for (int i = 0; i < 3; ++i) d->qvel[s.tree.platform_v[static_cast<std::size_t>(i)]] = pose_rate[i];
    mju_zero(d->qfrc_applied, m->nv);
    d->time = t;
    s.plant_steps = 0;
}

void MujocoMechanism::setActuatorForces(const Eigen::VectorXd& tau) {
    Impl& s = *impl_;
    const int n = s.robot.actuatorCount();
    if (tau.size() != n)
        throw Error("MuJoCo plant: " + std::to_string(tau.size()) + " actuator forces for " + std::to_string(n) +
                    " actuators");
    // generalised force Q = sum_a tau_a r_a, r_a the row giving u_a from the tree coordinates
    Eigen::Map<Eigen::VectorXd> Q(s.d->qfrc_applied, s.m->nv);
    Q.setZero();
    int a = 0;
    for (std::size_t j = 0; j < s.robot.limbs.size(); ++j) {
        for (std::size_t k = 0; k < 3; ++k) {
            if (!s.robot.limbs[j].joints[k].actuated) continue;
            Q += tau[a++] * s.rows.row(static_cast<Eigen::Index>(3 * j + k)).transpose();
        }
    }
}

void MujocoMechanism::advance(double dt) {
    Impl& s = *impl_;
    const double h = s.m->opt.timestep;
    if (!(dt >= 0.0) || !(dt / h < 1e9)) throw Error("MuJoCo plant: cannot advance by " + std::to_string(dt) + " s");
    const long steps = std::lround(dt / h);
    for (long k = 0; k < steps; ++k) {
        mj_step(s.m, s.d);
        if (s.d->warning[mjWARN_BADQACC].number > 0) {
            std::ostringstream msg;
            msg << "MuJoCo plant: unstable acceleration at t=" << s.d->time << " s";
            throw Error(msg.str());
        }
    }
    s.plant_steps += steps;
}

double MujocoMechanism::time() const { return impl_->d->time; }

Eigen::Vector3d MujocoMechanism::pose() const {
    const Impl& s = *impl_;
    const auto& v = s.tree.platform_v;
    return Eigen::Vector3d(s.d->qpos[v[0]], s.d->qpos[v[1]], s.d->qpos[v[2]]) + s.robot.home;
}

double MujocoMechanism::loopError() const {
    Impl& s = *impl_;
    s.positionStage();
    return s.residual().cwiseAbs().maxCoeff();
}

long MujocoMechanism::plantSteps() const { return impl_->plant_steps; }

std::vector<MujocoMechanism::LinearMode> MujocoMechanism::linearModes(const Eigen::Vector3d& pose, double timestep) {
    Impl& s = *impl_;
    mjModel* m = s.m;
    for (std::size_t j = 0; j < s.robot.limbs.size(); ++j) {
        const JointDescription& joint = s.robot.limbs[j].joints[static_cast<std::size_t>(s.closure[j])];
        if (joint.stiffness && *joint.stiffness > 0.0)
            throw Error("MuJoCo plant: limb " + std::to_string(j + 1) +
                        "'s spring is at its loop closure, which MuJoCo's connect cannot carry");
    }
    if (!(timestep > 0.0)) throw Error("MuJoCo plant: the linearisation's time step must be positive");
    const double saved_timestep = m->opt.timestep, saved_tolerance = m->opt.tolerance;
    const int saved_flags = m->opt.disableflags;
    const std::vector<mjtNum> saved_spring(m->qpos_spring, m->qpos_spring + m->nq);
    m->opt.timestep = timestep;  // the constraints' time constant follows: solref [2 h, 1]
    m->opt.disableflags |= mjDSBL_GRAVITY;
    m->opt.tolerance = 0.0;  // the solver to its iteration limit: no tolerance in the differences
    resetPlant(pose);
    for (int i = 0; i < m->nq; ++i) m->qpos_spring[i] = s.d->qpos[i];  // springref at the pose
    const int nv = m->nv;
    Eigen::Matrix<mjtNum, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> A(2 * nv, 2 * nv);
    mjd_transitionFD(m, s.d, 1e-6, 1, A.data(), nullptr, nullptr, nullptr);
    m->opt.timestep = saved_timestep;
    m->opt.tolerance = saved_tolerance;
    m->opt.disableflags = saved_flags;
    std::copy(saved_spring.begin(), saved_spring.end(), m->qpos_spring);
    resetPlant(pose);
    // semi-implicit Euler: v' = v + h a(q, v), q' = q + h v', so A's velocity rows are exactly
    // [h a_q, I + h a_v]: the continuous-time A_c = [[0, I], [a_q, a_v]]
    const double h = timestep;
    Eigen::MatrixXd Ac = Eigen::MatrixXd::Zero(2 * nv, 2 * nv);
    Ac.topRightCorner(nv, nv).setIdentity();
    Ac.bottomLeftCorner(nv, nv) = A.bottomLeftCorner(nv, nv) / h;
    Ac.bottomRightCorner(nv, nv) = (A.bottomRightCorner(nv, nv) - Eigen::MatrixXd::Identity(nv, nv)) / h;
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(Ac, false);
    std::vector<LinearMode> modes;
    for (Eigen::Index i = 0; i < eig.eigenvalues().size(); ++i) {
        const std::complex<double> lambda = eig.eigenvalues()(i);
        if (!(lambda.imag() > 0.0)) continue;  // one of each conjugate pair; real ones are no oscillation
        modes.push_back({std::abs(lambda) / (2.0 * std::numbers::pi), -lambda.real() / std::abs(lambda)});
    }
    std::sort(modes.begin(), modes.end(),
              [](const LinearMode& a, const LinearMode& b) { return a.frequency < b.frequency; });
    return modes;
}

MujocoMechanism::PlatformDerivatives MujocoMechanism::platformDerivatives(double eps, double h, double impedance) {
    Impl& s = *impl_;
    mjModel* m = s.m;
    mjData* d = s.d;
    const int nv = m->nv;
    const int n = s.robot.actuatorCount();
    const auto& pv = s.tree.platform_v;
    const Eigen::VectorXd qpos0 = Eigen::Map<const Eigen::VectorXd>(d->qpos, nv);
    const Eigen::VectorXd qvel0 = Eigen::Map<const Eigen::VectorXd>(d->qvel, nv);
    const Eigen::VectorXd qfrc0 = Eigen::Map<const Eigen::VectorXd>(d->qfrc_applied, nv);
    const double t0 = d->time;
    const Eigen::Vector3d pose0 = pose();
    Eigen::Vector3d rate0;
    for (int i = 0; i < 3; ++i) rate0[i] = qvel0[pv[static_cast<std::size_t>(i)]];
    const auto restore = [&] {
        Eigen::Map<Eigen::VectorXd>(d->qpos, nv) = qpos0;
        Eigen::Map<Eigen::VectorXd>(d->qvel, nv) = qvel0;
        Eigen::Map<Eigen::VectorXd>(d->qfrc_applied, nv) = qfrc0;
        d->time = t0;
    };
    // V: the loop-consistent qvel of each unit platform rate (G qvel = 0)
    const auto velocityMap = [&] {
        s.positionStage();
        const Eigen::MatrixXd G = s.jacobian();
        const Eigen::MatrixXd Vf = s.freeColumns(G).partialPivLu().solve(-s.platformColumns(G));
        Eigen::MatrixXd V = Eigen::MatrixXd::Zero(nv, 3);
        for (std::size_t c = 0; c < s.free_v.size(); ++c) V.row(s.free_v[c]) = Vf.row(static_cast<Eigen::Index>(c));
        for (int i = 0; i < 3; ++i) V(pv[static_cast<std::size_t>(i)], i) = 1.0;
        return V;
    };
    const Eigen::MatrixXd V = velocityMap();
    // d qvel/d p at fixed dp/dt: centred differences of the assembled states
    Eigen::MatrixXd dqvel_dp(nv, 3);
    for (int i = 0; i < 3; ++i) {
        Eigen::VectorXd plus, minus;
        for (const double sign : {1.0, -1.0}) {
            resetPlant(pose0 + sign * h * Eigen::Vector3d::Unit(i), rate0, t0);
            (sign > 0 ? plus : minus) = Eigen::Map<const Eigen::VectorXd>(d->qvel, nv);
        }
        dqvel_dp.col(i) = (plus - minus) / (2.0 * h);
    }
    resetPlant(pose0, rate0, t0);
    restore();
    // the loops' impedance, restored below
    const std::ptrdiff_t neq = m->neq;
    const std::vector<double> solimp(m->eq_solimp, m->eq_solimp + mjNIMP * neq);
    for (std::ptrdiff_t i = 0; i < neq; ++i) {
        m->eq_solimp[mjNIMP * i] = impedance;
        m->eq_solimp[mjNIMP * i + 1] = impedance;
    }
    PlatformDerivatives out;
    mj_forward(m, d);
    for (int i = 0; i < 3; ++i) out.ddp[i] = d->qacc[pv[static_cast<std::size_t>(i)]];
    // A: (2 nv) x (2 nv), row-major; rows [dqpos_next; dqvel_next], columns [dqpos; dqvel]
    std::vector<mjtNum> A(static_cast<std::size_t>(4 * nv * nv));
    mjd_transitionFD(m, d, eps, 1, A.data(), nullptr, nullptr, nullptr);
    restore();
    const double dt = m->opt.timestep;
    Eigen::MatrixXd dqacc(3, 2 * nv);  // d qacc/d(qpos, qvel) of the platform's rows
    for (int r = 0; r < 3; ++r) {
        const int row = nv + pv[static_cast<std::size_t>(r)];
        for (int c = 0; c < 2 * nv; ++c) {
            const double identity = c == row ? 1.0 : 0.0;
            dqacc(r, c) =
                (A[static_cast<std::size_t>(row) * 2 * static_cast<std::size_t>(nv) + static_cast<std::size_t>(c)] -
                 identity) /
                dt;
        }
    }
    out.d_p = dqacc.leftCols(nv) * V + dqacc.rightCols(nv) * dqvel_dp;
    out.d_dp = dqacc.rightCols(nv) * V;
    // d_tau: qacc is linear in qfrc_applied = sum_a tau_a r_a
    out.d_tau.resize(3, n);
    for (int a = 0; a < n; ++a) {
        Eigen::Vector3d plus, minus;
        for (const double sign : {1.0, -1.0}) {
            Eigen::VectorXd tau = Eigen::VectorXd::Zero(n);
            tau[a] = sign;
            setActuatorForces(tau);
            Eigen::Map<Eigen::VectorXd>(d->qfrc_applied, nv) += qfrc0;
            mj_forward(m, d);
            for (int i = 0; i < 3; ++i) (sign > 0 ? plus : minus)[i] = d->qacc[pv[static_cast<std::size_t>(i)]];
            restore();
        }
        out.d_tau.col(a) = (plus - minus) / 2.0;
    }
    std::copy(solimp.begin(), solimp.end(), m->eq_solimp);
    mj_forward(m, d);
    return out;
}

}  // namespace nocdyn::validation
