// Small helpers shared by the library's source files (one definition each, so that a folder's
// files can also be read as one translation unit, as the lint does). Not part of the API.
#pragma once

#include <cstddef>

namespace nocdyn::detail {

/// A limb, joint or column number held as int (the model's counts) as a std::vector index.
[[nodiscard]] constexpr std::size_t at(int i) noexcept { return static_cast<std::size_t>(i); }

/// sgn(v): 1, -1 or 0 (Coulomb friction's direction, f sgn(q')).
[[nodiscard]] constexpr double sign(double v) noexcept { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

}  // namespace nocdyn::detail
