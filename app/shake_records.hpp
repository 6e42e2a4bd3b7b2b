// `shake`'s records: single-component AT2 files, and the components of three-component records
// (two horizontals and a vertical, each file's orientation in its header) read onto the table.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "nocdyn/sim/shake.hpp"

namespace nocdyn::app {

/// One record to replay: one component file, or the components of one record.
struct RecordFiles {
    std::string label;               ///< the file, or the components' shared name (io::componentGroup)
    std::vector<std::string> files;  ///< one file, or two or three components
};

/// The records named: files, and the *.AT2 files of folders (sorted by name). Throws
/// OptionError("record") for a folder that cannot be listed or holds no .AT2 file.
[[nodiscard]] std::vector<std::string> expandRecords(const std::vector<std::string>& names);

/// One folder name per record, safe and unique: the record's stem (a file's; the components'
/// shared name) with every character but letters, digits, '-' and '_' replaced by '_', "record"
/// when nothing is left, "-2", "-3", ... after a name already taken ignoring case.
[[nodiscard]] std::vector<std::string> recordFolders(const std::vector<RecordFiles>& records);

/// The files as records, in the order given: files that share a name (io::componentGroup), two
/// or three of them, each with its orientation at the end of its second header line, are the
/// components of one record; every other file is a record of its own.
[[nodiscard]] std::vector<RecordFiles> groupRecordFiles(const std::vector<std::string>& files);

/// A record of several components on a planar table: its horizontals rotated onto x and y (the
/// table's x at x_azimuth, by default the first horizontal's, io::combineComponents), its first `window`
/// seconds (all when 0). What was done beyond reading (padding; the vertical, which a planar
/// table does not move along, left out) is appended to `notes`. Throws nocdyn::Error naming the
/// file or the record.
[[nodiscard]] GroundRecord readComponents(const RecordFiles& record, double window, std::vector<std::string>& notes,
                                          std::optional<double> x_azimuth = std::nullopt);

}  // namespace nocdyn::app
