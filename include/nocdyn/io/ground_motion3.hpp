// Three-component ground-motion records: two horizontal components and a vertical one, each an
// AT2 file (at2.hpp) whose second header line ends in the component's orientation, as PEER's
// NGA-West2 files write it:
//
//   Imperial Valley-02, 5/19/1940, El Centro Array #9, 180     a horizontal, azimuth 180 degrees
//   Northridge-05, 1/18/1994, Sylmar - County Hospital Grounds, UP     the vertical, positive up
//
// An azimuth is in degrees clockwise from north seen from above (0 to 360, "90" or "090"); a
// vertical is UP, or DWN (DOWN) when positive downwards (its sign is reversed).
//
// The horizontals are rotated into the table's axes: x at the azimuth beta_x, y 90 degrees
// counter-clockwise from x seen from above (at azimuth beta_x - 90), z up, a right-handed frame.
// With a_1, a_2 the horizontals at azimuths alpha_1, alpha_2 (orthogonal):
//   a_x = a_1 cos(alpha_1 - beta_x) + a_2 cos(alpha_2 - beta_x),
//   a_y = a_1 sin(beta_x - alpha_1) + a_2 sin(beta_x - alpha_2).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nocdyn/io/at2.hpp"

namespace nocdyn::io {

/// The direction of one component, from its AT2 header.
struct ComponentDirection {
    bool vertical = false;
    double azimuth = 0.0;  ///< a horizontal's, as written [deg] (0 to 360)
    double sign = 1.0;     ///< a vertical's: +1 (UP) or -1 (DWN: positive downwards)
};

/// The orientation that ends the second header line (after its last comma, blanks and an older
/// file's station note in parentheses ignored): an azimuth 0 to 360 of at most three digits,
/// UP, DWN or DOWN (any case). std::nullopt for anything else.
[[nodiscard]] std::optional<ComponentDirection> componentDirection(std::string_view event_line);

/// A record's components on the table's axes, uniformly sampled from t = 0.
struct TableMotion {
    std::string name;                  ///< the components' shared name (componentGroup)
    std::vector<std::string> sources;  ///< the files: the first horizontal, the second, the vertical
    double dt = 0.0;                   ///< [s]
    double x_azimuth = 0.0;            ///< the table's x [deg]
    bool has_vertical = false;         ///< a vertical component was given (else az is zero)
    std::vector<double> ax, ay, az;    ///< [m/s^2], equal lengths
    /// What was done beyond reading (components padded with zeros), one sentence each.
    std::vector<std::string> notes;

    /// Duration (n - 1) dt [s].
    [[nodiscard]] double duration() const;
};

/// The table motion of two horizontal components and at most one vertical, given in any order.
/// The first horizontal is the one of smaller azimuth as written (180 before 270, 090 before
/// 360); x_azimuth [deg] defaults to it. Components of unequal length are aligned at their start
/// and the shorter ones padded with zeros to the longest (said in notes). Throws nocdyn::Error
/// naming the file for a component without an orientation, two verticals, not exactly two
/// horizontals, horizontals that are not orthogonal, or unequal time steps.
[[nodiscard]] TableMotion combineComponents(const std::vector<GroundMotionRecord>& components,
                                            std::optional<double> x_azimuth = std::nullopt);

/// The name a record's component files share: the file's stem without its component suffix
/// (a trailing -hor1, -hor2, -ver, then an orientation: 180, 090, UP, DWN, with the - or _
/// before it). RSN6_IMPVALL.I_I-ELC180-hor1.AT2 and RSN6_IMPVALL.I_I-ELC-UP.AT2 give
/// RSN6_IMPVALL.I_I-ELC.
[[nodiscard]] std::string componentGroup(const std::string& path);

/// The files grouped by componentGroup, groups and files sorted by name.
[[nodiscard]] std::vector<std::pair<std::string, std::vector<std::string>>> groupComponents(
    const std::vector<std::string>& paths);

}  // namespace nocdyn::io
