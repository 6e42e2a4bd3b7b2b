// The operating envelope (analysis/envelope.hpp) as a figure: amplitude versus frequency.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/analysis/spatial_envelope.hpp"
#include "render/plot.hpp"

namespace nocdyn::render {

/// Amplitude versus frequency, log axes: one panel for x and y [mm], one for theta [deg]. With a
/// known resonance, each panel draws the first natural frequency as a vertical line (the band's
/// third bound) and shades the frequencies above it up to the last point.
[[nodiscard]] Figure envelopeFigure(const std::vector<EnvelopePoint>& points, const std::string& robot,
                                    const std::string& reading = "flat = stroke-bound, slope -2 = peak-force-bound",
                                    const EnvelopeResonance& resonance = {});

/// A spatial robot's envelope: one panel for x, y, z [mm], one for roll, pitch, yaw [deg] (motion
/// full), one curve per axis, log axes, each point's binding limit as a marker (range, velocity,
/// effort, workspace). `coordinates` names the pose coordinates (spatial::Model::coordinates).
[[nodiscard]] Figure spatialEnvelopeFigure(const std::vector<spatial::EnvelopePoint>& points,
                                           const std::vector<std::string>& coordinates, const std::string& robot);

}  // namespace nocdyn::render
