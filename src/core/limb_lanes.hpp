// The limbs' constants lane by lane, the layout of the lean per-sample kernel and of the batch:
// the kernel's lanes (one limb per lane, held by the Model) and the batch's (one limb in every
// lane, once per chunk) are filled by the same assignment. Internal (not installed).
#pragma once

#include <array>
#include <cstddef>
#include <new>

#include "nocdyn/model.hpp"

namespace nocdyn {

/// The constants of up to kN limbs side by side, lane l = limb l (lanes past the last limb
/// repeat limb 0), for the lean per-sample kernel: on a robot whose limbs are uniform
/// (Model::uniform_limbs) it runs every limb at once in the lanes of one vector. The batch
/// fills every lane with one limb (four or eight lanes, its packet's width).
template <int kN>
struct LimbLanesOf {
    static constexpr int kLanes = kN;
    using Lane = std::array<double, kLanes>;
    std::array<Lane, 3> point_x{}, point_y{};            ///< LimbModel::point
    std::array<Lane, 3> point_home_x{}, point_home_y{};  ///< LimbModel::point_home
    std::array<Lane, 3> direction_x{}, direction_y{};    ///< LimbModel::direction
    std::array<Lane, 2> com_x{}, com_y{};                ///< LimbModel::com_home
    std::array<Lane, 2> mass{}, inertia{};               ///< LimbModel::M
    std::array<Lane, 3> damping{}, friction{};
    Lane screw_x{}, screw_y{};  ///< LimbModel::screw_home[0](1), (2)
    Lane length1{}, length2{}, inv_length1_sq{}, inv_length2_sq{};
    Lane branch{};  ///< LimbModel::branch
};
using LimbLanes = LimbLanesOf<4>;

namespace detail {

/// Lane `lane` of `l` holds `limb`'s constants (defined in model.cpp for four and eight lanes).
template <int kN>
void fillLane(LimbLanesOf<kN>& l, std::size_t lane, const LimbModel& limb);
extern template void fillLane<4>(LimbLanesOf<4>& l, std::size_t lane, const LimbModel& limb);
extern template void fillLane<8>(LimbLanesOf<8>& l, std::size_t lane, const LimbModel& limb);

/// The per-sample kernel's view of a Model: its limbs lane by lane, in the Model's private
/// storage (sized for LimbLanes; the object is created there by model.cpp's fillLanes).
struct ModelKernel {
    [[nodiscard]] static const LimbLanes& lanes(const Model& model) {
        static_assert(sizeof(LimbLanes) == sizeof(model.lanes_) && alignof(LimbLanes) == alignof(double));
        return *std::launder(reinterpret_cast<const LimbLanes*>(model.lanes_.data()));
    }
    /// A LimbLanes, value-initialised, in the model's storage; limbs not yet in use.
    [[nodiscard]] static LimbLanes& startLanes(Model& model) {
        model.limbs_in_lanes_ = false;
        return *new (model.lanes_.data()) LimbLanes{};
    }
    /// Whether the per-sample path reads the lanes (Model::limbsInLanes). A model whose limbs'
    /// constants are changed after construction is set back to the per-limb path.
    static void setLimbsInLanes(Model& model, bool in_lanes) { model.limbs_in_lanes_ = in_lanes; }
};

}  // namespace detail
}  // namespace nocdyn
