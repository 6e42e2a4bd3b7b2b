// One limb's constants into one lane of a LimbLanes (model.hpp): the per-sample kernel's lanes
// (one limb per lane, Model::lanes) and the batch's (one limb in every lane, once per chunk)
// are filled by the same assignment. Internal (not installed).
#pragma once

#include <cstddef>

#include "nocdyn/model.hpp"

namespace nocdyn::detail {

/// Lane `lane` of `l` holds `limb`'s constants (defined in model.cpp for four and eight lanes).
template <int kN>
void fillLane(LimbLanesOf<kN>& l, std::size_t lane, const LimbModel& limb);
extern template void fillLane<4>(LimbLanesOf<4>& l, std::size_t lane, const LimbModel& limb);
extern template void fillLane<8>(LimbLanesOf<8>& l, std::size_t lane, const LimbModel& limb);

}  // namespace nocdyn::detail
