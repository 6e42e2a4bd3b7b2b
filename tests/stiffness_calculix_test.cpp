// The platform's static compliance and natural frequencies against CalculiX (Debian's
// calculix-ccx, /usr/bin/ccx) on the same frame, for robots with rigid bodies and joint springs
// (drive springs, flexure hinges), where the lumped, elastodynamic and finite-element models are
// one. The CalculiX input is written here from the robot at the pose, in absolute coordinates,
// independent of the library's joint-space formulation:
//   - every rigid body is a node R at its c.o.m. (translations) and a node PHI whose x
//     displacement is its rotation; a MASS element on R (m) and one on PHI (I about the c.o.m.);
//   - a joint ties the velocities of its two bodies at its point, v_i(r) = u_R + phi E (r - R):
//     R joint: both components; P joint: equal rotations and the component normal to its
//     direction, its slide a node Q with u_Q = d . (v_b - v_a);
//   - a joint spring is a SPRING1/SPRING2 element on the PHI or Q degrees of freedom;
//   - the platform's point C is a node; its load cases give the compliance columns.
// The linear constraints are written in CalculiX's *EQUATION form, one dependent degree of
// freedom each (solved for here by a rank-revealing QR); CalculiX assembles the springs and
// masses, solves the three load cases and the eigenproblem. Its .dat file prints 7 significant
// digits, so agreement is asserted to 1e-6 relative.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/QR>

#include "cli_support.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "skip.hpp"

extern char** environ;

namespace nocdyn {
namespace {

namespace fs = std::filesystem;
using analysis::JointSpring;

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

class CalculixModel {
public:
    CalculixModel(const Model& model, const analysis::StiffnessModel& compliance, const Data& data) {
        const int bodies = model.bodies;
        body_R_.resize(static_cast<std::size_t>(bodies));
        body_PHI_.resize(static_cast<std::size_t>(bodies));
        com_.resize(static_cast<std::size_t>(bodies));
        for (int i = 0; i < bodies; ++i) {
            const bool platform = i == model.platformBody();
            const Vector2 com =
                platform
                    ? Vector2(data.x_P)
                    : data.limb[static_cast<std::size_t>(i % model.limbs)].x[static_cast<std::size_t>(i / model.limbs)];
            com_[static_cast<std::size_t>(i)] = com;
            body_R_[static_cast<std::size_t>(i)] = addNode(com, 2);
            body_PHI_[static_cast<std::size_t>(i)] = addNode(com, 1);
            const InertiaDyad& M = model.inertia(i);
            if (M.mass > 0.0) masses_.push_back({body_R_[static_cast<std::size_t>(i)], M.mass});
            if (M.inertia > 0.0) masses_.push_back({body_PHI_[static_cast<std::size_t>(i)], M.inertia});
        }
        const Vector2 C = data.p.tail<2>();
        node_C_ = addNode(C, 2);
        const int P = model.platformBody();
        // C rides on the platform
        addVelocityRow(node_C_, 1, P, C, -1.0);
        addVelocityRow(node_C_, 2, P, C, -1.0);
        for (int j = 0; j < model.limbs; ++j) {
            const auto J = static_cast<std::size_t>(j);
            for (int k = 0; k < 3; ++k) {
                const auto K = static_cast<std::size_t>(k);
                const int a = k == 0 ? -1 : model.body(j, k - 1);
                const int b = k == 2 ? P : model.body(j, k);
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
                    const Vector2 r = com_[static_cast<std::size_t>(b)];
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
        for (const Mass& m : masses_) {
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
    static constexpr int kPadding = 20;
    struct Node {
        Vector2 point;
        int dofs;
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
    int phi(int body) const { return body < 0 ? -1 : body_PHI_[static_cast<std::size_t>(body)]; }

    /// row += sign * component c of the velocity of body i at point r (nothing for the ground).
    void addVelocity(Row& row, int i, const Vector2& r, int c, double sign) const {
        if (i < 0) return;
        const Vector2 arm = r - com_[static_cast<std::size_t>(i)];
        row[{body_R_[static_cast<std::size_t>(i)], c}] += sign;
        row[{body_PHI_[static_cast<std::size_t>(i)], 1}] += sign * (c == 1 ? -arm.y() : arm.x());
    }
    void addVelocityRow(int node, int c, int body, const Vector2& r, double sign) {
        Row row;
        row[{node, c}] = 1.0;
        addVelocity(row, body, r, c, sign);
        rows_.push_back(row);
    }
    Row relativeRotation(int a, int b) const {
        Row row;
        row[{phi(b), 1}] += 1.0;
        if (a >= 0) row[{phi(a), 1}] -= 1.0;
        return row;
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
    const std::regex number_line(R"(^\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)(\s+(\S+))?\s*$)");
    while (std::getline(in, line)) {
        if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
            ++step;
            eigen = false;
            continue;
        }
        if (line.find("E I G E N V A L U E   O U T P U T") != std::string::npos) {
            eigen = true;
            continue;
        }
        if (line.find("P A R T I C I P A T I O N") != std::string::npos) eigen = false;
        std::smatch m;
        if (!std::regex_match(line, m, number_line)) continue;
        if (eigen && m[6].matched) {
            out.frequency.push_back(std::stod(m[4].str()));
        } else if (!eigen && step >= 0 && step < 3) {
            const int node = std::stoi(m[1].str());
            if (node == phi_node) out.compliance(0, step) = std::stod(m[2].str());
            if (node == c_node) {
                out.compliance(1, step) = std::stod(m[2].str());
                out.compliance(2, step) = std::stod(m[3].str());
            }
        }
    }
    return out;
}

struct Agreement {
    double compliance = 0.0, stiffness = 0.0, frequency = 0.0;
};

Agreement compareWithCalculix(RobotDescription robot, const Pose& p, const std::string& job) {
    const Model model(std::move(robot));
    const analysis::StiffnessModel compliance(model);
    Data data(model);
    analysis::StiffnessData K;
    analysis::LumpedModes modes;
    const Status status = analysis::stiffnessAndModes(model, compliance, data, p, K, modes);
    EXPECT_TRUE(status.ok()) << describe(status, model);
    const CalculixModel fe(model, compliance, data);
    const fs::path dir = test::freshScratchDirectory("stiffness_calculix");
    for (const bool statics : {true, false}) {
        const std::string name = job + (statics ? "_static" : "_modes");
        {
            std::ofstream deck(dir / (name + ".inp"));
            deck << fe.deck(statics, 3);
        }
        EXPECT_TRUE(runCalculix(dir, name)) << test::readWhole(dir / (name + ".log"));
    }
    CalculixResult result = parseDat(test::readWhole(dir / (job + "_static.dat")), fe.platformPhi(), fe.platformC());
    result.frequency =
        parseDat(test::readWhole(dir / (job + "_modes.dat")), fe.platformPhi(), fe.platformC()).frequency;
    // nocdyn's compliance: dp under the unit generalized forces
    Matrix3 C;
    for (int c = 0; c < 3; ++c) {
        Vector3 dp;
        EXPECT_TRUE(analysis::displacementUnderWrench(K, model.length_scale, Vector3::Unit(c), dp));
        C.col(c) = dp;
    }
    // compared with theta in metres (times L), every entry in m/N
    const double L = model.length_scale;
    const Vector3 d(L, 1.0, 1.0);
    const auto scaledC = [&](const Matrix3& m) { return Matrix3(d.asDiagonal() * m * d.asDiagonal()); };
    const auto scaledK = [&](const Matrix3& m) {
        return Matrix3(d.cwiseInverse().asDiagonal() * m * d.cwiseInverse().asDiagonal());
    };
    Agreement agreement;
    agreement.compliance = (scaledC(result.compliance) - scaledC(C)).norm() / scaledC(C).norm();
    agreement.stiffness = (scaledK(result.compliance.inverse()) - scaledK(K.K)).norm() / scaledK(K.K).norm();
    EXPECT_EQ(result.frequency.size(), 3U);
    for (std::size_t i = 0; i < std::min<std::size_t>(3, result.frequency.size()); ++i) {
        agreement.frequency = std::max(
            agreement.frequency, std::abs(result.frequency[i] / modes.frequency(static_cast<Eigen::Index>(i)) - 1.0));
    }
    std::printf(
        "%s: CalculiX vs nocdyn: compliance %.3g, stiffness %.3g, frequencies %.3g (relative); "
        "nocdyn f = %.9g %.9g %.9g Hz\n",
        job.c_str(), agreement.compliance, agreement.stiffness, agreement.frequency, modes.frequency(0),
        modes.frequency(1), modes.frequency(2));
    return agreement;
}

RobotDescription robotDescription(const std::string& robot) {
    return io::loadRobotDescription((fs::path(NOCDYN_SOURCE_DIR) / "robots" / (robot + ".yaml")).string());
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

}  // namespace
}  // namespace nocdyn
