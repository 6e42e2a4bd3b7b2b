// Errors raised outside the real-time path: invalid robot or trajectory descriptions,
// unreadable files, and samples rejected by the layer above the per-sample algorithms.
#pragma once

#include <stdexcept>
#include <string>

namespace nocdyn {

/// Any error nocdyn reports to a user. what() is one line naming the problem
/// (file, field, line, sample time, limb, as they apply).
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace nocdyn
