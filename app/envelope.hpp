// `envelope`: per axis (x, y, theta) and log-spaced frequency, the largest amplitude of a
// sinusoid about the home posture within every limit, and which limit binds; the band's third
// bound, the first natural frequency at home, when the robot file declares compliance
// (envelope.hpp).
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
/// Samples of each period the limits are checked on, and the bisection's relative tolerance.
inline constexpr Range kSamplesPerPeriodRange{8.0, 65536.0, "samples"};
inline constexpr Range kEnvelopeToleranceRange{1e-15, 0.5, ""};

struct EnvelopeOptions {
    RobotSource robot;
    double min_frequency = 1.0;    ///< [Hz] (kEnvelopeFrequencyRange)
    double max_frequency = 100.0;  ///< [Hz], at least min_frequency
    int points = 41;               ///< log-spaced frequencies per axis, both ends included
    int samples_per_period = 256;  ///< samples of each period checked (kSamplesPerPeriodRange)
    /// The amplitude's bisection stops at (hi - lo) <= tolerance * hi (kEnvelopeToleranceRange).
    double relative_tolerance = 1e-6;
    /// The band's third bound: the largest dynamic amplification of an axis accepted
    /// (kAmplificationRange; envelope.hpp).
    double amplification = kDefaultAmplification;
};

inline constexpr Range kAmplificationRange{kMinAmplification, kMaxAmplification, ""};

struct EnvelopeResult {
    std::string robot;
    /// Axis after axis (x, y, theta), frequency after frequency.
    std::vector<EnvelopePoint> points;
    /// The band's third bound: the first natural frequency of the lumped model at home, or why
    /// it is unknown.
    EnvelopeResonance resonance;
    /// The points as the CSV's table (io::TableId::envelope): axis and limit as words, limb,
    /// joint and actuator numbered from 1 (0: not applicable); first_natural_frequency [Hz] when
    /// the resonance is known.
    io::Table table;
    /// One line: the third bound with its unit, or why it is unknown.
    std::string summary;
};

/// Throws OptionError for a frequency or count out of range, or max below min.
void validate(const EnvelopeOptions& options);

/// The envelope; progress in points (3 * options.points), a stop between points.
[[nodiscard]] EnvelopeResult runEnvelope(const EnvelopeOptions& options, Observer& observer);

/// The summary line of a resonance.
[[nodiscard]] std::string resonanceSummary(const EnvelopeResonance& resonance);

/// The figure (amplitude versus frequency, log axes; the first natural frequency as a vertical
/// line when known): STEM.png and STEM.svg.
void writeEnvelopeFigure(const EnvelopeResult& result, const std::string& stem);

}  // namespace nocdyn::app
