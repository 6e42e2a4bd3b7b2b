// The one check of a command's paths, for the command line and Python alike, before its work: every
// output can be written (its folder exists), and no output may replace one of the command's inputs
// or another of its outputs. A figure's stem stands for each file it names (STEM.png, STEM.svg; a
// frequency map's also STEM.csv).
//
// And the one place that writes a job's files: a job (app/*.cpp) computes and returns typed
// results and never touches the filesystem; what it must hand over while it runs (a long
// sweep's journal, each finished record of a suite) goes through a sink (FileSink here,
// DesignSink in app/design.hpp), whose writing implementation lives in the output files
// (app/outputs*.cpp, app/*_outputs.cpp) like the writers the front ends call once a job has
// returned. Only those files write (tests/check_outputs.cmake keeps it so).
#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "nocdyn/io/csv.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

struct EnvelopeResult;
struct LoadsOptions;
struct LoadsResult;
struct WorkspaceResult;

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

/// Receives a job's files as it makes them, each named relative to one output folder
/// ("shake.csv", "elcentro/shake.json", a figure's stem "identification/forces").
class FileSink {
public:
    FileSink() = default;
    FileSink(const FileSink&) = default;
    FileSink& operator=(const FileSink&) = default;
    FileSink(FileSink&&) = default;
    FileSink& operator=(FileSink&&) = default;
    virtual ~FileSink() = default;
    /// Makes the folder `name` ready for files ("": the output folder itself).
    virtual void folder(const std::string& name) = 0;
    /// A CSV table.
    virtual void table(const std::string& name, const io::Table& table) = 0;
    /// A text file (JSON, Markdown, an HTML page) as it is.
    virtual void text(const std::string& name, const std::string& text) = 0;
    /// A figure: STEM.png and STEM.svg.
    virtual void figure(const std::string& stem, const render::Figure& figure) = 0;
};

/// The files in a folder on disk (each written to a temporary file and renamed).
class OutputFolder final : public FileSink {
public:
    /// How folder() words a folder it cannot create: "cannot create the folder 'DIR': why" (the
    /// replays' records), or "cannot create output folder 'DIR'" (reproduce's).
    enum class Wording { folder, output_folder };
    explicit OutputFolder(std::string root, Wording wording = Wording::folder)
        : root_(std::move(root)), wording_(wording) {}
    void folder(const std::string& name) override;
    void table(const std::string& name, const io::Table& table) override;
    void text(const std::string& name, const std::string& text) override;
    void figure(const std::string& stem, const render::Figure& figure) override;
    /// The path of `name` in the folder (the folder itself for "").
    [[nodiscard]] std::string path(const std::string& name) const;

private:
    std::string root_;
    Wording wording_;
};

/// `folder`/`name`, or `name` alone in the output folder itself (folder "").
[[nodiscard]] std::string inFolder(const std::string& folder, const std::string& name);

/// The figures of the analysis commands, once they have returned: STEM.png and STEM.svg
/// (app/outputs_figures.cpp). An envelope's amplitude over frequency (envelopeResultFigure).
void writeEnvelopeFigure(const EnvelopeResult& result, const std::string& stem);
/// The robot at the pose of the largest peak force (loadsResultFigure; planar robots only).
void writeLoadsFigure(const LoadsOptions& options, const LoadsResult& result, const std::string& stem);
/// The workspace map (workspaceResultFigure).
void writeWorkspaceFigure(const WorkspaceResult& result, const std::string& stem);
/// The first natural frequency over the map (frequencyResultFigure; nocdyn::Error without one).
void writeFrequencyFigure(const WorkspaceResult& result, const std::string& stem);

}  // namespace nocdyn::app
