// `design`: a sweep over a family of robots (a parametric robot file with some of its parameters
// varied), every design's metrics (design.hpp) on a pool of threads, the Pareto front, and
// handed to a DesignSink (written by app/design_outputs.hpp into an output folder) the tables,
// the figures and a journal from which a stopped sweep resumes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/tables/design.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

inline constexpr Range kDesignThetaRange{-1e3, 1e3, "rad"};
inline constexpr Range kDesignResolutionRange{11.0, 2001.0, "points"};
inline constexpr Range kDesignThreadsRange{0.0, 256.0, "threads"};

struct DesignOptions {
    /// A parametric robot file (required); `set` fixes parameters for every design.
    RobotSource robot;
    std::vector<std::string> vary;    ///< NAME=LOWER:UPPER, a declared parameter and its range
    std::vector<std::string> metric;  ///< metric names (design.hpp); the first ranks "best"
    /// designs.csv, pareto.csv, the figures and journal.csv (a stopped sweep resumes from it);
    /// empty: nothing is written and nothing resumed.
    std::string out_dir;
    SweepKind sweep = SweepKind::random;  ///< grid or random
    std::size_t samples = 64;             ///< designs (grid: round(N^(1/d)) values per parameter)
    std::uint64_t seed = 1;               ///< of the random sweep
    int threads = 0;                      ///< worker threads; 0: every core
    std::optional<double> theta;          ///< workspace orientation [rad]; empty: each design's home
    int resolution = 201;                 ///< workspace grid points per side
    /// The trajectory of the force metrics (peak_force, rms_force, stroke, peak_reaction).
    std::string trajectory;
    std::optional<double> duration;  ///< [s]; empty: the trajectory's own, else 0.2
    double rate = 10000.0;           ///< [Hz]
    bool no_figures = false;         ///< with out_dir: write no figures
};

struct DesignResult {
    std::vector<std::string> names;    ///< the varied parameters
    std::vector<std::string> metrics;  ///< the metrics' names
    std::vector<std::string> columns;  ///< designs.csv's
    /// Every design in sweep order (index 0-based as in designs.csv).
    std::vector<tables::DesignRecord> records;
    std::vector<std::size_t> front;  ///< indices into records of the Pareto front
    std::size_t feasible = 0;
    std::size_t resumed = 0;  ///< designs read back from the journal
    /// The best feasible design by the first metric (index into records), and it in words:
    /// "design 30 (a = 0.1, b = 0.2): metric = 5.3" ("" when no design is feasible).
    std::optional<std::size_t> best;
    std::string best_text;
};

/// Receives a sweep's files as it runs: the journal, read back before the first design and
/// appended to design by design (so that a stopped sweep resumes), then the tables and the
/// figures. The front ends pass a DesignFolder of out_dir (app/design_outputs.hpp).
class DesignSink {
public:
    DesignSink() = default;
    DesignSink(const DesignSink&) = default;
    DesignSink& operator=(const DesignSink&) = default;
    DesignSink(DesignSink&&) = default;
    DesignSink& operator=(DesignSink&&) = default;
    virtual ~DesignSink() = default;
    /// Before the first design: opens the journal of the sweep `signature` (every input and
    /// option that changes a design's numbers: another sweep's journal is refused) with
    /// designs.csv's columns, and returns the designs it already holds.
    virtual std::vector<tables::DesignRecord> open(const std::string& signature,
                                                   const std::vector<std::string>& columns, std::size_t parameters,
                                                   std::size_t metrics) = 0;
    /// Where the journal is, as the warning of a resumed sweep names it.
    [[nodiscard]] virtual std::string journal() const = 0;
    /// One design evaluated, recorded before the next is.
    virtual void append(const tables::DesignRecord& record) = 0;
    /// A table of designs: designs.csv (every one), pareto.csv (the front).
    virtual void designs(const std::string& name, const std::vector<std::string>& columns,
                         const std::vector<tables::DesignRecord>& records) = 0;
    /// A figure: STEM.png and STEM.svg.
    virtual void figure(const std::string& stem, const render::Figure& figure) = 0;
};

/// Throws OptionError naming the field for a bad range, metric, sweep or number.
void validate(const DesignOptions& options);

/// The sweep. Worker threads evaluate designs; this thread records each (the journal, handed
/// to `files` when options.out_dir is given, as the tables and figures are), reports progress
/// in designs and polls the observer at least every 0.1 s: a stop (or an exception from the
/// observer) lets the designs under way finish, keeps the journal, and throws.
[[nodiscard]] DesignResult runDesign(const DesignOptions& options, Observer& observer, DesignSink& files);

}  // namespace nocdyn::app
