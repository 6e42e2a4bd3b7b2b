// Static stiffness and natural frequencies by the virtual joint method (stiffness.hpp).
#include "nocdyn/analysis/stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "nocdyn/detail/eigen_instances.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"

namespace nocdyn {

namespace {

constexpr double kRankTolerance = 1e-9;  // relative, on unit columns in metres
constexpr int kMaxLimbColumns = 9;       // 3 joints + 2 beams of 3 deflections
/// Every small matrix this file decomposes (a limb's columns, the carried rows, a block of K or M)
/// has this one type: dynamic sizes within a fixed capacity, so that nothing allocates, and one
/// instantiation of each Eigen decomposition (JacobiSVD and its QR preconditioners, LLT, the
/// eigensolvers) instead of one per shape, a third of this file's compile time.
constexpr int kMaxWork = std::max(3 * kMaxLimbs, kMaxLimbColumns);
using Work = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxWork, kMaxWork>;
/// A limb's joint and beam twists, column by column (3 x at most kMaxLimbColumns).
using LimbColumns = Work;
/// The rows N_j^T S_s of every limb: the platform directions each limb carries a wrench in.
using CarriedRows = Work;

/// D = diag(L, 1, 1): a twist with its rotation in metres (or a pose with theta in metres).
Vector3 scaled(const Vector3& v, double L) { return {v(0) * L, v(1), v(2)}; }

/// The current point of a revolute joint from its screw s = [1; r_y; -r_x].
Vector2 revolutePoint(const Twist& s) { return {-s(2), s(1)}; }

/// The twists G_b = [[0; e], [0; n], s_B] of beam b's tip deflection [u_e, v_n, phi].
Matrix3 beamTwists(const LimbData& limb, int b) {
    const Vector2 a = revolutePoint(limb.s[static_cast<std::size_t>(b)]);
    const Vector2 tip = revolutePoint(limb.s[static_cast<std::size_t>(b) + 1]);
    const Vector2 e = (tip - a).normalized();
    const Vector2 n = perp(e);
    Matrix3 G;
    G.col(0) = Twist(0.0, e.x(), e.y());
    G.col(1) = Twist(0.0, n.x(), n.y());
    G.col(2) = limb.s[static_cast<std::size_t>(b) + 1];
    return G;
}

}  // namespace

std::string coordinateLabel(int r) {
    const PoseCoordinate& c = kReportedCoordinates[static_cast<std::size_t>(r)];
    return std::string(c.name) + " [" + c.unit + "]";
}

std::string stiffnessUnit(int r, int c) {
    const bool moment = kReportedCoordinates[static_cast<std::size_t>(r)].index == 0;
    const bool angle = kReportedCoordinates[static_cast<std::size_t>(c)].index == 0;
    if (moment) return angle ? "N m/rad" : "N";
    return angle ? "N/rad" : "N/m";
}

Vector3 reported(const Vector3& v) {
    Vector3 out;
    for (int r = 0; r < 3; ++r) out(r) = v(kReportedCoordinates[static_cast<std::size_t>(r)].index);
    return out;
}

Matrix3 reported(const Matrix3& m) {
    Matrix3 out;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            out(r, c) = m(kReportedCoordinates[static_cast<std::size_t>(r)].index,
                          kReportedCoordinates[static_cast<std::size_t>(c)].index);
        }
    }
    return out;
}

std::string describeDirection(const Vector3& dp) {
    std::ostringstream out;
    out.precision(6);
    const Vector2 v = dp.tail<2>();
    if (std::abs(dp(0)) > 1e-12 * (1.0 + v.norm())) {
        // dp = [w, v]: a rotation w about the point P with v = -w E (P - C), P = C + E v / w
        const Vector2 centre = perp(v) / dp(0);
        out << "a rotation about the point (x, y) = (" << centre.x() + 0.0 << ", " << centre.y() + 0.0
            << ") m from the platform's reference point";
    } else {
        const Vector2 d = v.normalized();
        out << "a translation along (x, y) = (" << d.x() + 0.0 << ", " << d.y() + 0.0 << ")";
    }
    return out.str();
}

StiffnessModel::StiffnessModel(const Model& model) {
    for (int j = 0; j < model.limbs; ++j) {
        const LimbDescription& limb = model.description.limbs[static_cast<std::size_t>(j)];
        const auto J = static_cast<std::size_t>(j);
        for (std::size_t q = 0; q < 3; ++q) {
            const JointDescription& jd = limb.joints[q];
            if (jd.stiffness) {
                any = true;
                k[J][q] = *jd.stiffness;
                joint[J][q] = *jd.stiffness > 0.0 ? JointSpring::spring : JointSpring::free;
            } else {
                joint[J][q] = jd.actuated ? JointSpring::locked : JointSpring::free;
            }
        }
        for (std::size_t b = 0; b < 2; ++b) {
            const BodyDescription& body = limb.bodies[b];
            if (!body.elastic) continue;
            any = any_elastic = true;
            elastic[J][b] = true;
            const double l = (limb.joints[b + 1].point - limb.joints[b].point).norm();
            const double EA = body.elastic->EA, EI = body.elastic->EI;
            Matrix3& C = beam_compliance[J][b];
            C << l / EA, 0.0, 0.0, 0.0, l * l * l / (3.0 * EI), l * l / (2.0 * EI), 0.0, l * l / (2.0 * EI), l / EI;
        }
    }
}

std::string contrastWarning(const StiffnessData& stiffness) {
    if (!(stiffness.contrast > kContrastWarning)) return {};
    std::ostringstream out;
    out.precision(3);
    out << "stiffness contrast " << stiffness.contrast
        << " between the stiffest and the softest direction the platform is held in: the softest stiffness and the "
           "lowest natural frequency are known only to about "
        << std::numeric_limits<double>::epsilon() * stiffness.contrast << " (relative)";
    return out.str();
}

Status cartesianStiffness(const Model& model, const StiffnessModel& compliance, const Data& data, StiffnessData& out) {
    const double L = model.length_scale;
    Matrix3 K_twist = Matrix3::Zero();
    const Matrix3 S = platformTwistMap(data.p.tail<2>());
    const Vector3 d(L, 1.0, 1.0), inv_d(1.0 / L, 1.0, 1.0);
    const Matrix3 S_s = d.asDiagonal() * S * inv_d.asDiagonal();  // scaled twist of a scaled dp
    CarriedRows carried(0, 3);
    for (int j = 0; j < model.limbs; ++j) {
        const auto J = static_cast<std::size_t>(j);
        const LimbData& limb = data.limb[J];
        // C_s: the springs' compliance on scaled twists; free and all yielding unit columns
        Matrix3 C = Matrix3::Zero();
        LimbColumns free(3, 0), yielding(3, 0);
        const auto append = [](LimbColumns& m, const Vector3& column) {
            m.conservativeResize(Eigen::NoChange, m.cols() + 1);
            m.col(m.cols() - 1) = column.normalized();
        };
        for (std::size_t q = 0; q < 3; ++q) {
            const Vector3 s = scaled(limb.s[q], L);
            switch (compliance.joint[J][q]) {
                case JointSpring::locked:
                    break;
                case JointSpring::free:
                    append(free, s);
                    append(yielding, s);
                    break;
                case JointSpring::spring:
                    C.noalias() += s * s.transpose() / compliance.k[J][q];
                    append(yielding, s);
                    break;
            }
        }
        for (int b = 0; b < 2; ++b) {
            if (!compliance.elastic[J][static_cast<std::size_t>(b)]) continue;
            Matrix3 G = beamTwists(limb, b);
            for (int c = 0; c < 3; ++c) G.col(c) = scaled(G.col(c), L);
            C.noalias() += G * compliance.beam_compliance[J][static_cast<std::size_t>(b)] * G.transpose();
            for (int c = 0; c < 3; ++c) append(yielding, G.col(c));
        }
        // a limb whose yielding joints and beams do not span the plane's twists is rigid
        if (yielding.cols() < 3) return {StatusCode::rigid_limb, j, 0.0};
        const Eigen::JacobiSVD<LimbColumns> span(yielding);
        if (!(span.singularValues()(2) > kRankTolerance * span.singularValues()(0))) {
            return {StatusCode::rigid_limb, j, 0.0};
        }
        // N: the wrenches the free joints let through, null(G_f^T)
        Matrix3 N = Matrix3::Identity();
        int rank_free = 0;
        if (free.cols() > 0) {
            const Eigen::JacobiSVD<LimbColumns> svd(free, Eigen::ComputeFullU);
            for (Eigen::Index i = 0; i < svd.singularValues().size(); ++i) {
                rank_free += svd.singularValues()(i) > kRankTolerance * svd.singularValues()(0) ? 1 : 0;
            }
            N = svd.matrixU();
        }
        const int m = 3 - rank_free;
        Matrix3 K_s = Matrix3::Zero();
        if (m > 0) {
            using Small = Work;
            const Work Nm = N.rightCols(m);
            const Small Kc = Nm.transpose() * C * Nm;
            const Eigen::LLT<Small> llt(Kc);
            if (llt.info() != Eigen::Success) return {StatusCode::rigid_limb, j, 0.0};
            const Small inv = llt.solve(Small::Identity(m, m));
            K_s.noalias() = Nm * inv * Nm.transpose();  // K_j = N (N^T C N)^-1 N^T
            // the platform directions this limb holds: N_j^T S_s
            const Eigen::Index rows = carried.rows();
            carried.conservativeResize(rows + m, Eigen::NoChange);
            carried.bottomRows(m) = Nm.transpose() * S_s;
        }
        // back to twists referred to O: K_j = D K_s D
        out.K_limb[J] = d.asDiagonal() * K_s * d.asDiagonal();
        K_twist += out.K_limb[J];
    }
    out.K = S.transpose() * K_twist * S;
    out.K = 0.5 * (out.K + out.K.transpose()).eval();
    // free directions: dp_s with N_j^T S_s dp_s = 0 for every limb, a rank decision on the
    // geometry (unit wrench columns), whatever the springs' values
    Matrix3 basis = Matrix3::Identity();  // [free | held], orthonormal in the scaled pose
    int held = 0;
    if (carried.rows() > 0) {
        const Eigen::JacobiSVD<CarriedRows> svd(carried, Eigen::ComputeFullV);
        const auto& sigma = svd.singularValues();
        for (Eigen::Index i = 0; i < sigma.size(); ++i) held += sigma(i) > kRankTolerance * sigma(0) ? 1 : 0;
        basis = svd.matrixV().rowwise().reverse();  // the smallest singular values first
    }
    out.free_directions = 3 - held;
    out.free.setZero();
    for (int i = 0; i < out.free_directions; ++i) {
        out.free.col(i) = (inv_d.asDiagonal() * basis.col(i)).normalized();
    }
    // the held block's eigen-decomposition, after the free directions (eigenvalue 0)
    const Matrix3 K_scaled = inv_d.asDiagonal() * out.K * inv_d.asDiagonal();
    out.scaled_eigenvalues.setZero();
    out.scaled_eigenvectors = basis;
    out.contrast = 1.0;
    if (held > 0) {
        using Small = Work;
        const Work H = basis.rightCols(held);
        const Small K_held = H.transpose() * K_scaled * H;
        const Eigen::SelfAdjointEigenSolver<Small> eig(K_held);
        out.scaled_eigenvalues.tail(held) = eig.eigenvalues();
        out.scaled_eigenvectors.rightCols(held) = H * eig.eigenvectors();
        const double lowest = eig.eigenvalues()(0), highest = eig.eigenvalues()(held - 1);
        out.contrast = lowest > 0.0 ? highest / lowest : std::numeric_limits<double>::infinity();
        if (!(out.contrast <= kContrastLimit)) return {StatusCode::stiffness_contrast, -1, out.contrast};
    }
    return {};
}

Matrix3 limbCompliance(const StiffnessModel& compliance, const Data& data, int j) {
    const auto J = static_cast<std::size_t>(j);
    const LimbData& limb = data.limb[J];
    Matrix3 C = Matrix3::Zero();
    for (std::size_t q = 0; q < 3; ++q) {
        if (compliance.joint[J][q] == JointSpring::spring)
            C.noalias() += limb.s[q] * limb.s[q].transpose() / compliance.k[J][q];
    }
    for (int b = 0; b < 2; ++b) {
        if (!compliance.elastic[J][static_cast<std::size_t>(b)]) continue;
        const Matrix3 G = beamTwists(limb, b);
        C.noalias() += G * compliance.beam_compliance[J][static_cast<std::size_t>(b)] * G.transpose();
    }
    return C;
}

bool displacementUnderWrench(const StiffnessData& stiffness, double length_scale, const Vector3& f, Vector3& dp) {
    // in the scaled coordinates p_s = D p the generalized force is f_s = D^-1 f
    const Vector3 f_s(f(0) / length_scale, f(1), f(2));
    Vector3 p_s = Vector3::Zero();
    for (int i = 0; i < 3; ++i) {
        const Vector3 v = stiffness.scaled_eigenvectors.col(i);
        const double load = v.dot(f_s);
        if (i < stiffness.free_directions) {
            if (std::abs(load) > 1e-12 * f_s.norm()) return false;
            continue;
        }
        p_s += v * (load / stiffness.scaled_eigenvalues(i));
    }
    dp = Vector3(p_s(0) / length_scale, p_s(1), p_s(2));
    return true;
}

namespace {

/// The mass matrix in the pose coordinates, M = sum_i T_i^T M_i T_i, from the NOC's I.
Matrix3 poseMassMatrix(const Data& data) {
    if (data.coordinates == Coordinates::platform) return data.I;
    // v = du = A S(c) dp/dt
    const Matrix3 AS = Matrix3(data.A) * platformTwistMap(data.p.tail<2>());
    return AS.transpose() * data.I * AS;
}

}  // namespace

bool lumpedHolds(const LumpedModes& lumped, const ElastodynamicModes& elastic) {
    if (elastic.dofs == 0) return true;
    const double a = lumped.frequency(0), b = elastic.frequency(0);
    return !(a > 0.0) || !(b > 0.0) || std::abs(a / b - 1.0) <= kLumpedMismatch;
}

std::string lumpedMismatchWarning(const LumpedModes& lumped, const ElastodynamicModes& elastic, bool elastic_used) {
    if (lumpedHolds(lumped, elastic)) return {};
    std::ostringstream out;
    out.precision(4);
    out << "the lumped model does not hold at this pose: its first natural frequency " << lumped.frequency(0)
        << " Hz against the elastodynamic model's " << elastic.frequency(0)
        << " Hz (it carries the links rigidly with the platform, which fails next to a limb singularity); "
        << (elastic_used ? "the elastodynamic frequencies are used here"
                         : "the elastodynamic frequencies are the ones to use here");
    return out.str();
}

bool lumpedFailsAt(const Model& model, const StiffnessModel& compliance, const Data& data, const LumpedModes& lumped,
                   ElastodynamicModes& elastic) {
    if (!compliance.any_elastic) return false;
    try {
        if (!elastodynamicModes(model, compliance, data, elastic)) return false;
    } catch (const Error&) {
        return false;  // a degree of freedom with neither mass nor stiffness: the lumped model stands
    }
    return elastic.frequency.allFinite() && !lumpedHolds(lumped, elastic);
}

bool nearLimbSingularity(const Model& model, const Data& data) {
    for (int j = 0; j < model.limbs; ++j) {
        if (!(data.limb[static_cast<std::size_t>(j)].cond < kLumpedCheckCondition)) return true;
    }
    return false;
}

double firstFrequency(const Model& model, const StiffnessModel& compliance, const Data& data, const LumpedModes& lumped,
                      std::string* warning) {
    ElastodynamicModes elastic;
    if (!lumpedFailsAt(model, compliance, data, lumped, elastic)) return lumped.frequency(0);
    if (warning) *warning = lumpedMismatchWarning(lumped, elastic, true);
    return elastic.frequency(0);
}

std::string elastodynamicPrecisionWarning(const ElastodynamicModes& elastic) {
    if (!(elastic.precision > 1e-6)) return {};
    std::ostringstream out;
    out.precision(3);
    out << "the elastodynamic model spans frequencies from " << elastic.frequency(0) << " to "
        << elastic.frequency(elastic.dofs - 1) << " Hz: its middle frequencies are known only to about "
        << elastic.precision << " (relative)";
    return out.str();
}

namespace {

/// The elastodynamic modes in flexibility form (stiffness.hpp): x = F f from the mixed system
/// [0 P^T A^T; P -C_s 0; A 0 0], then (L^T F L) y = mu y with M_x = L L^T, w^2 = 1 / mu. Replaces
/// out's lowest modes (frequency, shape in scaled coordinates) where this form is the more
/// precise; out holds the stiffness form's `dofs` modes on entry, the first `free` of them the
/// free directions' (0 Hz, kept). Leaves out as it is when the mixed system is singular (an
/// internal mechanism without stiffness or mass).
void flexibleModes(const Eigen::MatrixXd& Mx, const Eigen::MatrixXd& A, const std::vector<double>& spring,
                   const std::vector<std::pair<int, Matrix3>>& beam_flex, int free, ElastodynamicModes& out) {
    const int dofs = out.dofs;
    if (free >= dofs) return;
    // with free directions, K + sigma M_x (its x block sigma M_x): mu = 1 / (lambda + sigma), the
    // free modes at mu = 1 / sigma first; sigma far below the lowest held lambda costs it nothing
    const double w_held = 2.0 * std::numbers::pi * out.frequency(free);
    const double sigma = free > 0 ? 1e-6 * w_held * w_held : 0.0;
    if (free > 0 && !(sigma > 0.0)) return;
    const Eigen::Index n = Mx.rows();
    // spring coordinates: each joint spring (compliance 1/k), each beam's three (C_b)
    std::vector<Eigen::Index> rows;
    for (std::size_t c = 0; c < spring.size(); ++c) {
        if (spring[c] > 0.0) rows.push_back(3 + static_cast<Eigen::Index>(c));
    }
    const auto joint_springs = static_cast<Eigen::Index>(rows.size());
    const Eigen::Index ns = joint_springs + 3 * static_cast<Eigen::Index>(beam_flex.size());
    const Eigen::Index nc = A.rows();
    const Eigen::Index size = n + ns + nc;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(size, size);
    for (Eigen::Index i = 0; i < joint_springs; ++i) {
        const Eigen::Index c = rows[static_cast<std::size_t>(i)];
        K(n + i, c) = K(c, n + i) = 1.0;
        K(n + i, n + i) = -1.0 / spring[static_cast<std::size_t>(c - 3)];
    }
    Eigen::Index g = n + joint_springs;
    for (const auto& [first, C] : beam_flex) {
        for (Eigen::Index k = 0; k < 3; ++k) K(g + k, first + k) = K(first + k, g + k) = 1.0;
        K.block(g, g, 3, 3) = -C;
        g += 3;
    }
    K.block(n + ns, 0, nc, n) = A;
    K.block(0, n + ns, n, nc) = A.transpose();
    K.topLeftCorner(n, n) = sigma * Mx;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    if (!lu.isInvertible()) return;
    // M_x = L L^T on its range
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> mass(Mx);
    const double top = mass.eigenvalues()(n - 1);
    Eigen::Index first_mass = 0;
    while (first_mass < n && mass.eigenvalues()(first_mass) <= 1e-12 * top) ++first_mass;
    const Eigen::Index rm = n - first_mass;
    if (rm < out.dofs) return;
    const Eigen::MatrixXd L = mass.eigenvectors().rightCols(rm) * mass.eigenvalues().tail(rm).cwiseSqrt().asDiagonal();
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(size, rm);
    rhs.topRows(n) = L;
    const Eigen::MatrixXd FL = lu.solve(rhs).topRows(n);
    Eigen::MatrixXd LtFL = L.transpose() * FL;
    LtFL = 0.5 * (LtFL + LtFL.transpose()).eval();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(LtFL);
    // mu descending: the lowest frequencies first; the stiffness form's lambda range decides
    const double w_high = 2.0 * std::numbers::pi * out.frequency(dofs - 1);
    const double lambda_middle = w_held * w_high;  // sqrt(lambda_min lambda_max) of the held modes
    for (int i = free; i < dofs; ++i) {
        const double mu = eig.eigenvalues()(rm - 1 - i);
        if (!(mu > 0.0)) break;
        const double lambda = 1.0 / mu - sigma;
        if (!(lambda > 0.0 && lambda <= lambda_middle)) break;
        out.frequency(i) = std::sqrt(lambda) / (2.0 * std::numbers::pi);
        out.shape.col(i) = FL * eig.eigenvectors().col(rm - 1 - i) / mu;  // x = F L y / mu, x^T M x = 1
    }
}

}  // namespace

void lumpedModes(const Model& model, const Data& data, const StiffnessData& stiffness, LumpedModes& out) {
    (void)model;
    out.M = poseMassMatrix(data);
    out.M = 0.5 * (out.M + out.M.transpose()).eval();
    const int f = stiffness.free_directions;
    const auto frequencyOf = [](double w2) { return std::sqrt(std::max(w2, 0.0)) / (2.0 * std::numbers::pi); };
    if (f == 0) {
        const Eigen::GeneralizedSelfAdjointEigenSolver<Work> eig(Work(stiffness.K), Work(out.M),
                                                                 Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
        for (int i = 0; i < 3; ++i) out.frequency(i) = frequencyOf(eig.eigenvalues()(i));
        out.shape = eig.eigenvectors();
        return;
    }
    using Cols = Work;
    using Small = Work;
    // the free modes: the free directions F, M-orthonormalised (F R^-1, F^T M F = R^T R)
    const Cols F = stiffness.free.leftCols(f);
    const Small FtMF = F.transpose() * out.M * F;
    const Eigen::LLT<Small> llt(FtMF);
    const Small R = llt.matrixU();
    out.shape.leftCols(f) = F * R.inverse();
    out.frequency.head(f).setZero();
    // the others on the M-orthogonal complement B, null((M F)^T): K restricted there
    const int h = 3 - f;
    if (h == 0) return;
    const Cols MF = out.M * F;
    const Eigen::JacobiSVD<Cols> svd(MF, Eigen::ComputeFullU);
    const Cols B = svd.matrixU().rightCols(h);
    const Small Kh = B.transpose() * stiffness.K * B, Mh = B.transpose() * out.M * B;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Small> eig(Kh, Mh, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    for (int i = 0; i < h; ++i) out.frequency(f + i) = frequencyOf(eig.eigenvalues()(i));
    out.shape.rightCols(h) = B * eig.eigenvectors();
}

void taskModes(const Model& model, const Data& data, const StiffnessData& stiffness, const LumpedModes& lumped,
               TaskModes& out) {
    if (model.task_dimension == 3) {
        out.K = stiffness.K;
        out.M = lumped.M;
        out.frequency = lumped.frequency;
        out.shape = lumped.shape;
        return;
    }
    // translation: E = [0 0; 1 0; 0 1], so E^T X E is X's x, y block
    const Matrix3 M = poseMassMatrix(data);
    const Matrix2 K_t = stiffness.K.bottomRightCorner<2, 2>();
    const Matrix2 M_t = 0.5 * (M.bottomRightCorner<2, 2>() + M.bottomRightCorner<2, 2>().transpose());
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix2> eig(0.5 * (K_t + K_t.transpose()), M_t,
                                                                Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    out.K = K_t;
    out.M = M_t;
    out.frequency.resize(2);
    for (int i = 0; i < 2; ++i)
        out.frequency(i) = std::sqrt(std::max(eig.eigenvalues()(i), 0.0)) / (2.0 * std::numbers::pi);
    out.shape = eig.eigenvectors();
}

Status stiffnessAndModes(const Model& model, const StiffnessModel& compliance, Data& data, const Pose& p,
                         StiffnessData& stiffness, LumpedModes& modes) {
    if (Status s = inverseDisplacement(model, data, p); !s) return s;
    if (Status s = velocityFromPlatformTwist(model, data, Twist::Zero()); !s) return s;
    twistShaping(model, data);
    jointSpaceDynamics(model, data);
    if (Status s = cartesianStiffness(model, compliance, data, stiffness); !s) return s;
    lumpedModes(model, data, stiffness, modes);
    return {};
}

Status elastodynamicModes(const Model& model, const StiffnessModel& compliance, const Data& data,
                          ElastodynamicModes& out) {
    // the limbs' K is computed first: it decides (and names) a rigid limb
    StiffnessData check;
    if (Status s = cartesianStiffness(model, compliance, data, check); !s) return s;
    const double L = model.length_scale;
    // coordinates x = [dp; z_1 ... z_L] in scaled form (angles times L: every one in metres);
    // element e of limb j in chain order: joint 0, beam 0 (3), joint 1, beam 1 (3), joint 2
    struct Column {
        int limb;
        int stage;      // 0..4: joint 0, beam 0, joint 1, beam 1, joint 2
        Vector3 twist;  // scaled twist (D t / s_x) of a unit scaled coordinate
    };
    std::vector<Column> columns;
    std::vector<double> spring;                      // per coordinate: stiffness in scaled units, or 0
    std::vector<std::pair<int, Matrix3>> beams;      // first coordinate, scaled beam stiffness
    std::vector<std::pair<int, Matrix3>> beam_flex;  // first coordinate, scaled beam compliance
    std::vector<double> unit{L, 1.0, 1.0};           // per coordinate: scaled / unscaled
    const Vector3 d(L, 1.0, 1.0);
    for (int j = 0; j < model.limbs; ++j) {
        const auto J = static_cast<std::size_t>(j);
        const LimbData& limb = data.limb[J];
        for (int stage = 0; stage < 5; ++stage) {
            if (stage % 2 == 0) {
                const auto q = static_cast<std::size_t>(stage / 2);
                if (compliance.joint[J][q] == JointSpring::locked) continue;
                const bool angle = model.limb[J].type[q] == JointType::revolute;
                const double sx = angle ? L : 1.0;
                columns.push_back({j, stage, d.cwiseProduct(limb.s[q]) / sx});
                spring.push_back(compliance.joint[J][q] == JointSpring::spring ? compliance.k[J][q] / (sx * sx) : 0.0);
                unit.push_back(sx);
            } else {
                const int b = stage / 2;
                if (!compliance.elastic[J][static_cast<std::size_t>(b)]) continue;
                const Matrix3 G = beamTwists(limb, b);
                const Vector3 sx(1.0, 1.0, L);
                const Matrix3 Kb = compliance.beam_compliance[J][static_cast<std::size_t>(b)].inverse();
                beams.emplace_back(3 + static_cast<int>(columns.size()),
                                   sx.cwiseInverse().asDiagonal() * Kb * sx.cwiseInverse().asDiagonal());
                beam_flex.emplace_back(
                    3 + static_cast<int>(columns.size()),
                    sx.asDiagonal() * compliance.beam_compliance[J][static_cast<std::size_t>(b)] * sx.asDiagonal());
                for (int c = 0; c < 3; ++c) {
                    columns.push_back({j, stage, d.cwiseProduct(G.col(c)) / sx(c)});
                    spring.push_back(0.0);
                    unit.push_back(sx(c));
                }
            }
        }
    }
    const int n = 3 + static_cast<int>(columns.size());
    const Matrix3 S = platformTwistMap(data.p.tail<2>());
    const Vector3 dp_scale(L, 1.0, 1.0);
    Matrix3 S_s;  // D S D_p^-1: the scaled platform twist of a scaled pose displacement
    for (int c = 0; c < 3; ++c) S_s.col(c) = d.cwiseProduct(S.col(c)) / dp_scale(c);
    // closure D S dp - sum D t z = 0, limb by limb
    Eigen::MatrixXd closure = Eigen::MatrixXd::Zero(Eigen::Index{3} * model.limbs, n);
    for (int j = 0; j < model.limbs; ++j) closure.block(Eigen::Index{3} * j, 0, 3, 3) = S_s;
    for (std::size_t c = 0; c < columns.size(); ++c) {
        closure.block(Eigen::Index{3} * columns[c].limb, 3 + static_cast<Eigen::Index>(c), 3, 1) = -columns[c].twist;
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(closure, Eigen::ComputeFullV);
    int rank = 0;
    for (Eigen::Index i = 0; i < svd.singularValues().size(); ++i) {
        rank += svd.singularValues()(i) > kRankTolerance * svd.singularValues()(0) ? 1 : 0;
    }
    const Eigen::MatrixXd Z = svd.matrixV().rightCols(n - rank);
    // H: springs and beams; M_x: every body's inertia, riding on the coordinates inboard of it
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t c = 0; c < spring.size(); ++c)
        H(3 + static_cast<Eigen::Index>(c), 3 + static_cast<Eigen::Index>(c)) = spring[c];
    for (const auto& [first, Kb] : beams) H.block(first, first, 3, 3) = Kb;
    Eigen::MatrixXd Mx = Eigen::MatrixXd::Zero(n, n);
    const auto addBody = [&](const Eigen::MatrixXd& twist_of_x, const InertiaDyad& dyad, const Vector2& com) {
        // t = Ad(com) xi on unscaled twists: [w; v_O + w E com]
        Eigen::MatrixXd T(3, n);
        for (Eigen::Index c = 0; c < n; ++c) {
            const Vector3 xi(twist_of_x(0, c) / L, twist_of_x(1, c), twist_of_x(2, c));
            T.col(c) = twistAt(xi, com);
        }
        Mx.noalias() += T.transpose() * dyad.matrix() * T;
    };
    {
        Eigen::MatrixXd xi = Eigen::MatrixXd::Zero(3, n);
        xi.leftCols(3) = S_s;
        addBody(xi, model.platform_M, data.x_P);
    }
    for (int j = 0; j < model.limbs; ++j) {
        for (int b = 0; b < 2; ++b) {
            Eigen::MatrixXd xi = Eigen::MatrixXd::Zero(3, n);
            const int last_stage = b == 0 ? 0 : 2;  // body 0 after joint 0; body 1 after joint 1
            for (std::size_t c = 0; c < columns.size(); ++c) {
                if (columns[c].limb == j && columns[c].stage <= last_stage) {
                    xi.col(3 + static_cast<Eigen::Index>(c)) = columns[c].twist;
                }
            }
            addBody(xi, model.inertia(model.body(j, b)),
                    data.limb[static_cast<std::size_t>(j)].x[static_cast<std::size_t>(b)]);
        }
    }
    const int r = n - rank;
    Eigen::MatrixXd Kr = Z.transpose() * H * Z, Mr = Z.transpose() * Mx * Z;
    Kr = 0.5 * (Kr + Kr.transpose()).eval();
    Mr = 0.5 * (Mr + Mr.transpose()).eval();
    // degrees of freedom without mass (a beam's tip rotation at a free pivot) are condensed
    // statically, exactly: y = V [a; b], M = diag(M_aa, 0), b = -K_bb^-1 K_ba a
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> mass(Mr);
    int massless = 0;
    while (massless < r && mass.eigenvalues()(massless) <= 1e-12 * mass.eigenvalues()(r - 1)) ++massless;
    const Eigen::MatrixXd& V = mass.eigenvectors();
    const Eigen::MatrixXd Vb = V.leftCols(massless), Va = V.rightCols(r - massless);
    Eigen::MatrixXd Kmass = Va.transpose() * Kr * Va;
    Eigen::MatrixXd back = Eigen::MatrixXd::Zero(massless, r - massless);  // b = back a
    if (massless > 0) {
        const Eigen::MatrixXd Kbb = Vb.transpose() * Kr * Vb;
        const Eigen::LLT<Eigen::MatrixXd> llt(Kbb);
        if (llt.info() != Eigen::Success) {
            throw Error(
                "the elastodynamic model has a degree of freedom with neither mass nor stiffness: give "
                "every body that moves a mass and an inertia");
        }
        back = -llt.solve(Vb.transpose() * Kr * Va);
        Kmass += (Va.transpose() * Kr * Vb) * back;
    }
    out.dofs = r - massless;
    out.K = 0.5 * (Kmass + Kmass.transpose());
    out.M = Va.transpose() * Mr * Va;
    out.M = 0.5 * (out.M + out.M.transpose()).eval();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(out.K, out.M,
                                                                        Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    out.frequency.resize(out.dofs);
    for (int i = 0; i < out.dofs; ++i) {
        const double w2 = i < check.free_directions ? 0.0 : std::max(eig.eigenvalues()(i), 0.0);
        out.frequency(i) = std::sqrt(w2) / (2.0 * std::numbers::pi);
    }
    out.shape = Z * (Va * eig.eigenvectors() + Vb * (back * eig.eigenvectors()));
    // the low modes again in flexibility form (stiffness.hpp), where they keep their digits when
    // the beams are many decades stiffer than the springs; each mode is taken from the form
    // whose rounding is the smaller for it: flexibility below sqrt(lambda_min lambda_max)
    if (out.dofs > 0) flexibleModes(Mx, closure, spring, beam_flex, check.free_directions, out);
    // the rigid image x_a of a unit pose displacement along axis a: per limb the joint
    // coordinates of J_j z = S dp (scaled twists), beams undeformed; phi_i^T M_x x_a, per unscaled
    // unit (x_a scales with dp_scale(a); the shapes are still scaled here)
    {
        Eigen::MatrixXd image = Eigen::MatrixXd::Zero(n, 3);
        image.topRows(3) = Matrix3(dp_scale.asDiagonal());
        bool whole = true;
        for (int j = 0; j < model.limbs && whole; ++j) {
            Matrix3 T;
            std::array<Eigen::Index, 3> at{};
            int joints = 0;
            for (std::size_t c = 0; c < columns.size(); ++c) {
                if (columns[c].limb != j || columns[c].stage % 2 != 0) continue;
                T.col(joints) = columns[c].twist;
                at[static_cast<std::size_t>(joints)] = 3 + static_cast<Eigen::Index>(c);
                ++joints;
            }
            whole = joints == 3;
            if (!whole) break;
            const Matrix3 z = T.fullPivLu().solve(S_s * dp_scale.asDiagonal());
            for (std::size_t q = 0; q < 3; ++q) image.row(at[q]) = z.row(static_cast<Eigen::Index>(q));
        }
        if (whole) {
            out.participation = out.shape.transpose() * (Mx * image);
        } else {
            out.participation.resize(out.dofs, 0);
        }
    }
    for (Eigen::Index c = 0; c < n; ++c) out.shape.row(c) /= unit[static_cast<std::size_t>(c)];
    out.platform_shape = out.shape.topRows(3);
    out.precision = 0.0;
    if (const int f = check.free_directions; out.dofs > f + 1 && out.frequency(f) > 0.0) {
        const double ratio = out.frequency(out.dofs - 1) / out.frequency(f);  // sqrt(lambda_max / lambda_min)
        out.precision = std::numeric_limits<double>::epsilon() * ratio;
    }
    // static condensation onto dp: W = P Z, W^T = Q [R1; 0], y = Q [a; b], dp = R1^T a
    const Eigen::MatrixXd W = Z.topRows(3);
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(W.transpose());
    const Eigen::MatrixXd Q = qr.householderQ();
    const Matrix3 R1 = qr.matrixQR().topRows(3).triangularView<Eigen::Upper>();
    const Eigen::MatrixXd Kq = Q.transpose() * Kr * Q;
    const int inner = r - 3;
    Matrix3 Ka = Kq.topLeftCorner(3, 3);
    if (inner > 0) {
        const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(Kq.bottomRightCorner(inner, inner));
        Ka -= Kq.topRightCorner(3, inner) * cod.solve(Kq.bottomLeftCorner(inner, 3));
    }
    const Matrix3 R1inv = R1.inverse();
    const Matrix3 K_s = R1inv * Ka * R1inv.transpose();  // on p_s = D_p dp
    out.K_condensed = dp_scale.asDiagonal() * K_s * dp_scale.asDiagonal();
    return {};
}

}  // namespace nocdyn
