// The one instantiation of the decompositions declared in nocdyn/detail/eigen_instances.hpp.
#define NOCDYN_EIGEN_INSTANCES
#include "nocdyn/detail/eigen_instances.hpp"
