// What a replay (nocdyn/sim/shake_replay.hpp) writes and prints: shake.csv's table, shake.json,
// the figures and the summary, for `shake` and the El Centro section of `reproduce`; the files
// go through a FileSink (app/outputs.hpp).
#pragma once

#include <iosfwd>
#include <span>
#include <string>

#include "app/outputs.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/shake_replay.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

/// A figure's panel `name` [unit]: the target and the achieved acceleration against t, the
/// achieved labelled with the plant's name.
[[nodiscard]] render::PlotPanel accelerationPanel(const std::string& name, const char* unit, std::span<const double> t,
                                                  std::span<const double> target, std::span<const double> achieved,
                                                  const std::string& plant);

/// A figure's panel `name` [unit]: the 5 %-damped pseudo-acceleration spectra of the target
/// (with its +-10 % band) and of the achieved motion, on a log period axis.
[[nodiscard]] render::PlotPanel spectrumPanel(const std::string& name, const char* unit, const ShakeScore& s);

/// shake.csv's table: the record's (scaled) samples (io::TableId::shake), u and tau at the tick
/// nearest each.
[[nodiscard]] io::Table shakeTable(const ShakeOutcome& outcome, const Model& model);

/// shake.json's text: scales, limit use, and per driven axis the scores, every error in percent
/// with "_percent" in its name (rms_error_percent: 100 sqrt(sum e^2 / sum a^2);
/// spectrum_outside_band_percent: of the counted periods, those outside +-10 %), and the spectra.
[[nodiscard]] std::string shakeJson(const ShakeOutcome& outcome);

/// A replay's files, handed to `files` in `folder` ("": the output folder itself): shake.csv,
/// shake.json, shake_acceleration.{png,svg}, shake_spectrum.{png,svg}.
void shakeFiles(const ShakeOutcome& outcome, const Model& model, const std::string& folder, const std::string& title,
                FileSink& files);

/// The scales, the limit use, the closed loop, then one line per driven axis: RMS error, peak
/// error, share outside the band. with_timing: also the closed loop's wall-clock time (which
/// differs from run to run, so it is left out of files meant to be reproducible).
void printShakeSummary(const ShakeOutcome& outcome, std::ostream& out, bool with_timing = true);

}  // namespace nocdyn::app
