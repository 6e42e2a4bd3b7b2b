// The one check of a command's paths, for the command line and Python alike, before its work: every
// output can be written (its folder exists), and no output may replace one of the command's inputs
// or another of its outputs. A figure's stem stands for each file it names (STEM.png, STEM.svg; a
// frequency map's also STEM.csv).
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

namespace nocdyn::app {

/// A path given to a command, under the name of the option that gave it (as the front end spells
/// it: "--summary" on the command line, "summary" in Python).
struct CommandPath {
    enum class Role {
        input,         ///< a file (or a folder of files) the command reads
        output,        ///< a file the command writes
        output_folder  ///< a folder the command writes files into
    };
    std::string option;
    std::string path;
    Role role = Role::input;
};

/// The paths of a command being gathered: outputs given as stems add one entry per file.
class CommandPaths {
public:
    void input(const std::string& option, const std::string& path);
    void output(const std::string& option, const std::string& path);
    /// STEM + each suffix, e.g. {".png", ".svg"}.
    void outputStem(const std::string& option, const std::string& stem, std::initializer_list<const char*> suffixes);
    void outputFolder(const std::string& option, const std::string& path);
    [[nodiscard]] const std::vector<CommandPath>& paths() const { return paths_; }

private:
    std::vector<CommandPath> paths_;
};

/// Refuses (nocdyn::Error, "command: ...", naming the option and the path) a command that could not
/// write an output file once its work is done: its folder does not exist (unless it is inside an
/// output folder of the call, which the command creates) or is a file. Then refuses one whose
/// output would replace:
///  - one of its input files (the same file by inode, through any path or link);
///  - another of its outputs (the same file by inode, or the same path once resolved: two
///    options naming one file, or two stems naming one figure); a device such as /dev/null is
///    not a file that can be replaced and is never refused;
///  - inside an output folder, an input file of a kind the command writes there (.csv .json .md
///    .png .svg .html), or an input folder that is the output folder.
/// Empty paths are skipped (an option not given).
void refuseOutputOverInput(const std::string& command, const CommandPaths& paths);

/// Refuses (OptionError naming `field`) an output folder that cannot be one: the path, or a folder
/// on its way, is an existing file. Called before a command's work, so that a long run does not
/// end on a folder it cannot write.
void requireOutputFolder(const std::string& path, const std::string& field);

/// Creates the output folder (and its parents), or throws OptionError naming `field` and why.
void createOutputFolder(const std::string& path, const std::string& field);

}  // namespace nocdyn::app
