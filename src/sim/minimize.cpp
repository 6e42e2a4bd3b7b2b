// Nelder-Mead and BFGS for the excitation design (minimize.hpp).
#include "minimize.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "nocdyn/detail/index.hpp"

namespace nocdyn::detail {

/// Nelder-Mead on f from x0 (standard coefficients), at most `budget` evaluations.
std::pair<Eigen::VectorXd, double> nelderMead(const Objective& f, const Eigen::VectorXd& x0, double f0, double step,
                                              int budget, int& used) {
    const auto d = x0.size();
    std::vector<Eigen::VectorXd> x(at(static_cast<int>(d) + 1), x0);
    std::vector<double> fx(x.size(), f0);
    for (Eigen::Index i = 0; i < d && used < budget; ++i) {
        x[at(static_cast<int>(i) + 1)](i) += step;
        fx[at(static_cast<int>(i) + 1)] = f(x[at(static_cast<int>(i) + 1)]);
        ++used;
    }
    std::vector<std::size_t> order(x.size());
    while (used < budget) {
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t l, std::size_t r) { return fx[l] < fx[r]; });
        const std::size_t best = order.front(), worst = order.back(), second = order[order.size() - 2];
        Eigen::VectorXd centroid = Eigen::VectorXd::Zero(d);
        for (std::size_t i = 0; i + 1 < order.size(); ++i) centroid += x[order[i]];
        centroid /= static_cast<double>(d);
        const Eigen::VectorXd reflected = centroid + (centroid - x[worst]);
        const double fr = f(reflected);
        ++used;
        if (fr < fx[best] && used < budget) {
            const Eigen::VectorXd expanded = centroid + 2.0 * (centroid - x[worst]);
            const double fe = f(expanded);
            ++used;
            if (fe < fr) {
                x[worst] = expanded;
                fx[worst] = fe;
            } else {
                x[worst] = reflected;
                fx[worst] = fr;
            }
        } else if (fr < fx[second]) {
            x[worst] = reflected;
            fx[worst] = fr;
        } else if (used < budget) {
            const Eigen::VectorXd contracted = centroid + 0.5 * (x[worst] - centroid);
            const double fc = f(contracted);
            ++used;
            if (fc < fx[worst]) {
                x[worst] = contracted;
                fx[worst] = fc;
            } else {
                // shrink towards the best
                for (std::size_t i = 0; i < x.size() && used < budget; ++i) {
                    if (i == best) continue;
                    x[i] = x[best] + 0.5 * (x[i] - x[best]);
                    fx[i] = f(x[i]);
                    ++used;
                }
            }
        }
    }
    const auto best = static_cast<std::size_t>(std::min_element(fx.begin(), fx.end()) - fx.begin());
    return {x[best], fx[best]};
}

/// BFGS on the exact gradient from x0 (f: the design objective, the shape judged at its largest
/// scale; grad: its gradient at the shape f judged last, each counting as one evaluation), at
/// most `budget` evaluations. f is invariant to the shape's size (the scale absorbs it), so
/// the gradient's part along the shape is removed. The first step (and a step after a restart)
/// is a quarter of the shape's norm along -g; backtracking halves the step until f decreases by
/// 1e-4 of the predicted decrease (Armijo); a line search that fails restarts from the scaled
/// identity once, twice in a row ends the refinement.
std::pair<Eigen::VectorXd, double> bfgs(const Objective& f, const ObjectiveGradient& grad, const Eigen::VectorXd& x0,
                                        double f0, int budget, int& used, int& gradients) {
    const auto d = x0.size();
    Eigen::VectorXd x = x0, g, g_new;
    double fx = f0;
    const auto gradient = [&](const Eigen::VectorXd& at_x, Eigen::VectorXd& out) {
        ++used;
        ++gradients;
        if (!std::isfinite(grad(at_x, out))) return false;
        out -= (out.dot(at_x) / at_x.squaredNorm()) * at_x;
        return out.allFinite();
    };
    if (used >= budget || !gradient(x, g)) return {x, fx};
    Eigen::MatrixXd H;
    bool restarted = false;
    const auto reset = [&] { H = (0.25 * x.norm() / std::max(g.norm(), 1e-300)) * Eigen::MatrixXd::Identity(d, d); };
    reset();
    while (used < budget) {
        const Eigen::VectorXd step = -H * g;
        const double slope = g.dot(step);
        if (!(slope < 0.0)) {
            if (restarted) break;
            reset();
            restarted = true;
            continue;
        }
        double t = 1.0, ft = fx;
        Eigen::VectorXd trial;
        bool accepted = false;
        while (used < budget && t >= 1e-6) {
            trial = x + t * step;
            ft = f(trial);
            ++used;
            if (ft <= fx + 1e-4 * t * slope) {
                accepted = true;
                break;
            }
            t *= 0.5;
        }
        if (!accepted) {
            if (restarted || used >= budget) break;
            reset();
            restarted = true;
            continue;
        }
        restarted = false;
        const Eigen::VectorXd s_k = trial - x;
        x = trial;
        fx = ft;
        if (used >= budget || !gradient(x, g_new)) break;
        const Eigen::VectorXd y_k = g_new - g;
        g = g_new;
        const double sy = s_k.dot(y_k);
        if (sy > 1e-12 * s_k.norm() * y_k.norm()) {
            // H+ = (I - rho s y^T) H (I - rho y s^T) + rho s s^T
            const double rho = 1.0 / sy;
            const Eigen::VectorXd Hy = H * y_k;
            H += rho * rho * (y_k.dot(Hy) + sy) * s_k * s_k.transpose() -
                 rho * (Hy * s_k.transpose() + s_k * Hy.transpose());
        }
    }
    return {x, fx};
}

}  // namespace nocdyn::detail
