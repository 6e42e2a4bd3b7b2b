// MuJoCo model of the 3-PRR robot and its rigid inverse dynamics (see mujoco_robot.hpp).
//
// Only io::RobotParameters (geometry, masses, inertias) and PoseTrajectory are taken from nocdyn.
// The reference posture below is computed here from the robot's definition (model notes:
// R = b/sqrt3, r = a/sqrt3, d^M = (R - r)/2, phi_A = asin(d^M / l)); every other posture,
// velocity and acceleration of the joints, and every force, comes from MuJoCo.
//
// Rigid inverse dynamics per sample (mj_inverse is not used: its soft constraints drop the
// dJ/dt qvel term and report spurious constraint forces for prescribed closed-loop motion):
//  1. platform qpos = pose; the six other joint positions by Newton on the connect residuals
//     efc_pos (x, y rows) with the constraint Jacobian efc_J, each iterate evaluated by
//     mj_kinematics + mj_comPos + mj_makeConstraint (the position stage of mj_fwdPosition
//     that the result depends on); seed = previous solution + first-order predictor;
//  2. qvel from efc_J qvel = 0 with the platform rates prescribed; mj_comVel;
//  3. qacc from efc_J qacc = -dJ/dt qvel, the bias being the relative acceleration of the
//     connect anchors at qacc = 0 (MuJoCo's cdof_dot recursion for cacc, then
//     mj_objectAcceleration, which adds the omega x v term);
//  4. mj_rne(flg_acc = 1) gives M qacc + c; M qacc + c = B tau + efc_J^T lambda is solved for
//     lambda from the six non-actuated rows and then tau from the slider rows.
#include "nocdyn/prr3/mujoco_robot.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>

#include <Eigen/Dense>

#include "nocdyn/error.hpp"

namespace nocdyn::prr3 {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kLimbs = 3;
constexpr int kNv = 9;  // 3 sliders + 3 link hinges + platform (x, y, theta)
constexpr int kNewtonMaxIter = 30;
constexpr int kHomotopySteps = 16;

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Vector9 = Eigen::Matrix<double, 9, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix63 = Eigen::Matrix<double, 6, 3>;

/// Reference geometry of limb j, computed from the robot's definition only.
struct LimbReference {
    Eigen::Vector2d e;      // rail direction e_j
    Eigen::Vector2d a_ref;  // A_j at the reference posture
    Eigen::Vector2d m_ref;  // M_j at the reference posture (platform vertex, C = O)
    double link_angle = 0;  // angle of A_j -> M_j from the X axis at the reference
};

std::array<LimbReference, kLimbs> referenceGeometry(const io::RobotParameters& robot) {
    const double R = robot.base_side / std::sqrt(3.0);
    const double r = robot.platform_side / std::sqrt(3.0);
    const double dM = 0.5 * (R - r);
    const double phiA = std::asin(dM / robot.link_length);
    const std::array<double, kLimbs> phi = {0.0, 2.0 * kPi / 3.0, -2.0 * kPi / 3.0};
    std::array<LimbReference, kLimbs> limbs{};
    for (int j = 0; j < kLimbs; ++j) {
        LimbReference& L = limbs[static_cast<std::size_t>(j)];
        const double ph = phi[static_cast<std::size_t>(j)];
        L.e = {std::cos(ph), std::sin(ph)};
        L.m_ref = r * Eigen::Vector2d(std::cos(ph - kPi / 6.0), std::sin(ph - kPi / 6.0));
        L.link_angle = ph + phiA;
        L.a_ref = L.m_ref - robot.link_length * Eigen::Vector2d(std::cos(L.link_angle), std::sin(L.link_angle));
    }
    return limbs;
}

std::string indexedName(const char* base, int k) {
    std::string name(base);
    name.push_back(static_cast<char>('0' + k));
    return name;
}

std::string num(double v) {
    std::ostringstream s;
    s << std::setprecision(17) << v;
    return s.str();
}

std::string buildMjcf(const io::RobotParameters& robot) {
    const auto limbs = referenceGeometry(robot);
    // Out-of-plane principal inertias never enter planar motion; they only have to make a
    // physical (positive, triangle-inequality-satisfying) tensor. Sliders translate only:
    // their rotational inertia is a token value.
    const double slider_inertia = 1e-6;
    std::ostringstream x;
    x << std::setprecision(17);
    x << "<mujoco model=\"nocdyn-3prr-" << robot.name << "\">\n"
      << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
      << "  <option gravity=\"0 0 0\" timestep=\"0.0001\" jacobian=\"dense\" integrator=\"Euler\">\n"
      << "    <flag contact=\"disable\" gravity=\"disable\" frictionloss=\"disable\""
         " limit=\"disable\"/>\n"
      << "  </option>\n"
      << "  <default>\n"
      << "    <joint damping=\"0\" armature=\"0\" frictionloss=\"0\" limited=\"false\"/>\n"
      << "  </default>\n"
      << "  <worldbody>\n";
    for (int j = 0; j < kLimbs; ++j) {
        const LimbReference& L = limbs[static_cast<std::size_t>(j)];
        const int k = j + 1;
        const double h = 0.5 * L.link_angle;
        x << "    <!-- limb " << k << ": slider at A_" << k << "'s reference position, "
          << "qpos = u_" << k << " -->\n"
          << "    <body name=\"slider" << k << "\" pos=\"" << L.a_ref.x() << " " << L.a_ref.y() << " 0\">\n"
          << "      <joint name=\"u" << k << "\" type=\"slide\" axis=\"" << L.e.x() << " " << L.e.y() << " 0\"/>\n"
          << "      <inertial pos=\"0 0 0\" mass=\"" << robot.slider_mass << "\" diaginertia=\"" << slider_inertia
          << " " << slider_inertia << " " << slider_inertia << "\"/>\n"
          << "      <body name=\"link" << k << "\" pos=\"0 0 0\" quat=\"" << std::cos(h) << " 0 0 " << std::sin(h)
          << "\">\n"
          << "        <joint name=\"hinge" << k << "\" type=\"hinge\" axis=\"0 0 1\"/>\n"
          << "        <inertial pos=\"" << robot.link_com << " 0 0\" mass=\"" << robot.link_mass << "\" diaginertia=\""
          << robot.link_inertia << " " << robot.link_inertia << " " << robot.link_inertia << "\"/>\n"
          << "        <site name=\"tip" << k << "\" pos=\"" << robot.link_length << " 0 0\"/>\n"
          << "      </body>\n"
          << "    </body>\n";
    }
    x << "    <!-- platform: qpos = [x, y, theta] of its centroid C, reference at O -->\n"
      << "    <body name=\"platform\" pos=\"0 0 0\">\n"
      << "      <joint name=\"x\" type=\"slide\" axis=\"1 0 0\"/>\n"
      << "      <joint name=\"y\" type=\"slide\" axis=\"0 1 0\"/>\n"
      << "      <joint name=\"theta\" type=\"hinge\" axis=\"0 0 1\"/>\n"
      << "      <inertial pos=\"0 0 0\" mass=\"" << robot.platform_mass << "\" diaginertia=\"" << robot.platform_inertia
      << " " << robot.platform_inertia << " " << robot.platform_inertia << "\"/>\n";
    for (int j = 0; j < kLimbs; ++j) {
        const LimbReference& L = limbs[static_cast<std::size_t>(j)];
        x << "      <site name=\"M" << j + 1 << "\" pos=\"" << L.m_ref.x() << " " << L.m_ref.y() << " 0\"/>\n";
    }
    x << "    </body>\n"
      << "  </worldbody>\n"
      << "  <equality>\n";
    for (int j = 0; j < kLimbs; ++j) {
        x << "    <connect name=\"loop" << j + 1 << "\" body1=\"link" << j + 1 << "\" body2=\"platform\" anchor=\""
          << robot.link_length << " 0 0\"/>\n";
    }
    x << "  </equality>\n"
      << "</mujoco>\n";
    return x.str();
}

mjModel* compileFromMemory(const std::string& xml, const std::string& robot_name) {
    // MuJoCo 2.2.2 loads from a virtual file system: one in-memory file, no disk access.
    auto vfs = std::make_unique<mjVFS>();  // ~2 MB: keep it off the stack
    mj_defaultVFS(vfs.get());
    const char* filename = "nocdyn_3prr.xml";
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

struct MujocoRobot::Impl {
    io::RobotParameters robot;
    std::string xml;
    mjModel* m = nullptr;
    mjData* d = nullptr;
    std::array<LimbReference, kLimbs> limbs{};

    // dof addresses (nv index) and qpos addresses
    std::array<int, 6> dof_u{};  // sliders 1..3, hinges 1..3 (the unknowns)
    std::array<int, 6> qpos_u{};
    std::array<int, 3> dof_p{};  // platform, in pose order [theta, x, y]
    std::array<int, 3> qpos_p{};
    std::array<int, kLimbs> tip_site{};
    std::array<int, kLimbs> vertex_site{};
    std::array<int, kLimbs> slider_body{};
    std::array<int, kLimbs> eq_row{};  // first efc row of connect j (rows x, y, z)
    double tol = 0.0;                  // closure tolerance [m]

    // per-sample state (fixed size: no allocation)
    Vector6 seed = Vector6::Zero();
    double kinetic = 0.0;
    double residual = 0.0;
    Vector9 rne = Vector9::Zero();
    Vector9 mv = Vector9::Zero();
    Eigen::Matrix<double, 6, 3> S = Eigen::Matrix<double, 6, 3>::Zero();  // previous qvel_u / dp
    Eigen::Vector3d p_previous = Eigen::Vector3d::Zero();
    bool have_previous = false;
    bool energy_valid = false;

    ~Impl() {
        if (d != nullptr) mj_deleteData(d);
        if (m != nullptr) mj_deleteModel(m);
    }

    int jointId(const char* name) const {
        const int id = mj_name2id(m, mjOBJ_JOINT, name);
        if (id < 0) throw Error(std::string("MuJoCo model: joint '") + name + "' missing");
        return id;
    }
    int siteId(const std::string& name) const {
        const int id = mj_name2id(m, mjOBJ_SITE, name.c_str());
        if (id < 0) throw Error("MuJoCo model: site '" + name + "' missing");
        return id;
    }

    void init() {
        if (m->nv != kNv || m->nq != kNv || m->neq != kLimbs) {
            throw Error("MuJoCo model: unexpected sizes nq=" + std::to_string(m->nq) + " nv=" + std::to_string(m->nv) +
                        " neq=" + std::to_string(m->neq));
        }
        const std::array<const char*, 6> unknown = {"u1", "u2", "u3", "hinge1", "hinge2", "hinge3"};
        for (std::size_t i = 0; i < unknown.size(); ++i) {
            const int jid = jointId(unknown[i]);
            dof_u[i] = m->jnt_dofadr[jid];
            qpos_u[i] = m->jnt_qposadr[jid];
        }
        const std::array<const char*, 3> pose = {"theta", "x", "y"};
        for (std::size_t i = 0; i < pose.size(); ++i) {
            const int jid = jointId(pose[i]);
            dof_p[i] = m->jnt_dofadr[jid];
            qpos_p[i] = m->jnt_qposadr[jid];
        }
        for (int j = 0; j < kLimbs; ++j) {
            const auto k = static_cast<std::size_t>(j);
            tip_site[k] = siteId(indexedName("tip", j + 1));
            vertex_site[k] = siteId(indexedName("M", j + 1));
            slider_body[k] = mj_name2id(m, mjOBJ_BODY, indexedName("slider", j + 1).c_str());
        }
        tol = 1e-14 * std::max(1.0, robot.base_side);

        // Constraint rows: three equality rows (x, y, z) per connect, found by type and id.
        mj_resetData(m, d);
        mj_fwdPosition(m, d);
        if (d->nefc != 3 * kLimbs) {
            throw Error("MuJoCo model: expected 9 constraint rows, got " + std::to_string(d->nefc));
        }
        eq_row.fill(-1);
        for (int i = 0; i < d->nefc; ++i) {
            if (d->efc_type[i] != mjCNSTR_EQUALITY) throw Error("MuJoCo model: non-equality constraint");
            const int id = d->efc_id[i];
            if (eq_row[static_cast<std::size_t>(id)] < 0) eq_row[static_cast<std::size_t>(id)] = i;
        }
        // The model is drawn assembled: qpos0 = 0 must close every loop.
        const double r0 = closureResidual();
        if (!(r0 < 1e-12)) {
            throw Error("MuJoCo model of robot '" + robot.name + "' is not assembled at qpos0: loop residual " +
                        num(r0) + " m");
        }
    }

    // Residual rows (x, y of each connect): efc_pos after mj_makeConstraint.
    Vector6 residualVector() const {
        Vector6 r;
        for (int j = 0; j < kLimbs; ++j) {
            const int row = eq_row[static_cast<std::size_t>(j)];
            r(2 * j) = d->efc_pos[row];
            r(2 * j + 1) = d->efc_pos[row + 1];
        }
        return r;
    }
    double closureResidual() const {
        double worst = 0.0;
        for (int j = 0; j < kLimbs; ++j) {
            const int row = eq_row[static_cast<std::size_t>(j)];
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(d->efc_pos[row + c]));
        }
        return worst;
    }
    // Planar rows of efc_J (dense: nefc x nv), split into unknown and pose columns.
    void jacobians(Matrix6& Ju, Matrix63& Jp) const {
        for (int j = 0; j < kLimbs; ++j) {
            for (int c = 0; c < 2; ++c) {
                const mjtNum* row =
                    d->efc_J + static_cast<std::ptrdiff_t>(eq_row[static_cast<std::size_t>(j)] + c) * m->nv;
                for (int i = 0; i < 6; ++i) Ju(2 * j + c, i) = row[dof_u[static_cast<std::size_t>(i)]];
                for (int i = 0; i < 3; ++i) Jp(2 * j + c, i) = row[dof_p[static_cast<std::size_t>(i)]];
            }
        }
    }

    void setPose(const Eigen::Vector3d& p) {
        for (int i = 0; i < 3; ++i) d->qpos[qpos_p[static_cast<std::size_t>(i)]] = p(i);
    }
    void setUnknowns(const Vector6& q) {
        for (int i = 0; i < 6; ++i) d->qpos[qpos_u[static_cast<std::size_t>(i)]] = q(i);
    }
    Vector6 unknowns() const {
        Vector6 q;
        for (int i = 0; i < 6; ++i) q(i) = d->qpos[qpos_u[static_cast<std::size_t>(i)]];
        return q;
    }
    void positionStage() {
        mj_kinematics(m, d);
        mj_comPos(m, d);
        mj_makeConstraint(m, d);
    }

    // Newton on the connect residuals for the six unknown joint positions, platform fixed.
    bool newton(const Eigen::Vector3d& p, const Vector6& start) {
        setPose(p);
        setUnknowns(start);
        Matrix6 Ju;
        Matrix63 Jp;
        for (int it = 0; it < kNewtonMaxIter; ++it) {
            positionStage();
            if (d->nefc != 3 * kLimbs) return false;
            const Vector6 r = residualVector();
            if (!r.allFinite()) return false;
            if (r.cwiseAbs().maxCoeff() <= tol) return onBranch();
            jacobians(Ju, Jp);
            const Eigen::PartialPivLU<Matrix6> lu(Ju);
            const Vector6 step = lu.solve(r);
            if (!step.allFinite()) return false;
            setUnknowns(unknowns() - step);
        }
        return false;
    }

    // The working assembly mode (model notes, eq. 39): M_j ahead of A_j along e_j and on the
    // platform's side of the rail, i.e. phi_Aj in (0, pi/2).
    bool onBranch() const {
        for (int j = 0; j < kLimbs; ++j) {
            const auto k = static_cast<std::size_t>(j);
            const mjtNum* tip = d->site_xpos + 3 * tip_site[k];
            const mjtNum* a = d->xpos + 3 * slider_body[k];
            const Eigen::Vector2d mvec(tip[0] - a[0], tip[1] - a[1]);
            const Eigen::Vector2d& e = limbs[k].e;
            const Eigen::Vector2d n(-e.y(), e.x());
            if (!(mvec.dot(e) > 0.0) || !(mvec.dot(n) > 0.0)) return false;
        }
        return true;
    }

    // Continuation from the reference posture along the straight line in pose space, for a
    // first sample far from the seed or a seed that converged off the working branch.
    void solveByContinuation(const Eigen::Vector3d& p) {
        Vector6 q = Vector6::Zero();
        for (int s = 1; s <= kHomotopySteps; ++s) {
            const Eigen::Vector3d ps = p * (static_cast<double>(s) / kHomotopySteps);
            if (!newton(ps, q)) {
                std::ostringstream msg;
                msg << std::setprecision(10) << "MuJoCo model of robot '" << robot.name
                    << "': cannot assemble the pose theta=" << p(0) << " rad, x=" << p(1) << " m, y=" << p(2)
                    << " m on the working branch (outside the workspace or singular)";
                throw Error(msg.str());
            }
            q = unknowns();
        }
    }

    // Body accelerations at qacc = 0 (the velocity-product part only), the forward pass of
    // MuJoCo's mj_rnePostConstraint restricted to cacc: cacc_i = cacc_parent + cdof_dot qvel.
    // Gravity is disabled, so the world's acceleration is zero.
    void velocityProductAccelerations() {
        mju_zero(d->cacc, 6);
        for (int b = 1; b < m->nbody; ++b) {
            mjtNum* acc = d->cacc + 6 * b;
            mju_copy(acc, d->cacc + 6 * m->body_parentid[b], 6);
            const int adr = m->body_dofadr[b];
            for (int k = 0; k < m->body_dofnum[b]; ++k) {
                mju_addToScl(acc, d->cdof_dot + 6 * (adr + k), d->qvel[adr + k], 6);
            }
        }
    }

    void sample(const Eigen::Vector3d& p, const Eigen::Vector3d& dp, const Eigen::Vector3d& ddp, Eigen::Vector3d& u,
                Eigen::Vector3d& du, Eigen::Vector3d& ddu, Eigen::Vector3d& tau) {
        // 1. positions: loop closure by Newton on MuJoCo's connect residuals. The seed is the
        // previous solution moved to first order along the previous velocity map.
        const Vector6 predicted = have_previous ? Vector6(seed + S * (p - p_previous)) : seed;
        if (!newton(p, predicted)) solveByContinuation(p);
        // mjData now holds mj_kinematics, mj_comPos and mj_makeConstraint at the solution.
        seed = unknowns();
        p_previous = p;
        residual = closureResidual();

        Matrix6 Ju;
        Matrix63 Jp;
        jacobians(Ju, Jp);
        const Eigen::PartialPivLU<Matrix6> lu(Ju);
        S = lu.solve(-Jp);  // qvel_u = S dp
        have_previous = true;

        // 2. velocities: J qvel = 0  ->  Ju qvel_u = -Jp dp
        const Vector6 qvel_u = S * dp;
        for (int i = 0; i < 6; ++i) d->qvel[dof_u[static_cast<std::size_t>(i)]] = qvel_u(i);
        for (int i = 0; i < 3; ++i) d->qvel[dof_p[static_cast<std::size_t>(i)]] = dp(i);
        mj_comVel(m, d);  // cvel, cdof_dot: all that mj_rne and the bias below need
        energy_valid = false;

        // 3. accelerations: J qacc + dJ/dt qvel = 0. The bias dJ/dt qvel of each connect is
        // the relative acceleration of its two anchor points at qacc = 0: MuJoCo's body
        // accelerations at qacc = 0, converted to the points' classical accelerations
        // (with the omega x v term) by mj_objectAcceleration.
        velocityProductAccelerations();
        Vector6 bias;
        for (int j = 0; j < kLimbs; ++j) {
            const auto k = static_cast<std::size_t>(j);
            mjtNum a1[6], a2[6];
            mj_objectAcceleration(m, d, mjOBJ_SITE, tip_site[k], a1, 0);
            mj_objectAcceleration(m, d, mjOBJ_SITE, vertex_site[k], a2, 0);
            bias(2 * j) = a1[3] - a2[3];
            bias(2 * j + 1) = a1[4] - a2[4];
        }
        const Vector6 qacc_u = lu.solve(-(Jp * ddp) - bias);
        for (int i = 0; i < 6; ++i) d->qacc[dof_u[static_cast<std::size_t>(i)]] = qacc_u(i);
        for (int i = 0; i < 3; ++i) d->qacc[dof_p[static_cast<std::size_t>(i)]] = ddp(i);

        // 4. forces: M qacc + c = B tau + J^T lambda (planar connect rows). The six rows of the
        // hinge and platform dofs carry no actuator: they give lambda; the slider rows then
        // give tau = (M qacc + c)_slider - (J^T lambda)_slider.
        mj_rne(m, d, 1, rne.data());
        Matrix6 Jh;   // J columns of the non-actuated dofs (hinges, platform)
        Matrix63 Js;  // J columns of the sliders
        for (int r = 0; r < 6; ++r) {
            for (int i = 0; i < 3; ++i) {
                Js(r, i) = Ju(r, i);
                Jh(r, i) = Ju(r, 3 + i);
                Jh(r, 3 + i) = Jp(r, i);
            }
        }
        Vector6 f_rest;
        Eigen::Vector3d f_slider;
        for (int i = 0; i < 3; ++i) {
            f_slider(i) = rne(dof_u[static_cast<std::size_t>(i)]);
            f_rest(i) = rne(dof_u[static_cast<std::size_t>(3 + i)]);
            f_rest(3 + i) = rne(dof_p[static_cast<std::size_t>(i)]);
        }
        const Vector6 lambda = Jh.transpose().partialPivLu().solve(f_rest);
        tau = f_slider - Js.transpose() * lambda;

        u = seed.head<3>();
        du = qvel_u.head<3>();
        ddu = qacc_u.head<3>();
    }

    // 0.5 qvel^T M qvel with MuJoCo's joint-space inertia (mj_crb, mj_mulM) of the last sample.
    double kineticEnergy() {
        if (!energy_valid) {
            mj_crb(m, d);
            mj_mulM(m, d, mv.data(), d->qvel);
            kinetic = 0.5 * Eigen::Map<const Vector9>(d->qvel).dot(mv);
            energy_valid = true;
        }
        return kinetic;
    }
};

MujocoRobot::MujocoRobot(const io::RobotParameters& robot) : impl_(std::make_unique<Impl>()) {
    validate(robot);
    impl_->robot = robot;
    impl_->limbs = referenceGeometry(robot);
    impl_->xml = buildMjcf(robot);
    impl_->m = compileFromMemory(impl_->xml, robot.name);
    impl_->d = mj_makeData(impl_->m);
    if (impl_->d == nullptr) throw Error("MuJoCo: mj_makeData failed for robot '" + robot.name + "'");
    impl_->init();
}

MujocoRobot::~MujocoRobot() = default;
MujocoRobot::MujocoRobot(MujocoRobot&&) noexcept = default;
MujocoRobot& MujocoRobot::operator=(MujocoRobot&&) noexcept = default;

std::string MujocoRobot::mjcf() const { return impl_->xml; }

double MujocoRobot::lastKineticEnergy() const { return impl_->kineticEnergy(); }
double MujocoRobot::lastClosureResidual() const { return impl_->residual; }
void MujocoRobot::resetSeed() {
    impl_->seed.setZero();
    impl_->have_previous = false;
}

void MujocoRobot::inverseDynamicsSample(const Eigen::Vector3d& p, const Eigen::Vector3d& dp, const Eigen::Vector3d& ddp,
                                        Eigen::Vector3d& u, Eigen::Vector3d& du, Eigen::Vector3d& ddu,
                                        Eigen::Vector3d& tau) {
    impl_->sample(p, dp, ddp, u, du, ddu, tau);
}

std::vector<MujocoSample> MujocoRobot::inverseDynamics(const PoseTrajectory& trajectory,
                                                       const std::vector<double>& times) {
    std::vector<MujocoSample> out;
    out.reserve(times.size());
    resetSeed();
    for (const double t : times) {
        MujocoSample s;
        s.t = t;
        Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        s.pose = p;
        try {
            impl_->sample(p, dp, ddp, s.u, s.du, s.ddu, s.tau);
        } catch (const Error& e) {
            std::ostringstream msg;
            msg << "t = " << t << " s: " << e.what();
            throw Error(msg.str());
        }
        s.kinetic = impl_->kineticEnergy();
        s.closure_residual = impl_->residual;
        out.push_back(s);
    }
    return out;
}

}  // namespace nocdyn::prr3
