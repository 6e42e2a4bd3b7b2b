// The excitation design's optimisers (excitation.cpp): Nelder-Mead and BFGS on an objective
// that counts its evaluations against a budget. Private to the sim layer.
#pragma once

#include <functional>
#include <utility>

#include <Eigen/Core>

namespace nocdyn::detail {

/// f(x), the objective at x.
using Objective = std::function<double(const Eigen::VectorXd& x)>;
/// The objective's gradient at x into g; returns a value that is not finite where there is none.
using ObjectiveGradient = std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd& g)>;

/// Nelder-Mead on f from x0 (standard coefficients), at most `budget` evaluations.
std::pair<Eigen::VectorXd, double> nelderMead(const Objective& f, const Eigen::VectorXd& x0, double f0, double step,
                                              int budget, int& used);

/// BFGS on the exact gradient from x0 (f: the design objective, the shape judged at its largest
/// scale; grad: its gradient at the shape f judged last, each counting as one evaluation), at
/// most `budget` evaluations. f is invariant to the shape's size (the scale absorbs it), so
/// the gradient's part along the shape is removed. The first step (and a step after a restart)
/// is a quarter of the shape's norm along -g; backtracking halves the step until f decreases by
/// 1e-4 of the predicted decrease (Armijo); a line search that fails restarts from the scaled
/// identity once, twice in a row ends the refinement.
std::pair<Eigen::VectorXd, double> bfgs(const Objective& f, const ObjectiveGradient& grad, const Eigen::VectorXd& x0,
                                        double f0, int budget, int& used, int& gradients);

}  // namespace nocdyn::detail
