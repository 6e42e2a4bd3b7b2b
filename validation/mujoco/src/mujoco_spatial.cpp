// MuJoCo model of a spatial parallel robot and its rigid inverse dynamics (see
// mujoco_spatial.hpp for the model and the force balance). Only the description's home data are
// taken from nocdyn; every posture, velocity and acceleration of the joints, and every force,
// comes from MuJoCo.
#include "nocdyn/validation/mujoco_spatial.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <limits>
#include <sstream>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "nocdyn/error.hpp"

namespace nocdyn::validation {
namespace {

constexpr int kNewtonMaxIter = 30;
// Largest change of a passive coordinate [rad or m] between the predicted seed and the solution
// accepted as the continuation of the same branch; a larger step is subdivided.
constexpr double kMaxJump = 0.05;
constexpr int kMaxHalvings = 8;
// MuJoCo's compiler rejects a moving body whose mass or a principal moment is below 1e-15
// (mjMINVAL), or whose moments break a triangle inequality by any round-off (a slender rod's
// 0 + I = I): such a body gets this token mass, and its moments are all raised by what is
// missing plus this margin times the largest, far below any compared digit.
constexpr double kMinMass = 1e-12;
constexpr double kInertiaMargin = 1e-14;

std::string triple(const Eigen::Vector3d& v) {
    std::ostringstream x;
    x << std::setprecision(17) << v.x() << " " << v.y() << " " << v.z();
    return x.str();
}

/// The tensor MuJoCo accepts nearest to I: I + delta 1 with the smallest delta >= 0 that makes
/// every principal moment at least the margin and the triangle inequalities hold with it.
Eigen::Matrix3d admissibleInertia(const Eigen::Matrix3d& I) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (I + I.transpose()), Eigen::EigenvaluesOnly);
    const Eigen::Vector3d m = eig.eigenvalues();  // ascending
    const double margin = kInertiaMargin * std::max(1e-3, m[2]);
    const double missing = std::max({0.0, margin - m[0], m[2] - m[0] - m[1] + margin});
    return missing > 0.0 ? Eigen::Matrix3d(I + missing * Eigen::Matrix3d::Identity()) : I;
}

void writeInertial(std::ostringstream& x, const std::string& indent, double mass, const Eigen::Vector3d& com,
                   const Eigen::Matrix3d& inertia) {
    // Principal moments and axes by Eigen's solver, to round-off: MuJoCo's compiler would
    // diagonalise a fullinertia by Jacobi sweeps stopped at off-diagonal entries of 1e-12.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(admissibleInertia(inertia));
    Eigen::Matrix3d axes = eig.eigenvectors();
    if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
    const Eigen::Quaterniond q(axes);
    const Eigen::Vector3d moments = eig.eigenvalues();
    x << indent << "<inertial pos=\"" << triple(com) << "\" quat=\"" << q.w() << " " << q.x() << " " << q.y() << " "
      << q.z() << "\" mass=\"" << std::max(kMinMass, mass) << "\" diaginertia=\"" << triple(moments) << "\"/>\n";
}

std::string bodyName(std::size_t limb, std::size_t body) {
    return "limb" + std::to_string(limb + 1) + "_body" + std::to_string(body + 1);
}
std::string jointName(std::size_t limb, std::size_t joint, const char* part = "") {
    return "limb" + std::to_string(limb + 1) + "_joint" + std::to_string(joint + 1) + part;
}
std::string siteName(std::size_t limb, bool platform) {
    return "limb" + std::to_string(limb + 1) + (platform ? "_closure_platform" : "_closure_limb");
}

/// R = Rz(yaw) Ry(pitch) Rx(roll), the pose's orientation.
Eigen::Matrix3d rotation(double roll, double pitch, double yaw) {
    return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
}

std::string buildMjcf(const SpatialRobotDescription& robot) {
    const Eigen::Vector3d c_home = robot.home.head<3>();
    const Eigen::Matrix3d R_home = rotation(robot.home(3), robot.home(4), robot.home(5));
    const Eigen::Quaterniond q_home(R_home);
    const bool gravity = robot.gravity.squaredNorm() > 0.0;
    std::ostringstream x;
    x << std::setprecision(17);
    x << "<mujoco model=\"nocdyn-spatial\">\n"
      << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
      << "  <option gravity=\"" << triple(robot.gravity) << "\" timestep=\"0.0001\" jacobian=\"dense\">\n"
      << "    <flag contact=\"disable\" frictionloss=\"disable\" limit=\"disable\""
      << (gravity ? "" : " gravity=\"disable\"") << "/>\n"
      << "  </option>\n"
      << "  <default>\n"
      << "    <joint damping=\"0\" armature=\"0\" frictionloss=\"0\" limited=\"false\"/>\n"
      << "  </default>\n"
      << "  <worldbody>\n";
    for (std::size_t j = 0; j < robot.limbs.size(); ++j) {
        const SpatialLimbDescription& limb = robot.limbs[j];
        const std::size_t last = limb.joints.size() - 1;
        std::string indent = "    ";
        for (std::size_t k = 0; k < last; ++k) {
            const SpatialJointDescription& joint = limb.joints[k];
            x << indent << "<body name=\"" << bodyName(j, k) << "\" pos=\"0 0 0\">\n";
            const std::string in = indent + "  ";
            switch (joint.type) {
                case SpatialJointType::revolute:
                    x << in << "<joint name=\"" << jointName(j, k) << "\" type=\"hinge\" pos=\"" << triple(joint.point)
                      << "\" axis=\"" << triple(joint.axis) << "\"/>\n";
                    break;
                case SpatialJointType::prismatic:
                    x << in << "<joint name=\"" << jointName(j, k) << "\" type=\"slide\" axis=\""
                      << triple(joint.direction) << "\"/>\n";
                    break;
                case SpatialJointType::universal:
                    // a1 fixed in the inboard body, then a2 turned by a1: MuJoCo applies a body's
                    // joints in order, each about its axis in the frame the previous ones moved
                    x << in << "<joint name=\"" << jointName(j, k, "_a1") << "\" type=\"hinge\" pos=\""
                      << triple(joint.point) << "\" axis=\"" << triple(joint.axis1) << "\"/>\n"
                      << in << "<joint name=\"" << jointName(j, k, "_a2") << "\" type=\"hinge\" pos=\""
                      << triple(joint.point) << "\" axis=\"" << triple(joint.axis2) << "\"/>\n";
                    break;
                case SpatialJointType::spherical:
                    x << in << "<joint name=\"" << jointName(j, k) << "\" type=\"ball\" pos=\"" << triple(joint.point)
                      << "\"/>\n";
                    break;
            }
            const SpatialBodyDescription& body = limb.bodies[k];
            writeInertial(x, in, body.mass, body.com, body.inertia);
            indent = in;
        }
        x << indent << "<site name=\"" << siteName(j, false) << "\" pos=\"" << triple(limb.joints[last].point)
          << "\"/>\n";
        for (std::size_t k = last; k > 0; --k) {
            indent.resize(indent.size() - 2);
            x << indent << "</body>\n";
        }
    }
    x << "    <body name=\"platform\" pos=\"" << triple(c_home) << "\" quat=\"" << q_home.w() << " " << q_home.x()
      << " " << q_home.y() << " " << q_home.z() << "\">\n"
      << "      <joint name=\"platform\" type=\"free\"/>\n";
    writeInertial(x, "      ", robot.platform.mass, robot.platform.com, robot.platform.inertia);
    for (std::size_t j = 0; j < robot.limbs.size(); ++j) {
        const Eigen::Vector3d point = robot.limbs[j].joints.back().point;
        x << "      <site name=\"" << siteName(j, true) << "\" pos=\"" << triple(R_home.transpose() * (point - c_home))
          << "\"/>\n";
    }
    x << "    </body>\n"
      << "  </worldbody>\n"
      << "  <equality>\n";
    for (std::size_t j = 0; j < robot.limbs.size(); ++j) {
        const SpatialLimbDescription& limb = robot.limbs[j];
        const std::size_t last = limb.joints.size() - 1;
        // the anchor in body1's frame (the world's at home); MuJoCo puts body2's at qpos0 = home
        x << "    <connect name=\"loop" << j + 1 << "\" body1=\""
          << (last == 0 ? std::string("world") : bodyName(j, last - 1)) << "\" body2=\"platform\" anchor=\""
          << triple(limb.joints[last].point) << "\"/>\n";
    }
    x << "  </equality>\n"
      << "</mujoco>\n";
    return x.str();
}

mjModel* compileFromMemory(const std::string& xml, const std::string& robot_name) {
    // MuJoCo 2.2.2 loads from a virtual file system: one in-memory file, no disk access.
    auto vfs = std::make_unique<mjVFS>();  // ~2 MB: keep it off the stack
    mj_defaultVFS(vfs.get());
    const char* filename = "nocdyn_spatial.xml";
    if (mj_makeEmptyFileVFS(vfs.get(), filename, static_cast<int>(xml.size())) != 0)
        throw Error("MuJoCo spatial model of robot '" + robot_name + "': cannot create the in-memory file");
    const int id = mj_findFileVFS(vfs.get(), filename);
    if (id < 0) {
        mj_deleteVFS(vfs.get());
        throw Error("MuJoCo spatial model of robot '" + robot_name + "': in-memory file not found");
    }
    std::memcpy(vfs->filedata[id], xml.data(), xml.size());
    std::array<char, 1024> err{};
    mjModel* m = mj_loadXML(filename, vfs.get(), err.data(), static_cast<int>(err.size()));
    mj_deleteVFS(vfs.get());
    if (m == nullptr)
        throw Error("MuJoCo could not compile the spatial model of robot '" + robot_name +
                    "': " + std::string(err.data()));
    return m;
}

/// The 2-norm condition number of A from the extreme eigenvalues of A^T A: a guard against
/// singular postures (max_condition 1e4 means eigenvalue ratios of 1e8, well within double
/// precision) at a fraction of a Jacobi SVD's cost, which took half of a sample's time.
double conditionNumber(const Eigen::MatrixXd& A) {
    if (A.size() == 0) return 0.0;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A.transpose() * A, Eigen::EigenvaluesOnly);
    const auto& lambda = eig.eigenvalues();  // ascending
    const double smallest = lambda(0);
    return smallest > 0.0 ? std::sqrt(lambda(lambda.size() - 1) / smallest) : std::numeric_limits<double>::infinity();
}

Eigen::Vector3d v3(const mjtNum* x) { return {x[0], x[1], x[2]}; }

}  // namespace

struct MujocoSpatialMechanism::Impl {
    SpatialRobotDescription robot;
    std::string xml;
    mjModel* m = nullptr;
    mjData* d = nullptr;
    int task = 6;

    /// One loop closure: its connect's first efc row, the sites at its centre, and for a U the
    /// constant angle between a1 (in the limb's last body) and a2 (in the platform).
    struct Closure {
        int eq = -1, row = -1, site_limb = -1, site_platform = -1, body = 0;
        bool universal = false;
        Eigen::Vector3d a1 = Eigen::Vector3d::Zero(), a2 = Eigen::Vector3d::Zero();  // in the bodies' frames
        double cos0 = 1.0;
    };
    /// An R or P joint of a tree: its dof and friction.
    struct Joint {
        int v = -1;
        double damping = 0.0, friction = 0.0;
    };
    std::vector<Closure> closures;
    std::vector<Joint> joints;
    std::vector<int> actuated_v;  // per actuator (file order): its dof
    std::vector<int>
        free_v;  // the dofs Newton solves for: the limbs' (and the platform's rotation for motion translation)
    int platform = -1, platform_q = -1, platform_v = -1;
    int rows = 0;  // closure equations
    double tol = 0.0;
    using Jacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>;  // as MuJoCo writes it
    Jacobian jacp, jacr, jacr2;                                                  // 3 x nv

    ~Impl() {
        if (d != nullptr) mj_deleteData(d);
        if (m != nullptr) mj_deleteModel(m);
    }

    [[nodiscard]] std::string origin() const { return robot.source.empty() ? std::string() : robot.source + ": "; }
    int id(mjtObj type, const std::string& name) const {
        const int i = mj_name2id(m, type, name.c_str());
        if (i < 0) throw Error("MuJoCo spatial model: '" + name + "' missing");
        return i;
    }

    void init();
    void positionStage() {
        mj_kinematics(m, d);
        mj_comPos(m, d);
        mj_makeConstraint(m, d);
    }
    /// a1 and a2 of closure c in the world now.
    void axes(const Closure& c, Eigen::Vector3d& a1, Eigen::Vector3d& a2) const {
        const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> R1(d->xmat + 9 * c.body);
        const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> R2(d->xmat + 9 * platform);
        a1 = R1 * c.a1;
        a2 = R2 * c.a2;
    }
    /// The closure residuals: each connect's efc_pos (limb's anchor minus the platform's), then
    /// a1 . a2 - cos0 of each U.
    Eigen::VectorXd residual() const {
        Eigen::VectorXd r(rows);
        int i = 0;
        for (const Closure& c : closures) {
            for (int k = 0; k < 3; ++k) r[i++] = d->efc_pos[c.row + k];
        }
        for (const Closure& c : closures) {
            if (!c.universal) continue;
            Eigen::Vector3d a1, a2;
            axes(c, a1, a2);
            r[i++] = a1.dot(a2) - c.cos0;
        }
        return r;
    }
    /// G = d residual / d qvel: the connects' efc_J rows; a U's n^T (Jr_limb - Jr_platform),
    /// n = a1 x a2, as d(a1 . a2)/dt = n . (w_limb - w_platform).
    Eigen::MatrixXd jacobian() {
        const int nv = m->nv;
        Eigen::MatrixXd G(rows, nv);
        int i = 0;
        for (const Closure& c : closures) {
            for (int k = 0; k < 3; ++k, ++i) {
                G.row(i) =
                    Eigen::Map<const Eigen::RowVectorXd>(d->efc_J + static_cast<std::ptrdiff_t>(c.row + k) * nv, nv);
            }
        }
        for (const Closure& c : closures) {
            if (!c.universal) continue;
            Eigen::Vector3d a1, a2;
            axes(c, a1, a2);
            mj_jacBody(m, d, nullptr, jacr.data(), c.body);
            mj_jacBody(m, d, nullptr, jacr2.data(), platform);
            G.row(i++) = a1.cross(a2).transpose() * (jacr - jacr2);
        }
        return G;
    }
    Eigen::MatrixXd freeColumns(const Eigen::MatrixXd& G) const {
        Eigen::MatrixXd Gf(G.rows(), static_cast<Eigen::Index>(free_v.size()));
        for (std::size_t c = 0; c < free_v.size(); ++c) Gf.col(static_cast<Eigen::Index>(c)) = G.col(free_v[c]);
        return Gf;
    }
    /// The platform frame's qpos at pose p (motion translation: its position only).
    void setPose(const Eigen::VectorXd& p) {
        for (int i = 0; i < 3; ++i) d->qpos[platform_q + i] = p[i];
        if (task == 6) {
            const Eigen::Quaterniond q(rotation(p[3], p[4], p[5]));
            d->qpos[platform_q + 3] = q.w();
            d->qpos[platform_q + 4] = q.x();
            d->qpos[platform_q + 5] = q.y();
            d->qpos[platform_q + 6] = q.z();
        }
    }
    bool newton(const Eigen::VectorXd& p, const Eigen::VectorXd& seed);
    void assemble(std::size_t sample, const Eigen::VectorXd& p, const Eigen::VectorXd& seed,
                  const Eigen::VectorXd& p_from, const Eigen::VectorXd& q_from);
    /// Body accelerations at qacc = 0 without gravity (the velocity-product part only):
    /// cacc_b = cacc_parent + sum cdof_dot qvel, the forward pass of mj_rnePostConstraint.
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

void MujocoSpatialMechanism::Impl::init() {
    const std::size_t L = robot.limbs.size();
    task = robot.taskDimension();
    platform = id(mjOBJ_BODY, "platform");
    const int pj = id(mjOBJ_JOINT, "platform");
    platform_q = m->jnt_qposadr[pj];
    platform_v = m->jnt_dofadr[pj];
    jacp.resize(3, m->nv);
    jacr.resize(3, m->nv);
    jacr2.resize(3, m->nv);
    double scale = 1.0;
    for (std::size_t j = 0; j < L; ++j) {
        const SpatialLimbDescription& limb = robot.limbs[j];
        const std::size_t last = limb.joints.size() - 1;
        for (std::size_t k = 0; k < last; ++k) {
            const SpatialJointDescription& joint = limb.joints[k];
            scale = std::max(scale, joint.point.cwiseAbs().maxCoeff());
            if (joint.type != SpatialJointType::revolute && joint.type != SpatialJointType::prismatic) continue;
            const int v = m->jnt_dofadr[id(mjOBJ_JOINT, jointName(j, k))];
            joints.push_back({v, joint.damping, joint.friction});
            if (joint.actuated) actuated_v.push_back(v);
        }
        const SpatialJointDescription& closing = limb.joints[last];
        Closure c;
        c.eq = id(mjOBJ_EQUALITY, "loop" + std::to_string(j + 1));
        c.site_limb = id(mjOBJ_SITE, siteName(j, false));
        c.site_platform = id(mjOBJ_SITE, siteName(j, true));
        c.body = last == 0 ? 0 : id(mjOBJ_BODY, bodyName(j, last - 1));
        c.universal = closing.type == SpatialJointType::universal;
        if (c.universal) {
            const Eigen::Matrix3d R_home = rotation(robot.home(3), robot.home(4), robot.home(5));
            c.a1 = closing.axis1;  // the limb body's frame is the world's at home
            c.a2 = R_home.transpose() * closing.axis2;
            c.cos0 = closing.axis1.dot(closing.axis2);
            ++rows;
        }
        rows += 3;
        closures.push_back(c);
    }
    for (int i = 0; i < m->nv; ++i) {
        const bool prescribed = i >= platform_v && i < platform_v + (task == 6 ? 6 : 3);
        if (!prescribed) free_v.push_back(i);
    }
    if (rows != static_cast<int>(free_v.size())) {
        throw Error(origin() + "MuJoCo spatial model: " + std::to_string(rows) + " closure equations for " +
                    std::to_string(free_v.size()) + " passive speeds");
    }
    tol = 1e-14 * scale;

    mj_resetData(m, d);
    positionStage();
    if (d->nefc != 3 * static_cast<int>(L))
        throw Error("MuJoCo spatial model: expected " + std::to_string(3 * L) + " constraint rows");
    for (int i = d->nefc - 1; i >= 0; --i) {
        if (d->efc_type[i] != mjCNSTR_EQUALITY) throw Error("MuJoCo spatial model: a non-equality constraint");
        for (Closure& c : closures) {
            if (c.eq == d->efc_id[i]) c.row = i;
        }
    }
    const double r0 = residual().cwiseAbs().maxCoeff();
    if (!(r0 < 1e-12)) {
        std::ostringstream msg;
        msg << origin() << "MuJoCo spatial model: the home posture is not assembled (loop error " << r0 << ")";
        throw Error(msg.str());
    }
}

bool MujocoSpatialMechanism::Impl::newton(const Eigen::VectorXd& p, const Eigen::VectorXd& seed) {
    const int nv = m->nv;
    Eigen::Map<Eigen::VectorXd>(d->qpos, m->nq) = seed;
    setPose(p);
    Eigen::VectorXd dq = Eigen::VectorXd::Zero(nv);
    double previous = std::numeric_limits<double>::infinity();
    for (int it = 0; it <= kNewtonMaxIter; ++it) {
        positionStage();
        const Eigen::VectorXd r = residual();
        if (!r.allFinite()) return false;
        const double error = r.cwiseAbs().maxCoeff();
        // converged, or at the round-off floor: near tol and no longer falling quadratically
        if (error <= tol || (error <= 1e3 * tol && error > 0.1 * previous)) {
            mj_differentiatePos(m, dq.data(), 1.0, seed.data(), d->qpos);
            double jump = 0.0;
            for (int i : free_v) jump = std::max(jump, std::abs(dq[i]));
            return jump <= kMaxJump;
        }
        if (it == kNewtonMaxIter) break;
        const Eigen::VectorXd step = freeColumns(jacobian()).partialPivLu().solve(r);
        if (!step.allFinite()) return false;
        dq.setZero();
        for (std::size_t c = 0; c < free_v.size(); ++c) dq[free_v[c]] = -step[static_cast<Eigen::Index>(c)];
        mj_integratePos(m, d->qpos, dq.data(), 1.0);
        previous = error;
    }
    return false;
}

void MujocoSpatialMechanism::Impl::assemble(std::size_t sample, const Eigen::VectorXd& p, const Eigen::VectorXd& seed,
                                            const Eigen::VectorXd& p_from, const Eigen::VectorXd& q_from) {
    if (newton(p, seed)) return;
    for (int halvings = 1; halvings <= kMaxHalvings; ++halvings) {
        const int pieces = 1 << halvings;
        Eigen::VectorXd q = q_from;
        bool ok = true;
        for (int s = 1; s <= pieces && ok; ++s) {
            ok = newton(p_from + (p - p_from) * (static_cast<double>(s) / pieces), q);
            if (ok) q = Eigen::Map<const Eigen::VectorXd>(d->qpos, m->nq);
        }
        if (ok) return;
    }
    throw Error(origin() + "MuJoCo spatial model: cannot assemble sample " + std::to_string(sample) +
                " on the home branch");
}

MujocoSpatialMechanism::MujocoSpatialMechanism(const SpatialRobotDescription& robot) : impl_(std::make_unique<Impl>()) {
    Impl& s = *impl_;
    s.robot = robot;
    for (const SpatialLimbDescription& limb : robot.limbs) {
        if (limb.joints.empty() || limb.bodies.size() + 1 != limb.joints.size())
            throw Error(s.origin() + "limb " + limb.name + ": the MuJoCo spatial model needs a body between joints");
        const SpatialJointType closing = limb.joints.back().type;
        if (closing != SpatialJointType::spherical && closing != SpatialJointType::universal)
            throw Error(s.origin() + "limb " + limb.name +
                        ": the MuJoCo spatial model closes a limb at an S or U joint only, not at an R or P");
    }
    s.xml = buildMjcf(s.robot);
    s.m = compileFromMemory(s.xml, s.robot.name);
    s.d = mj_makeData(s.m);
    if (s.d == nullptr) throw Error("MuJoCo: mj_makeData failed for robot '" + s.robot.name + "'");
    s.init();
}

MujocoSpatialMechanism::~MujocoSpatialMechanism() = default;
MujocoSpatialMechanism::MujocoSpatialMechanism(MujocoSpatialMechanism&&) noexcept = default;
MujocoSpatialMechanism& MujocoSpatialMechanism::operator=(MujocoSpatialMechanism&&) noexcept = default;

std::string MujocoSpatialMechanism::mjcf() const { return impl_->xml; }
int MujocoSpatialMechanism::actuatorCount() const { return static_cast<int>(impl_->actuated_v.size()); }

Eigen::MatrixXd MujocoSpatialMechanism::actuatorForces(const std::vector<Eigen::VectorXd>& p,
                                                       const std::vector<Eigen::VectorXd>& dp,
                                                       const std::vector<Eigen::VectorXd>& ddp) {
    Impl& s = *impl_;
    const mjModel* m = s.m;
    mjData* d = s.d;
    const int task = s.task, nv = m->nv, n = actuatorCount(), rows = s.rows;
    if (dp.size() != p.size() || ddp.size() != p.size())
        throw Error("MuJoCo spatial model: p, dp and ddp differ in length");
    Eigen::MatrixXd tau(static_cast<Eigen::Index>(p.size()), n);

    // Continuation from home: the seed is the previous solution moved along the previous
    // velocity map N (qvel = N dp) by the pose step.
    mj_resetData(m, d);
    Eigen::VectorXd q_prev = Eigen::Map<const Eigen::VectorXd>(m->qpos0, m->nq);
    Eigen::VectorXd p_prev = s.robot.home.head(task);
    Eigen::MatrixXd N = Eigen::MatrixXd::Zero(nv, task);
    Eigen::MatrixXd K(nv, nv), W = Eigen::MatrixXd::Zero(nv, task);
    Eigen::VectorXd seed(m->nq), h(nv), rhs(nv);
    for (std::size_t k = 0; k < p.size(); ++k) {
        if (p[k].size() != task || dp[k].size() != task || ddp[k].size() != task)
            throw Error("MuJoCo spatial model: sample " + std::to_string(k) + " is not of size " +
                        std::to_string(task));
        seed = q_prev;
        const Eigen::VectorXd step = N * (p[k] - p_prev);
        mj_integratePos(m, seed.data(), step.data(), 1.0);
        s.assemble(k, p[k], seed, p_prev, q_prev);
        if (task == 3) {
            // the limbs' U closures, not the prescription, hold the platform's orientation
            const double angle = 2.0 * std::acos(std::min(1.0, std::abs(d->qpos[s.platform_q + 3])));
            if (!(angle < 1e-9)) {
                std::ostringstream msg;
                msg << s.origin() << "MuJoCo spatial model: the limbs turn the platform by " << angle
                    << " rad at sample " << k;
                throw Error(msg.str());
            }
        }

        // K = [G; J_p]: the closures' Jacobian and the platform frame's (its origin, then for
        // motion full its rotation), all of MuJoCo's at the assembled posture
        const Eigen::MatrixXd G = s.jacobian();
        const double cond_G = conditionNumber(s.freeColumns(G));
        if (!(cond_G <= s.robot.max_condition))
            throw Error("MuJoCo spatial model: the loop closure is singular at sample " + std::to_string(k));
        mj_jacBody(m, d, s.jacp.data(), s.jacr.data(), s.platform);
        K.topRows(rows) = G;
        K.middleRows(rows, 3) = s.jacp;
        if (task == 6) K.bottomRows(3) = s.jacr;
        // W: the platform frame's velocity [v; w] of the pose rates; w = E [roll', pitch', yaw']
        // for R = Rz(yaw) Ry(pitch) Rx(roll), E = [Rz Ry x, Rz y, z]
        W.middleRows(rows, 3).leftCols(3).setIdentity();
        Eigen::Vector3d ex, ey, ez = Eigen::Vector3d::UnitZ(), alpha = Eigen::Vector3d::Zero();
        if (task == 6) {
            const Eigen::Matrix3d Rz = Eigen::AngleAxisd(p[k][5], ez).toRotationMatrix();
            const Eigen::Matrix3d Ry = Eigen::AngleAxisd(p[k][4], Eigen::Vector3d::UnitY()).toRotationMatrix();
            ey = Rz.col(1);
            ex = Rz * Ry.col(0);
            W.block(rows + 3, 3, 3, 1) = ex;
            W.block(rows + 3, 4, 3, 1) = ey;
            W.block(rows + 3, 5, 3, 1) = ez;
            // dW/dt dp: the columns turn with the yaw and the pitch rates
            const Eigen::Vector3d w_zy = dp[k][5] * ez + dp[k][4] * ey;
            alpha = dp[k][4] * ez.cross(ey) * dp[k][5] + dp[k][3] * w_zy.cross(ex);
        }
        const Eigen::PartialPivLU<Eigen::MatrixXd> lu(K);
        N = lu.solve(W);

        // qvel = N dp, then MuJoCo's velocity stage
        Eigen::Map<Eigen::VectorXd>(d->qvel, nv) = N * dp[k];
        mj_comVel(m, d);

        // qacc: K qacc = [-bias_G; W ddp + dW/dt dp - bias_p], the biases being MuJoCo's
        // accelerations at qacc = 0 (velocity-product terms only)
        s.velocityProductAccelerations();
        int i = 0;
        for (const Impl::Closure& c : s.closures) {
            mjtNum a_limb[6], a_platform[6];
            mj_objectAcceleration(m, d, mjOBJ_SITE, c.site_limb, a_limb, 0);
            mj_objectAcceleration(m, d, mjOBJ_SITE, c.site_platform, a_platform, 0);
            for (int r = 0; r < 3; ++r) rhs[i++] = -(a_limb[3 + r] - a_platform[3 + r]);
        }
        for (const Impl::Closure& c : s.closures) {
            if (!c.universal) continue;
            // (a1 . a2)'' at qacc = 0, a' = w x a, a'' = alpha x a + w x (w x a)
            Eigen::Vector3d a1, a2;
            s.axes(c, a1, a2);
            mjtNum v1[6], v2[6], acc1[6], acc2[6];
            mj_objectVelocity(m, d, mjOBJ_XBODY, c.body, v1, 0);
            mj_objectVelocity(m, d, mjOBJ_XBODY, s.platform, v2, 0);
            mj_objectAcceleration(m, d, mjOBJ_XBODY, c.body, acc1, 0);
            mj_objectAcceleration(m, d, mjOBJ_XBODY, s.platform, acc2, 0);
            const Eigen::Vector3d w1 = v3(v1), w2 = v3(v2);
            const Eigen::Vector3d d1 = w1.cross(a1), d2 = w2.cross(a2);
            const Eigen::Vector3d dd1 = v3(acc1).cross(a1) + w1.cross(d1), dd2 = v3(acc2).cross(a2) + w2.cross(d2);
            rhs[i++] = -(dd1.dot(a2) + 2.0 * d1.dot(d2) + a1.dot(dd2));
        }
        mjtNum a_p[6];
        mj_objectAcceleration(m, d, mjOBJ_XBODY, s.platform, a_p, 0);
        for (int r = 0; r < 3; ++r) rhs[i++] = ddp[k][r] - a_p[3 + r];
        if (task == 6) {
            const Eigen::Vector3d alpha_w = W.block(rows + 3, 3, 3, 3) * ddp[k].tail<3>() + alpha;
            for (int r = 0; r < 3; ++r) rhs[i++] = alpha_w[r] - a_p[r];
        }
        Eigen::Map<Eigen::VectorXd>(d->qacc, nv) = lu.solve(rhs);

        // h = M qacc + c - Q_gravity (mj_rne's bias includes gravity), then the joint friction
        mj_rne(m, d, 1, h.data());
        for (const Impl::Joint& j : s.joints) {
            const double rate = d->qvel[j.v];
            const double sign = rate > 0.0 ? 1.0 : (rate < 0.0 ? -1.0 : 0.0);
            h[j.v] += j.damping * rate + j.friction * sign;  // h - Q_f
        }
        // N^T (h - Q_f) = A^T tau over the pose coordinates
        Eigen::MatrixXd A(n, task);
        for (int a = 0; a < n; ++a) A.row(a) = N.row(s.actuated_v[static_cast<std::size_t>(a)]);
        const Eigen::VectorXd F = N.transpose() * h;
        if (!(conditionNumber(A) <= s.robot.max_condition))
            throw Error("MuJoCo spatial model: the actuation map is singular at sample " + std::to_string(k));
        // the minimum-norm solution (the unique one when n = task)
        const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A.transpose());
        tau.row(static_cast<Eigen::Index>(k)) = cod.solve(F).transpose();

        q_prev = Eigen::Map<const Eigen::VectorXd>(d->qpos, m->nq);
        p_prev = p[k];
    }
    return tau;
}

}  // namespace nocdyn::validation
