// `reproduce`: the paper's results for its prototype and the project's checks on them, written
// into one folder with a summary.md: both paper trajectories (CSV, figures like Figs. 5 and 6,
// with the engines' curves when built in), animations, the forward-dynamics round trip,
// closed-loop control, the envelope, the workspace, the El Centro replay, the example robots
// against Simbody and MuJoCo, and the payload identification experiment (reproduce_sections.hpp).
#pragma once

#include <filesystem>
#include <string>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "app/outputs.hpp"

namespace nocdyn::app {

inline constexpr Range kClosedLoopDurationRange{1e-3, 10.0, "s"};
inline constexpr Range kIdentificationDurationRange{0.01, 60.0, "s"};

struct ReproduceOptions {
    std::string out_dir = "results";       ///< output folder (created if missing)
    double closed_loop_duration = 0.2;     ///< [s] of each closed-loop run (kClosedLoopDurationRange)
    double identification_duration = 5.0;  ///< [s] of data per identification experiment
};

struct ReproduceResult {
    std::filesystem::path folder;   ///< where the files are
    std::filesystem::path summary;  ///< folder / summary.md
    int sections = 0;               ///< sections run
};

/// Throws OptionError for a duration outside its range or an empty folder name.
void validate(const ReproduceOptions& options);

/// Runs every section, each announced to the observer as a step (and a stop between them), each
/// handing its files to `files` as it makes them (the front ends pass an OutputFolder of
/// options.out_dir with OutputFolder::Wording::output_folder: app/outputs.hpp).
[[nodiscard]] ReproduceResult runReproduce(const ReproduceOptions& options, Observer& observer, FileSink& files);

}  // namespace nocdyn::app
