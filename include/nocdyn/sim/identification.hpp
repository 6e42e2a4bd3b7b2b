// Inertia-parameter identification of the general planar parallel robot, one header per stage:
//   regressor.hpp                tau = Y pi: the standard parameters pi and the regressor Y;
//   base_parameters.hpp          the identifiable combinations beta = K pi;
//   identification_options.hpp   calibration, payload bounds, the options of the fit;
//   motion.hpp                   measurements, and the motion reconstructed from them;
//   least_squares.hpp            the payload or the base parameters by weighted least squares.
#pragma once

#include "nocdyn/sim/base_parameters.hpp"
#include "nocdyn/sim/identification_options.hpp"
#include "nocdyn/sim/least_squares.hpp"
#include "nocdyn/sim/motion.hpp"
#include "nocdyn/sim/regressor.hpp"
