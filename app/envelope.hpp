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
#include "nocdyn/analysis/spatial_envelope.hpp"
#include "nocdyn/io/csv.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

/// Frequencies [Hz] and their count per axis the envelope accepts.
inline constexpr Range kEnvelopeFrequencyRange{kEnvelopeMinFrequency, kEnvelopeMaxFrequency, "Hz"};
inline constexpr Range kEnvelopePointsRange{1.0, static_cast<double>(kEnvelopeMaxPoints), "points"};
/// Samples of each period the limits are checked on, and the bisection's relative tolerance.
inline constexpr Range kSamplesPerPeriodRange{8.0, 65536.0, "samples"};
inline constexpr Range kEnvelopeToleranceRange{1e-15, 0.5, ""};

/// The search's own options (analysis/envelope.hpp: min_frequency and max_frequency in
/// kEnvelopeFrequencyRange, points per axis, samples_per_period in kSamplesPerPeriodRange, the
/// bisection's relative_tolerance in kEnvelopeToleranceRange, the third bound's amplification in
/// kAmplificationRange), with the robot. Progress and polling are the job's own (the observer).
struct EnvelopeOptions : nocdyn::EnvelopeOptions {
    RobotSource robot;
};

inline constexpr Range kAmplificationRange{kMinAmplification, kMaxAmplification, ""};

struct EnvelopeResult {
    std::string robot;
    /// Axis after axis (x, y, theta), frequency after frequency (a planar robot).
    std::vector<EnvelopePoint> points;
    /// A spatial robot's points (points is then empty), axis after axis (x, y, z, and roll,
    /// pitch, yaw for motion full), frequency after frequency, and its pose coordinates' names.
    std::vector<spatial::EnvelopePoint> spatial_points;
    std::vector<std::string> coordinates;
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

/// The library's envelope options: the job's, with progress in points and a stop between points
/// through `observer`, which must outlive them.
[[nodiscard]] nocdyn::EnvelopeOptions libraryEnvelopeOptions(const EnvelopeOptions& options, Observer& observer);

/// The envelope; progress in points (3 * options.points), a stop between points.
[[nodiscard]] EnvelopeResult runEnvelope(const EnvelopeOptions& options, Observer& observer);

/// The envelope of a spatial robot file (options.robot; spatial_envelope.hpp): its table has
/// the planar columns (axis x, y, z, roll, pitch or yaw; peak_effort_ratio, peak_u, peak_tau at
/// the amplitude), the resonance is unknown (a spatial robot file declares no compliance).
/// Throws OptionError("amplification") for an amplification other than the default.
[[nodiscard]] EnvelopeResult runSpatialEnvelope(const EnvelopeOptions& options, Observer& observer);

/// A spatial envelope as text: one line per point (axis, f [Hz], amplitude [mm or deg], the
/// limit, its actuator or limb and joint, the peak effort ratio).
[[nodiscard]] std::string spatialEnvelopeText(const EnvelopeResult& result);

/// The summary line of a resonance.
[[nodiscard]] std::string resonanceSummary(const EnvelopeResonance& resonance);

/// The figure (amplitude versus frequency, log axes; the first natural frequency as a vertical
/// line when known; a spatial robot's binding limits as markers), written by
/// writeEnvelopeFigure (app/outputs.hpp).
[[nodiscard]] render::Figure envelopeResultFigure(const EnvelopeResult& result);

}  // namespace nocdyn::app
