// The operating envelope (analysis/envelope.hpp) as a figure: amplitude versus frequency.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/analysis/envelope.hpp"
#include "render/plot.hpp"

namespace nocdyn::render {

/// Amplitude versus frequency, log axes: one panel for x and y [mm], one for theta [deg]. With a
/// known resonance, each panel draws the first natural frequency as a vertical line (the band's
/// third bound) and shades the frequencies above it up to the last point.
[[nodiscard]] Figure envelopeFigure(const std::vector<EnvelopePoint>& points, const std::string& robot,
                                    const std::string& reading = "flat = stroke-bound, slope -2 = peak-force-bound",
                                    const EnvelopeResonance& resonance = {});

}  // namespace nocdyn::render
