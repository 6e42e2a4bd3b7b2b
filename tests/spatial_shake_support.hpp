// El Centro 1940 (Array #9), its three components in data/records3/, on a six-DOF table's x, y,
// z: the record the hexapod's shake tests play.
#pragma once

#include <string>

#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/ground_motion3.hpp"
#include "nocdyn/sim/spatial_shake.hpp"

namespace nocdyn::test {

/// A component's file: `name` is its suffix (180-hor1.AT2, 270-hor2.AT2, -UP.AT2).
inline std::string elCentroComponent(const std::string& name) {
    return std::string(NOCDYN_SOURCE_DIR) + "/data/records3/RSN6_IMPVALL.I_I-ELC" + name;
}

/// The three components on the table's x, y, z: their first `seconds`.
inline spatial::GroundRecord3 elCentro3(double seconds) {
    const io::TableMotion m = io::combineComponents({io::readAt2File(elCentroComponent("180-hor1.AT2")),
                                                     io::readAt2File(elCentroComponent("270-hor2.AT2")),
                                                     io::readAt2File(elCentroComponent("-UP.AT2"))});
    spatial::GroundRecord3 r;
    r.dt = m.dt;
    r.a = {m.ax, m.ay, m.az};
    for (auto& a : r.a) a.resize(static_cast<std::size_t>(seconds / m.dt) + 1);
    return r;
}

}  // namespace nocdyn::test
