// Families of robots for design sweeps (design.hpp): a parametric robot file with some
// parameters varied, each design the robot file that parameter set means; the designs table
// (designs.csv) and the journal that lets a stopped sweep resume without losing a design.
//
// Table columns: design (its number in the sweep, from 1; DesignRecord::index is 0-based), one
// per varied parameter (its name), one per metric (its name, SI units), feasible (true/false),
// reason (empty when feasible).
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "nocdyn/analysis/design.hpp"
#include "nocdyn/io/robot_file.hpp"

namespace nocdyn::tables {

/// A parametric robot file and which of its parameters a sweep varies.
struct DesignFamily {
    std::string text;                 ///< the robot file's YAML text
    std::string source;               ///< its name in messages
    io::ParameterSet fixed;           ///< parameters set for every design (--set)
    std::vector<DesignRange> ranges;  ///< the varied parameters, each declared by the file
};

/// Checks that the file parses and declares every varied and fixed parameter; throws
/// nocdyn::Error naming the first that it does not.
void checkDesignFamily(const DesignFamily& family);

/// The robot of one design: the family's file with `point` (one value per range) and the
/// fixed parameters set. Throws nocdyn::Error as io::parseRobotDescription.
[[nodiscard]] RobotDescription designRobot(const DesignFamily& family, const std::vector<double>& point);

/// evaluateDesign on designRobot; a parameter set the robot file refuses (a negative mass, a
/// limb that does not close) is an infeasible design with that reason.
[[nodiscard]] DesignEvaluation evaluateFamilyDesign(const DesignFamily& family, const std::vector<double>& point,
                                                    const std::vector<DesignMetric>& metrics,
                                                    const DesignOptions& options);

/// One evaluated design.
struct DesignRecord {
    std::size_t index = 0;
    std::vector<double> point;
    DesignEvaluation evaluation;
};

/// The table's column names.
[[nodiscard]] std::vector<std::string> designColumns(const std::vector<DesignRange>& ranges,
                                                     const std::vector<DesignMetric>& metrics);

/// One table row, newline-terminated; numbers in shortest round-trip form (empty for NaN).
[[nodiscard]] std::string designCsvRow(const DesignRecord& record);

/// Writes the table (records in the order given) through a temporary file renamed into place.
void writeDesignTable(const std::string& path, const std::vector<std::string>& columns,
                      const std::vector<DesignRecord>& records);

/// A 64-bit FNV-1a hash of `text`, as 16 hex digits (stable across runs and platforms).
[[nodiscard]] std::string fingerprint(const std::string& text);

/// The journal of a sweep: every evaluated design as one line, appended and flushed as it is
/// evaluated. Opening it reads the designs a previous run of the same sweep (`signature`)
/// recorded, drops an unfinished last line, and continues after them; a journal of another
/// sweep is an error naming the file.
class DesignJournal {
public:
    DesignJournal(const std::string& path, const std::string& signature, const std::vector<std::string>& columns,
                  std::size_t parameters, std::size_t metrics);
    /// The designs recorded before this run, in journal order.
    [[nodiscard]] const std::vector<DesignRecord>& previous() const { return previous_; }
    /// Records one design (written and flushed before returning).
    void append(const DesignRecord& record);

private:
    std::string path_;
    std::vector<DesignRecord> previous_;
    std::ofstream out_;
};

}  // namespace nocdyn::tables
