// `envelope`: per axis (theta, x, y) and log-spaced frequency, the largest amplitude of a
// sinusoid about the home posture within every limit, and which limit binds (envelope.hpp).
#pragma once

#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::app {

/// Frequencies [Hz] and their count per axis the envelope accepts.
inline constexpr Range kEnvelopeFrequencyRange{kEnvelopeMinFrequency, kEnvelopeMaxFrequency, "Hz"};
inline constexpr Range kEnvelopePointsRange{1.0, static_cast<double>(kEnvelopeMaxPoints), "points"};

struct EnvelopeOptions {
    RobotSource robot;
    double min_frequency = 1.0;    ///< [Hz] (kEnvelopeFrequencyRange)
    double max_frequency = 100.0;  ///< [Hz], at least min_frequency
    int points = 41;               ///< log-spaced frequencies per axis, both ends included
};

struct EnvelopeResult {
    std::string robot;
    /// Axis after axis (theta, x, y), frequency after frequency.
    std::vector<EnvelopePoint> points;
    /// The points as the CSV's table (io::TableId::envelope): axis and limit as words, limb,
    /// joint and actuator numbered from 1 (0: not applicable).
    io::Table table;
};

/// Throws OptionError for a frequency or count out of range, or max below min.
void validate(const EnvelopeOptions& options);

/// The envelope; progress in points (3 * options.points), a stop between points.
[[nodiscard]] EnvelopeResult runEnvelope(const EnvelopeOptions& options, Observer& observer);

/// The figure (amplitude versus frequency, log axes): STEM.png and STEM.svg.
void writeEnvelopeFigure(const EnvelopeResult& result, const std::string& stem);

}  // namespace nocdyn::app
