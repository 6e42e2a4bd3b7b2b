// Base parameters by a column-pivoted QR of random motions' regressors (base_parameters.hpp).
#include "nocdyn/sim/base_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "nocdyn/detail/eigen_instances.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/printable.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/detail/index.hpp"

namespace nocdyn {

namespace {

using detail::at;

/// Random motions around home (poses, rates, accelerations), each accepted by the stages.
struct RandomMotion {
    Pose p;
    Twist dp, ddp;
};

std::vector<RandomMotion> randomMotions(const Model& model, int count, unsigned seed, double scale) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<RandomMotion> motions;
    Data data(model);
    const double L = model.length_scale;
    for (int attempt = 0; attempt < 50 * count && static_cast<int>(motions.size()) < count; ++attempt) {
        RandomMotion m;
        m.p = model.home + scale * Pose(0.05 * unit(rng), 0.05 * L * unit(rng), 0.05 * L * unit(rng));
        m.dp = Twist(unit(rng), L * unit(rng), L * unit(rng));
        m.ddp = 20.0 * Twist(unit(rng), L * unit(rng), L * unit(rng));
        if (model.task_dimension == 2) {
            // translation: theta is no coordinate (it stays at home(0), its rates 0)
            m.p(0) = model.home(0);
            m.dp(0) = 0.0;
            m.ddp(0) = 0.0;
        }
        if (!inverseDynamics(model, data, m.p, m.dp, m.ddp)) continue;
        motions.push_back(m);
    }
    return motions;
}

}  // namespace

BaseParameters baseParameters(const Model& model, const BaseParameterOptions& options) {
    const std::vector<RandomMotion> motions = randomMotions(model, options.samples, options.seed, options.pose_scale);
    const int P = parameterCount(model);
    const int n = model.actuators;
    if (static_cast<int>(motions.size()) * n < 2 * P) {
        throw Error("base parameters: only " + std::to_string(motions.size()) +
                    " random motions around home are valid; the robot may be singular at home");
    }
    Eigen::MatrixXd stacked(static_cast<Eigen::Index>(motions.size()) * n, P);
    Data data(model);
    RegressorMatrix Y;
    for (std::size_t s = 0; s < motions.size(); ++s) {
        (void)inverseDynamicsRegressor(model, data, motions[s].p, motions[s].dp, motions[s].ddp, Y);
        stacked.middleRows(static_cast<Eigen::Index>(s) * n, n) = Y;
    }
    // columns scaled to unit norm; those with no effect on tau are unidentifiable
    const Eigen::VectorXd norms = stacked.colwise().norm();
    const double largest = norms.maxCoeff();
    BaseParameters base;
    std::vector<int> active;
    for (int c = 0; c < P; ++c) {
        if (norms(c) <= options.tolerance * largest) {
            base.unidentifiable.push_back(c);
        } else {
            active.push_back(c);
        }
    }
    const auto m = static_cast<Eigen::Index>(active.size());
    Eigen::MatrixXd scaled(stacked.rows(), m);
    for (Eigen::Index c = 0; c < m; ++c)
        scaled.col(c) = stacked.col(active[at(static_cast<int>(c))]) / norms(active[at(static_cast<int>(c))]);
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
    qr.setThreshold(options.tolerance);
    const auto r = static_cast<Eigen::Index>(qr.rank());
    base.rank = static_cast<int>(r);
    const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(r, m).template triangularView<Eigen::Upper>();
    const Eigen::MatrixXd R1 = R.leftCols(r);
    // dependent scaled columns = independent ones X_s: X_s = R1^-1 R2
    const Eigen::MatrixXd X_s = R1.triangularView<Eigen::Upper>().solve(R.rightCols(m - r));
    const auto& perm = qr.colsPermutation().indices();
    base.K = Eigen::MatrixXd::Zero(r, P);
    for (Eigen::Index k = 0; k < r; ++k) {
        const int ik = active[at(perm(k))];
        base.independent.push_back(ik);
        base.K(k, ik) = 1.0;
        for (Eigen::Index l = 0; l < m - r; ++l) {
            const int il = active[at(perm(r + l))];
            // unscaled: X = D1^-1 X_s D2
            const double x = X_s(k, l) * norms(il) / norms(ik);
            if (std::abs(x) > 1e-10) base.K(k, il) = x;
        }
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(R1);
    base.condition = svd.singularValues()(0) / svd.singularValues()(r - 1);
    return base;
}

std::string describeBaseParameters(const Model& model, const BaseParameters& base) {
    std::ostringstream out;
    const ParameterVector pi = standardParameters(model);
    const int P = parameterCount(model);
    out << "# " << text::printable(model.description.name) << ": " << P << " standard parameters, " << base.rank
        << " identifiable combinations (base parameters), condition number " << base.condition << "\n";
    out << "# Standard parameters per body (body frame): m, mc_x, mc_y = m * c.o.m., I_O = inertia about the\n"
           "# frame origin (limb bodies: the base frame at home; platform: C, turning with theta);\n"
           "# per joint: damping and Coulomb friction.\n";
    const Eigen::VectorXd beta = base.K * pi;
    std::string buffer;
    for (int k = 0; k < base.rank; ++k) {
        out << "beta_" << (k + 1) << " = " << text::printable(parameterName(model, base.independent[at(k)]));
        for (int c = 0; c < P; ++c) {
            const double x = base.K(k, c);
            if (c == base.independent[at(k)] || x == 0.0) continue;
            buffer = text::format(" %c %.6g ", x < 0.0 ? '-' : '+', std::abs(x));
            out << buffer << text::printable(parameterName(model, c));
        }
        buffer = text::format("%.9g", beta(k));
        out << "   (robot file: " << buffer << " " << parameterUnit(model, base.independent[at(k)]) << ")\n";
    }
    if (base.unidentifiable.empty()) {
        out << "unidentifiable (no effect on the actuator forces): none\n";
    } else {
        out << "unidentifiable (no effect on the actuator forces):";
        for (const int c : base.unidentifiable) out << " " << text::printable(parameterName(model, c));
        out << "\n";
    }
    // standard parameters only identifiable in combination
    std::vector<int> combined;
    for (int c = 0; c < P; ++c) {
        if (std::find(base.independent.begin(), base.independent.end(), c) != base.independent.end()) continue;
        if (std::find(base.unidentifiable.begin(), base.unidentifiable.end(), c) != base.unidentifiable.end()) continue;
        combined.push_back(c);
    }
    out << "identifiable only in the combinations above:";
    if (combined.empty()) out << " none";
    for (const int c : combined) out << " " << text::printable(parameterName(model, c));
    out << "\n";
    return out.str();
}
}  // namespace nocdyn
