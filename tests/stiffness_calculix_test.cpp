// The platform's static compliance and natural frequencies against CalculiX (Debian's
// calculix-ccx 2.20, /usr/bin/ccx) on the same frame, for robots with joint springs (drive springs,
// flexure hinges) and elastic links. The CalculiX input is written here from the robot at the
// pose, in absolute coordinates, independent of the library's joint-space formulation:
//   - every rigid body is a node R at its c.o.m. (translations) and a node PHI whose x
//     displacement is its rotation; a MASS element on R (m) and one on PHI (I about the c.o.m.);
//   - a joint ties the velocities of its two bodies at its point, v_i(r) = u_R + phi E (r - R):
//     R joint: both components; P joint: equal rotations and the component normal to its
//     direction, its slide a node Q with u_Q = d . (v_b - v_a);
//   - a joint spring is a SPRING1/SPRING2 element on the PHI or Q degrees of freedom;
//   - an elastic link is a chain of beam segments between its joints (addBeam): each segment's
//     stiffness is that of CalculiX's own beam element U1 (a Timoshenko beam, its shear
//     coefficient set to 1e10, so Euler-Bernoulli's), measured by CalculiX on a clamped
//     cantilever of the segment's length (three tip load cases), and written as springs on the
//     segment's relative deflection; the link's R and PHI nodes are welded to its root, so its
//     inertia rides on its root (nocdyn's elastodynamic model) or, in the distributed mass model,
//     its mass is spread over the beam's nodes;
//   - the platform's point C is a node; its load cases give the compliance columns.
// The U1 elements are not in the assembled model itself: there CalculiX 2.20 drops a beam
// rotation that an *EQUATION makes dependent, and U1 has no mass matrix ("e_c3d_u1: no
// dynamic"). One U1 element reproduces the Euler-Bernoulli cantilever's tip compliance to
// CalculiX's 7 printed digits, so the segment count does not change a massless beam (1 and 4
// segments agree) and converges the distributed mass (8 and 16 segments, Richardson).
// The linear constraints are written in CalculiX's *EQUATION form, one dependent degree of
// freedom each (solved for here by a rank-revealing QR); CalculiX assembles the springs and
// masses, solves the three load cases and the eigenproblem. Its .dat file prints 7 significant
// digits, so agreement is asserted to 1e-6 relative.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "cli_support.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "skip.hpp"
#include "robot_files.hpp"

extern char** environ;

namespace nocdyn {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCcx = "/usr/bin/ccx";

/// A real number as CalculiX reads it: a field of at most 20 characters (14 significant digits).
std::string real(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.13e", value);
    return buffer;
}

/// A scalar unknown of the finite-element model: node and degree of freedom (1 or 2).
struct Dof {
    int node;
    int dof;
};

/// Where an elastic body's inertia is: rigidly on its root (nocdyn's elastodynamic model), or
/// spread along its beam (the continuum: its mass shared among the beam's nodes).
enum class MassModel { root, distributed };

class CalculixModel {
public:
    /// The tip compliance of a cantilever (EA, EI, length) on [u_e, v_n, phi].
    using SegmentCompliance = std::function<Matrix3(double, double, double)>;

    /// `segment`: the beams' segment compliance (needed when a body is elastic).
    CalculixModel(const Model& model, const StiffnessModel& compliance, const Data& data,
                  MassModel mass_model = MassModel::root, int beam_elements = 1, SegmentCompliance segment = {})
        : segment_(std::move(segment)) {
        const int bodies = model.bodies;
        body_R_.resize(static_cast<std::size_t>(bodies));
        body_PHI_.resize(static_cast<std::size_t>(bodies));
        com_.resize(static_cast<std::size_t>(bodies));
        root_.resize(static_cast<std::size_t>(bodies));
        tip_.resize(static_cast<std::size_t>(bodies));
        for (int i = 0; i < bodies; ++i) {
            const auto I = static_cast<std::size_t>(i);
            const bool platform = i == model.platformBody();
            const Vector2 com =
                platform
                    ? Vector2(data.x_P)
                    : data.limb[static_cast<std::size_t>(i % model.limbs)].x[static_cast<std::size_t>(i / model.limbs)];
            com_[I] = com;
            body_R_[I] = addNode(com, 2);
            body_PHI_[I] = addNode(com, 1);
            root_[I] = tip_[I] = {body_R_[I], com, body_PHI_[I], 1};
            const bool elastic = !platform && compliance.elastic[static_cast<std::size_t>(i % model.limbs)]
                                                                [static_cast<std::size_t>(i / model.limbs)];
            const InertiaDyad& M = model.inertia(i);
            if (elastic) addBeam(model, data, i, mass_model, beam_elements);
            if (elastic && mass_model == MassModel::distributed) continue;
            if (M.mass > 0.0) masses_.push_back({body_R_[I], M.mass});
            if (M.inertia > 0.0) masses_.push_back({body_PHI_[I], M.inertia});
        }
        const Vector2 C = data.p.tail<2>();
        node_C_ = addNode(C, 2);
        const int P = model.platformBody();
        // C rides on the platform
        addVelocityRow(node_C_, 1, &root_[static_cast<std::size_t>(P)], C, -1.0);
        addVelocityRow(node_C_, 2, &root_[static_cast<std::size_t>(P)], C, -1.0);
        for (int j = 0; j < model.limbs; ++j) {
            const auto J = static_cast<std::size_t>(j);
            for (int k = 0; k < 3; ++k) {
                const auto K = static_cast<std::size_t>(k);
                // the joint ties the outboard end (tip) of body a to the inboard end (root) of b
                const Frame* a = k == 0 ? nullptr : &tip_[static_cast<std::size_t>(model.body(j, k - 1))];
                const Frame* b = &root_[static_cast<std::size_t>(k == 2 ? P : model.body(j, k))];
                const Twist& s = data.limb[J].s[K];
                const JointSpring kind = compliance.joint[J][K];
                if (model.limb[J].type[K] == JointType::revolute) {
                    const Vector2 r(-s(2), s(1));
                    for (int c = 1; c <= 2; ++c) {
                        Row row;
                        addVelocity(row, b, r, c, 1.0);
                        addVelocity(row, a, r, c, -1.0);
                        rows_.push_back(row);
                    }
                    if (kind == JointSpring::spring) springs_.push_back({phi(a), phi(b), compliance.k[J][K]});
                    if (kind == JointSpring::locked) rows_.push_back(relativeRotation(a, b));
                } else {
                    const Vector2 d(s(1), s(2)), n = perp(d);
                    const Vector2 r = b->origin;
                    rows_.push_back(relativeRotation(a, b));
                    Row normal;
                    for (int c = 1; c <= 2; ++c) {
                        addVelocity(normal, b, r, c, n(c - 1));
                        addVelocity(normal, a, r, c, -n(c - 1));
                    }
                    rows_.push_back(normal);
                    if (kind == JointSpring::free) continue;
                    const int Q = addNode(r, 1);
                    Row slide;
                    slide[{Q, 1}] += 1.0;
                    for (int c = 1; c <= 2; ++c) {
                        addVelocity(slide, b, r, c, -d(c - 1));
                        addVelocity(slide, a, r, c, d(c - 1));
                    }
                    rows_.push_back(slide);
                    if (kind == JointSpring::spring) springs_.push_back({-1, Q, compliance.k[J][K]});
                    if (kind == JointSpring::locked) {
                        Row fixed;
                        fixed[{Q, 1}] = 1.0;
                        rows_.push_back(fixed);
                    }
                }
            }
        }
        // independent oscillators far above the robot's band: the eigensolver (ARPACK) needs
        // more degrees of freedom than the modes it is asked for
        for (int i = 0; i < kPadding; ++i) {
            const int pad = addNode(Vector2(10.0 + i, 10.0), 1);
            springs_.push_back({-1, pad, 1.0e12});
            masses_.push_back({pad, 1.0});
        }
        independent_ = {{body_PHI_[static_cast<std::size_t>(P)], 1}, {node_C_, 1}, {node_C_, 2}};
    }

    /// The input deck: the three load cases (moment about C, f_x, f_y), or the lowest modes.
    [[nodiscard]] std::string deck(bool statics, int modes) const {
        std::ostringstream out;
        out.precision(17);
        out << "*NODE\n";
        for (std::size_t i = 0; i < nodes_.size(); ++i) {
            out << i + 1 << ", " << real(nodes_[i].point.x()) << ", " << real(nodes_[i].point.y()) << ", 0\n";
        }
        out << "*NSET, NSET=PLAT\n" << body_PHI_.back() + 1 << ", " << node_C_ + 1 << "\n";
        int element = 1;
        for (const Spring& s : springs_) {
            if (s.a < 0) {
                out << "*ELEMENT, TYPE=SPRING1, ELSET=K" << element << "\n" << element << ", " << s.b + 1 << "\n";
                out << "*SPRING, ELSET=K" << element << "\n1\n" << real(s.k) << "\n";
            } else {
                out << "*ELEMENT, TYPE=SPRING2, ELSET=K" << element << "\n"
                    << element << ", " << s.a + 1 << ", " << s.b + 1 << "\n";
                out << "*SPRING, ELSET=K" << element << "\n1, 1\n" << real(s.k) << "\n";
            }
            ++element;
        }
        // zero springs among the platform's three independent unknowns: CalculiX's frequency
        // step needs their couplings in the matrix structure, which the masses reach only
        // through the equations
        const int Pn = body_PHI_.back() + 1, Cn = node_C_ + 1;
        const int zero_springs[3][4] = {{Pn, 1, Cn, 1}, {Pn, 1, Cn, 2}, {Cn, 1, Cn, 2}};
        for (const auto& z : zero_springs) {
            out << "*ELEMENT, TYPE=SPRING2, ELSET=K" << element << "\n"
                << element << ", " << z[0] << ", " << z[2] << "\n*SPRING, ELSET=K" << element << "\n"
                << z[1] << ", " << z[3] << "\n"
                << real(0.0) << "\n";
            ++element;
        }
        // no masses in the load cases: they play no part there, and with a beam's nodal masses
        // CalculiX 2.20's static step fails ("add_sm_st: coefficient should be 0")
        for (const Mass& m : statics ? std::vector<Mass>{} : masses_) {
            out << "*ELEMENT, TYPE=MASS, ELSET=M" << element << "\n" << element << ", " << m.node + 1 << "\n";
            out << "*MASS, ELSET=M" << element << "\n" << real(m.mass) << "\n";
            ++element;
        }
        std::vector<Dof> zero;
        out << equations(zero);
        out << "*BOUNDARY\n";
        for (const Dof& z : zero) out << z.node + 1 << ", " << z.dof << ", " << z.dof << "\n";
        for (std::size_t i = 0; i < nodes_.size(); ++i) {
            out << i + 1 << ", 3, 3\n";
            if (nodes_[i].dofs == 1) out << i + 1 << ", 2, 2\n";
        }
        if (!statics) {
            out << "*STEP\n*FREQUENCY\n" << modes << "\n*END STEP\n";
            return out.str();
        }
        const std::pair<int, int> loads[3] = {{body_PHI_.back(), 1}, {node_C_, 1}, {node_C_, 2}};
        for (const auto& [node, dof] : loads) {
            out << "*STEP\n*STATIC\n*CLOAD, OP=NEW\n" << node + 1 << ", " << dof << ", 1.0\n";
            out << "*NODE PRINT, NSET=PLAT\nU\n*END STEP\n";
        }
        return out.str();
    }

    /// Nodes of the platform's displacement: PHI_P (x = theta) and C.
    [[nodiscard]] int platformPhi() const { return body_PHI_.back() + 1; }
    [[nodiscard]] int platformC() const { return node_C_ + 1; }

private:
    static constexpr int kPadding = 64;
    struct Node {
        Vector2 point;
        int dofs;
    };
    /// A body's frame: velocity at r = u_trans + rotation E (r - origin).
    struct Frame {
        int trans;
        Vector2 origin;
        int rot_node, rot_dof;
    };
    struct Spring {
        int a, b;  // PHI or Q nodes, a = -1 for the ground
        double k;
    };
    struct Mass {
        int node;
        double mass;
    };
    using Row = std::map<std::pair<int, int>, double>;

    int addNode(const Vector2& point, int dofs) {
        nodes_.push_back({point, dofs});
        return static_cast<int>(nodes_.size()) - 1;
    }
    static int phi(const Frame* f) { return f == nullptr ? -1 : f->rot_node; }

    /// row += sign * component c of the velocity of frame f at point r (nothing for the ground).
    static void addVelocity(Row& row, const Frame* f, const Vector2& r, int c, double sign) {
        if (f == nullptr) return;
        const Vector2 arm = r - f->origin;
        row[{f->trans, c}] += sign;
        row[{f->rot_node, f->rot_dof}] += sign * (c == 1 ? -arm.y() : arm.x());
    }
    void addVelocityRow(int node, int c, const Frame* f, const Vector2& r, double sign) {
        Row row;
        row[{node, c}] = 1.0;
        addVelocity(row, f, r, c, sign);
        rows_.push_back(row);
    }
    static Row relativeRotation(const Frame* a, const Frame* b) {
        Row row;
        row[{b->rot_node, b->rot_dof}] += 1.0;
        if (a != nullptr) row[{a->rot_node, a->rot_dof}] -= 1.0;
        return row;
    }

    /// Body i (limb i % limbs, link i / limbs) as a chain of `elements` beam segments from its
    /// inboard joint A to its outboard one B. Each beam node is a 2-dof node and a rotation node;
    /// each segment has the stiffness K_s of CalculiX's U1 cantilever of its length (`segment_`,
    /// in the segment's axes [u_e, v_n, phi], rotated here to the plane's), written as three
    /// springs: K_s = sum lambda_k q_k q_k^T, a spring lambda_k on a_k = q_k^T d, d the segment
    /// tip's displacement relative to its root's frame. The body's root frame (its R and PHI
    /// nodes, which carry its inertia in the root mass model) is welded to the first beam node;
    /// its tip frame is the last one with a rotation node of its own, equal to the beam's (without
    /// it, CalculiX's eigensolver returned a spurious negative eigenvalue on the 3-RRR with one
    /// segment per link, the singular mass matrix's doing). In the distributed mass model each
    /// beam node carries its share of the link's mass instead (translations only, as
    /// Euler-Bernoulli's beam).
    void addBeam(const Model& model, const Data& data, int i, MassModel mass_model, int elements) {
        const auto I = static_cast<std::size_t>(i);
        const auto J = static_cast<std::size_t>(i % model.limbs), b = static_cast<std::size_t>(i / model.limbs);
        const Twist& sa = data.limb[J].s[b];
        const Twist& sb = data.limb[J].s[b + 1];
        const Vector2 A(-sa(2), sa(1)), B(-sb(2), sb(1));
        const BodyDescription& body = model.description.limbs[J].bodies[b];
        const double EA = body.elastic->EA, EI = body.elastic->EI, l = (B - A).norm();
        std::vector<Frame> node;
        for (int e = 0; e <= elements; ++e) {
            const Vector2 x = A + (B - A) * (static_cast<double>(e) / elements);
            const int t = addNode(x, 2);
            node.push_back({t, x, addNode(x, 1), 1});
            if (mass_model == MassModel::distributed) {
                const double share = (e == 0 || e == elements) ? 0.5 : 1.0;
                masses_.push_back({t, share * model.inertia(i).mass / elements});
            }
        }
        const Vector2 e = (B - A).normalized();
        Matrix3 R = Matrix3::Identity();  // local [u_e, v_n, phi] to global [u_x, u_y, phi]
        R.block<2, 1>(0, 0) = e;
        R.block<2, 1>(0, 1) = perp(e);
        const Matrix3 K_local = segment_(EA, EI, l / elements).inverse();
        const Eigen::SelfAdjointEigenSolver<Matrix3> eig(0.5 * (K_local + K_local.transpose()));
        for (std::size_t k = 0; k + 1 < node.size(); ++k) {
            for (int m = 0; m < 3; ++m) {
                const Vector3 q = R * eig.eigenvectors().col(m);
                const int a = addNode(node[k + 1].origin, 1);
                Row row;  // a = q^T d, d = [v_tip - v_root(x_tip); phi_tip - phi_root]
                row[{a, 1}] = 1.0;
                for (int c = 1; c <= 2; ++c) {
                    addVelocity(row, &node[k + 1], node[k + 1].origin, c, -q(c - 1));
                    addVelocity(row, &node[k], node[k + 1].origin, c, q(c - 1));
                }
                row[{node[k + 1].rot_node, 1}] -= q(2);
                row[{node[k].rot_node, 1}] += q(2);
                rows_.push_back(row);
                springs_.push_back({-1, a, eig.eigenvalues()(m)});
            }
        }
        for (int c = 1; c <= 2; ++c) {
            Row row;
            row[{body_R_[I], c}] = 1.0;
            addVelocity(row, &node.front(), com_[I], c, -1.0);
            rows_.push_back(row);
        }
        rows_.push_back(relativeRotation(&node.front(), &root_[I]));
        const int tip_phi = addNode(B, 1);
        const Frame tip_rotation{-1, B, tip_phi, 1};
        rows_.push_back(relativeRotation(&node.back(), &tip_rotation));
        tip_[I] = {node.back().trans, B, tip_phi, 1};
    }

    /// The constraints with one dependent unknown each: x_D = G x_I, the platform's three
    /// displacements and the padding kept independent.
    /// Dependents equal to zero are returned in `zero` (a boundary condition, not an equation).
    [[nodiscard]] std::string equations(std::vector<Dof>& zero) const {
        std::vector<Dof> unknowns;
        std::map<std::pair<int, int>, int> column;
        for (const Row& row : rows_) {
            for (const auto& [key, value] : row) {
                if (!column.count(key)) {
                    column[key] = static_cast<int>(unknowns.size());
                    unknowns.push_back({key.first, key.second});
                }
            }
        }
        const auto n = static_cast<Eigen::Index>(unknowns.size());
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows_.size()), n);
        for (std::size_t r = 0; r < rows_.size(); ++r) {
            for (const auto& [key, value] : rows_[r]) A(static_cast<Eigen::Index>(r), column.at(key)) = value;
        }
        std::vector<Eigen::Index> allowed, kept;
        for (Eigen::Index c = 0; c < n; ++c) {
            const Dof& u = unknowns[static_cast<std::size_t>(c)];
            bool independent = false;
            for (const Dof& i : independent_) independent = independent || (i.node == u.node && i.dof == u.dof);
            (independent ? kept : allowed).push_back(c);
        }
        Eigen::MatrixXd A_allowed(A.rows(), static_cast<Eigen::Index>(allowed.size()));
        for (std::size_t c = 0; c < allowed.size(); ++c)
            A_allowed.col(static_cast<Eigen::Index>(c)) = A.col(allowed[c]);
        Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A_allowed);
        qr.setThreshold(1e-12);
        const Eigen::Index rank = qr.rank();
        std::vector<Eigen::Index> dependent;
        for (Eigen::Index i = 0; i < rank; ++i)
            dependent.push_back(allowed[static_cast<std::size_t>(qr.colsPermutation().indices()(i))]);
        for (Eigen::Index i = rank; i < static_cast<Eigen::Index>(allowed.size()); ++i) {
            kept.push_back(allowed[static_cast<std::size_t>(qr.colsPermutation().indices()(i))]);
        }
        Eigen::MatrixXd A_D(A.rows(), rank), A_I(A.rows(), static_cast<Eigen::Index>(kept.size()));
        for (Eigen::Index i = 0; i < rank; ++i) A_D.col(i) = A.col(dependent[static_cast<std::size_t>(i)]);
        for (std::size_t i = 0; i < kept.size(); ++i) A_I.col(static_cast<Eigen::Index>(i)) = A.col(kept[i]);
        const Eigen::MatrixXd G = A_D.colPivHouseholderQr().solve(-A_I);  // x_D = G x_I
        EXPECT_LT((A_D * G + A_I).norm(), 1e-9 * (1.0 + A.norm())) << "inconsistent constraints";
        std::ostringstream out;
        for (Eigen::Index i = 0; i < rank; ++i) {
            std::vector<std::pair<Dof, double>> terms{
                {unknowns[static_cast<std::size_t>(dependent[static_cast<std::size_t>(i)])], 1.0}};
            for (std::size_t k = 0; k < kept.size(); ++k) {
                const double g = G(i, static_cast<Eigen::Index>(k));
                if (std::abs(g) > 1e-13) terms.push_back({unknowns[static_cast<std::size_t>(kept[k])], -g});
            }
            if (terms.size() == 1) {
                zero.push_back(terms[0].first);
                continue;
            }
            out << "*EQUATION\n" << terms.size() << "\n";
            for (std::size_t t = 0; t < terms.size(); ++t) {
                out << terms[t].first.node + 1 << ", " << terms[t].first.dof << ", " << real(terms[t].second)
                    << (t + 1 == terms.size() || t % 4 == 3 ? "\n" : ", ");
            }
        }
        return out.str();
    }

    std::vector<Node> nodes_;
    std::vector<int> body_R_, body_PHI_;
    std::vector<Vector2> com_;
    std::vector<Frame> root_, tip_;
    SegmentCompliance segment_;
    int node_C_ = -1;
    std::vector<Row> rows_;
    std::vector<Spring> springs_;
    std::vector<Mass> masses_;
    std::vector<Dof> independent_;
};

/// Runs ccx on `job`.inp in `dir` (no shell), its output to `job`.log. True on exit code 0.
bool runCalculix(const fs::path& dir, const std::string& job) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
    const std::string log = (dir / (job + ".log")).string();
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    const char* argv[] = {"ccx", "-i", job.c_str(), nullptr};
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, kCcx, &actions, nullptr, const_cast<char**>(argv), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return false;
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) return false;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

struct CalculixResult {
    Matrix3 compliance = Matrix3::Zero();  ///< columns: moment about C, f_x, f_y; rows dp
    std::vector<double> frequency;         ///< [Hz]
};

CalculixResult parseDat(const std::string& text, int phi_node, int c_node) {
    CalculixResult out;
    std::istringstream in(text);
    std::string line;
    int step = -1;
    bool eigen = false;
    while (std::getline(in, line)) {
        // "displacements (vx,vy,vz)", or "(v(i),i=1..ndof)" with rotational DOFs (the cantilever)
        if (line.find("displacements (") != std::string::npos) {
            ++step;
            eigen = false;
            continue;
        }
        if (line.find("E I G E N V A L U E   O U T P U T") != std::string::npos) {
            eigen = true;
            continue;
        }
        if (line.find("P A R T I C I P A T I O N") != std::string::npos) eigen = false;
        // a row: an integer (node or mode) and numbers
        std::istringstream fields(line);
        long index = 0;
        if (!(fields >> index)) continue;
        std::vector<double> values;
        std::string field;
        bool numbers = true;
        while (fields >> field) {
            char* end = nullptr;
            values.push_back(std::strtod(field.c_str(), &end));
            numbers = numbers && end != field.c_str() && *end == '\0';
        }
        if (!numbers || values.size() < 3) continue;
        // eigenvalue rows: mode, eigenvalue, omega [rad/time], f [cycles/time], imaginary part
        if (eigen && values.size() == 4) {
            out.frequency.push_back(values[2]);
        } else if (!eigen && step >= 0 && step < 3) {
            if (index == phi_node) out.compliance(0, step) = values[0];
            if (index == c_node) {
                out.compliance(1, step) = values[0];
                out.compliance(2, step) = values[1];
            }
        }
    }
    return out;
}

/// The tip compliance on [u_e, v_n, phi] of a cantilever of CalculiX's U1 beam element (length
/// l along x, clamped at x = 0), from three load cases at its tip: f_x, f_y, m_z.
Matrix3 cantileverCompliance(const fs::path& dir, double EA, double EI, double l) {
    constexpr double E = 7.0e10;
    std::ostringstream deck;
    deck << "*NODE, NSET=NALL\n1, 0, 0, 0\n2, " << real(l) << ", 0, 0\n"
         << "*USER ELEMENT, TYPE=U1, INTEGRATION POINTS=2, MAXDOF=6, NODES=2\n"
         << "*ELEMENT, TYPE=U1, ELSET=B\n1, 1, 2\n*MATERIAL, NAME=MB\n*ELASTIC\n"
         << real(E) << ", 0.3\n*BEAM SECTION, ELSET=B, MATERIAL=MB, SECTION=GENERAL\n"
         << real(EA / E) << ", " << real(EI / E) << ", 0, " << real(EI / E) << ", 1.0e10\n0, 0, 1\n"
         << "*NSET, NSET=TIP\n2\n*BOUNDARY\n1, 1, 6\n2, 3, 5\n";
    for (const int dof : {1, 2, 6}) {
        deck << "*STEP\n*STATIC\n*CLOAD, OP=NEW\n2, " << dof << ", 1.0\n*NODE PRINT, NSET=TIP\nU\n*END STEP\n";
    }
    const std::string job = "cantilever";
    {
        std::ofstream file(dir / (job + ".inp"));
        file << deck.str();
    }
    EXPECT_TRUE(runCalculix(dir, job)) << test::readWhole(dir / (job + ".log"));
    Matrix3 C = Matrix3::Zero();
    std::istringstream in(test::readWhole(dir / (job + ".dat")));
    std::string line;
    int step = -1;
    while (std::getline(in, line)) {
        if (line.find("displacements (") != std::string::npos) ++step;
        std::istringstream fields(line);
        int node = 0;
        std::array<double, 6> u{};
        if (!(fields >> node) || node != 2 || step < 0 || step > 2) continue;
        for (double& v : u) fields >> v;
        C.col(step) = Vector3(u[0], u[1], u[5]);
    }
    return C;
}

struct Agreement {
    double compliance = 0.0, stiffness = 0.0, frequency = 0.0;
};

/// nocdyn's and CalculiX's answers on one robot at one pose.
struct Comparison {
    Agreement agreement;               ///< statics; frequency: CalculiX against `reference`
    std::vector<double> calculix;      ///< CalculiX's lowest frequencies [Hz]
    Vector3 lumped = Vector3::Zero();  ///< nocdyn's lumped frequencies [Hz]
    Eigen::VectorXd elastodynamic;     ///< nocdyn's elastodynamic frequencies [Hz]
};

/// Runs both; the frequencies compared are the lumped ones for rigid bodies, the elastodynamic
/// ones (all of them, or `modes`) when a body is elastic.
Comparison compare(RobotDescription robot, const Pose& p, const std::string& job,
                   MassModel mass_model = MassModel::root, int beam_elements = 1, int modes = 0) {
    const Model model(std::move(robot));
    const StiffnessModel compliance(model);
    Data data(model);
    StiffnessData K;
    LumpedModes lumped;
    Comparison out;
    const Status status = stiffnessAndModes(model, compliance, data, p, K, lumped);
    EXPECT_TRUE(status.ok()) << describe(status, model);
    out.lumped = lumped.frequency;
    ElastodynamicModes elastic;
    EXPECT_TRUE(elastodynamicModes(model, compliance, data, elastic).ok());
    out.elastodynamic = elastic.frequency;
    const Eigen::VectorXd reference = compliance.any_elastic ? out.elastodynamic : Eigen::VectorXd(out.lumped);
    const int n = modes > 0 ? modes : static_cast<int>(reference.size());
    const fs::path dir = test::freshScratchDirectory("stiffness_calculix");
    const auto cantilever = [&](double EA, double EI, double l) { return cantileverCompliance(dir, EA, EI, l); };
    const CalculixModel fe(model, compliance, data, mass_model, beam_elements, cantilever);
    const CalculixModel& fe_modes = fe;
    for (const bool statics : {true, false}) {
        const std::string name = job + (statics ? "_static" : "_modes");
        {
            std::ofstream deck(dir / (name + ".inp"));
            deck << (statics ? fe : fe_modes).deck(statics, n);
        }
        EXPECT_TRUE(runCalculix(dir, name)) << test::readWhole(dir / (name + ".log"));
    }
    const CalculixResult result =
        parseDat(test::readWhole(dir / (job + "_static.dat")), fe.platformPhi(), fe.platformC());
    out.calculix =
        parseDat(test::readWhole(dir / (job + "_modes.dat")), fe_modes.platformPhi(), fe_modes.platformC()).frequency;
    // nocdyn's compliance: dp under the unit generalized forces
    Matrix3 C;
    for (int c = 0; c < 3; ++c) {
        Vector3 dp;
        EXPECT_TRUE(displacementUnderWrench(K, model.length_scale, Vector3::Unit(c), dp));
        C.col(c) = dp;
    }
    // compared with theta in metres (times L), every entry in m/N
    const double L = model.length_scale;
    const Vector3 d(L, 1.0, 1.0);
    const auto scaledC = [&](const Matrix3& m) { return Matrix3(d.asDiagonal() * m * d.asDiagonal()); };
    const auto scaledK = [&](const Matrix3& m) {
        return Matrix3(d.cwiseInverse().asDiagonal() * m * d.cwiseInverse().asDiagonal());
    };
    Agreement& agreement = out.agreement;
    agreement.compliance = (scaledC(result.compliance) - scaledC(C)).norm() / scaledC(C).norm();
    agreement.stiffness = (scaledK(result.compliance.inverse()) - scaledK(K.K)).norm() / scaledK(K.K).norm();
    EXPECT_EQ(out.calculix.size(), static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < std::min(static_cast<std::size_t>(n), out.calculix.size()); ++i) {
        agreement.frequency =
            std::max(agreement.frequency, std::abs(out.calculix[i] / reference(static_cast<Eigen::Index>(i)) - 1.0));
    }
    std::printf("%s: CalculiX vs nocdyn: compliance %.3g, stiffness %.3g, frequencies %.3g (relative)\n", job.c_str(),
                agreement.compliance, agreement.stiffness, agreement.frequency);
    for (std::size_t i = 0; i < out.calculix.size(); ++i) {
        std::printf("  mode %zu: CalculiX %.9g Hz, nocdyn %.9g Hz%s\n", i + 1, out.calculix[i],
                    i < static_cast<std::size_t>(reference.size()) ? reference(static_cast<Eigen::Index>(i)) : 0.0,
                    compliance.any_elastic ? " (elastodynamic)" : " (lumped)");
    }
    return out;
}

Agreement compareWithCalculix(RobotDescription robot, const Pose& p, const std::string& job) {
    return compare(std::move(robot), p, job).agreement;
}

class StiffnessCalculix : public testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists(kCcx))
            NOCDYN_SKIP_OR_FAIL_IN_CI("CalculiX (/usr/bin/ccx, Debian's calculix-ccx) is not installed");
    }
};

TEST_F(StiffnessCalculix, A3PrrWithDriveSpringsAgreesTo1e6) {
    RobotDescription robot = robotDescription("paper-3prr-general");
    const double k[3] = {1.0e5, 2.0e5, 3.0e5};
    for (std::size_t j = 0; j < 3; ++j) robot.limbs[j].joints[0].stiffness = k[j];
    const Agreement a = compareWithCalculix(robot, Pose(0.02, 0.002, -0.001), "prr");
    EXPECT_LT(a.compliance, 1e-6);
    EXPECT_LT(a.stiffness, 1e-6);
    EXPECT_LT(a.frequency, 1e-6);
}

TEST_F(StiffnessCalculix, A3RprWithFlexureHingesAgreesTo1e6) {
    RobotDescription robot = robotDescription("3-rpr");
    const double drive[3] = {2.0e5, 2.5e5, 3.0e5};
    for (std::size_t j = 0; j < 3; ++j) {
        robot.limbs[j].joints[0].stiffness = 40.0 + 5.0 * static_cast<double>(j);
        robot.limbs[j].joints[1].stiffness = drive[j];
        robot.limbs[j].joints[2].stiffness = 25.0 + 3.0 * static_cast<double>(j);
    }
    const Agreement a = compareWithCalculix(robot, Pose(0.02, 0.003, -0.001), "rpr");
    EXPECT_LT(a.compliance, 1e-6);
    EXPECT_LT(a.stiffness, 1e-6);
    EXPECT_LT(a.frequency, 1e-6);
}

TEST_F(StiffnessCalculix, A3RrrWithMotorSpringsAndFlexureElbowsAgreesTo1e6) {
    RobotDescription robot = robotDescription("3-rrr");
    for (std::size_t j = 0; j < 3; ++j) {
        robot.limbs[j].joints[0].stiffness = 20.0 + 2.0 * static_cast<double>(j);
        robot.limbs[j].joints[1].stiffness = 3.0;
    }
    const Agreement a = compareWithCalculix(robot, Pose(0.01, 0.002, 0.003), "rrr");
    EXPECT_LT(a.compliance, 1e-6);
    EXPECT_LT(a.stiffness, 1e-6);
    EXPECT_LT(a.frequency, 1e-6);
}

// The beams' stiffness in the models below: one U1 element with the shear coefficient 1e10 is the
// Euler-Bernoulli cantilever, C_b = [l/EA 0 0; 0 l^3/(3 EI) l^2/(2 EI); 0 l^2/(2 EI) l/EI].
TEST_F(StiffnessCalculix, OneU1ElementIsTheEulerBernoulliCantileverTo1e6) {
    const fs::path dir = test::freshScratchDirectory("stiffness_calculix");
    const double EA = 1.4e7, EI = 466.667, l = 0.105157;
    Matrix3 expected;
    expected << l / EA, 0.0, 0.0, 0.0, l * l * l / (3.0 * EI), l * l / (2.0 * EI), 0.0, l * l / (2.0 * EI), l / EI;
    const Matrix3 C = cantileverCompliance(dir, EA, EI, l);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            if (expected(r, c) == 0.0) {
                EXPECT_LT(std::abs(C(r, c)), 1e-12 * expected.norm()) << r << ", " << c;
            } else {
                EXPECT_NEAR(C(r, c) / expected(r, c), 1.0, 1e-6) << r << ", " << c;
            }
        }
    }
}

// Elastic links: CalculiX's beams are its U1 element with a shear coefficient of 1e10 (Euler-
// Bernoulli); the mass model is nocdyn's elastodynamic one (each link's inertia on its root frame,
// its beam massless), so every elastodynamic frequency must agree, not only the lowest three.
// The beam's segmentation must not matter for massless beams: 1 and 4 segments per link.
TEST_F(StiffnessCalculix, A3RrrWithElasticLinksAgreesTo1e6InStiffnessAndEveryElastodynamicMode) {
    for (const int segments : {1, 4}) {
        const Comparison c = compare(robotDescription("3-rrr-elastic"), Pose(0.01, 0.002, 0.003),
                                     "rrr_elastic_" + std::to_string(segments), MassModel::root, segments);
        EXPECT_EQ(c.elastodynamic.size(), 15);  // 3 platform + 12 beam-deflection DOFs with mass
        EXPECT_LT(c.agreement.compliance, 1e-6);
        EXPECT_LT(c.agreement.stiffness, 1e-6);
        EXPECT_LT(c.agreement.frequency, 1e-6);
    }
}

TEST_F(StiffnessCalculix, ThePaper3PrrWithElasticLinksAgreesTo1e6InStiffnessAndEveryElastodynamicMode) {
    const Comparison c = compare(robotDescription("paper-3prr-compliant"), Pose(0.01, 0.002, -0.001), "prr_elastic");
    EXPECT_EQ(c.elastodynamic.size(), 9);
    EXPECT_LT(c.agreement.compliance, 1e-6);
    EXPECT_LT(c.agreement.stiffness, 1e-6);
    EXPECT_LT(c.agreement.frequency, 1e-6);
}

// The lumped model (rigid links' inertia on the pose coordinates, K from every compliance) against
// the elastodynamic one: the links' inertia no longer follows their beams' deflection, so the
// lumped frequencies are lower. Measured (docs/stiffness-validation.md).
TEST_F(StiffnessCalculix, TheLumpedModelIsWithin0p2PercentOfTheElastodynamicOneOnBothElasticRobots) {
    struct Case {
        const char* robot;
        Pose p;
        std::array<double, 3> lumped_over_elastodynamic;  // minus 1, measured
    };
    const Case cases[] = {
        {"3-rrr-elastic", Pose(0.01, 0.002, 0.003), {-1.33192e-3, -1.44579e-3, -1.76810e-3}},
        {"paper-3prr-compliant", Pose(0.01, 0.002, -0.001), {-8.85272e-5, -1.57557e-4, -1.38208e-3}},
    };
    for (const Case& k : cases) {
        const Comparison c = compare(robotDescription(k.robot), k.p, std::string("lumped_") + k.robot);
        for (int i = 0; i < 3; ++i) {
            const double d = c.lumped(i) / c.elastodynamic(i) - 1.0;
            std::printf("%s mode %d: lumped %.9g Hz, elastodynamic %.9g Hz, lumped/elastodynamic - 1 = %.6g\n", k.robot,
                        i + 1, c.lumped(i), c.elastodynamic(i), d);
            EXPECT_LT(std::abs(d), 2e-3);
            EXPECT_NEAR(d, k.lumped_over_elastodynamic[static_cast<std::size_t>(i)], 1e-7);
        }
    }
}

// The mass-model error: CalculiX with each link's mass spread along its beam (Euler-Bernoulli's
// continuum, lumped at the beam's nodes, converged in the segment count) against nocdyn's
// elastodynamic model, whose link inertia rides on its root. Measured (docs/stiffness-validation.md).
TEST_F(StiffnessCalculix, ADistributedLinkMassLowersThe3RrrsFirstFrequenciesByAbout0p1Percent) {
    std::vector<Comparison> runs;
    for (const int segments : {8, 16}) {
        runs.push_back(compare(robotDescription("3-rrr-elastic"), Pose(0.01, 0.002, 0.003),
                               "rrr_distributed_" + std::to_string(segments), MassModel::distributed, segments, 6));
    }
    const std::array<double, 3> measured{-1.0496e-3, -1.1390e-3, -1.39556e-3};  // continuum / elastodynamic - 1
    for (std::size_t i = 0; i < 3; ++i) {
        // lumped nodal masses converge as 1/N^2: Richardson's extrapolation from 8 and 16 segments
        const double f8 = runs[0].calculix[i], f16 = runs[1].calculix[i];
        const double continuum = f16 + (f16 - f8) / 3.0;
        const double elastodynamic = runs[1].elastodynamic(static_cast<Eigen::Index>(i));
        const double d = continuum / elastodynamic - 1.0;
        std::printf(
            "mode %zu: CalculiX 8 segments %.7g, 16 segments %.7g, extrapolated %.7g Hz; nocdyn elastodynamic "
            "%.9g, lumped %.9g Hz; continuum/elastodynamic - 1 = %.6g\n",
            i + 1, f8, f16, continuum, elastodynamic, runs[1].lumped(static_cast<Eigen::Index>(i)), d);
        EXPECT_LT(std::abs(f16 / f8 - 1.0), 2e-3);
        EXPECT_NEAR(d, measured[i], 2e-5);  // CalculiX prints 7 digits
    }
    // the beams' own modes are beyond the elastodynamic model: its 4th mode (the links swinging on
    // their beams' tip springs) against the continuum's first bending mode
    std::printf("mode 4: CalculiX (16 segments) %.7g Hz, nocdyn elastodynamic %.7g Hz\n", runs[1].calculix[3],
                runs[1].elastodynamic(3));
}

}  // namespace
}  // namespace nocdyn
