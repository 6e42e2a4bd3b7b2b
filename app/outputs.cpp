#include "app/outputs.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "app/options.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

namespace fs = std::filesystem;

namespace {

bool sameFile(const fs::path& a, const fs::path& b) {
    std::error_code error;
    return fs::equivalent(a, b, error) && !error;
}

/// A path that names a device or another special file (/dev/null, /dev/stdout): writing it
/// twice replaces nothing.
bool special(const fs::path& path) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    return !error && fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status);
}

/// Whether two outputs name one file: the same inode when both exist, else the same path once
/// made absolute and its existing folders' links resolved.
bool sameOutput(const fs::path& a, const fs::path& b) {
    if (special(a) || special(b)) return false;
    if (sameFile(a, b)) return true;
    std::error_code ea, eb;
    const fs::path ca = fs::weakly_canonical(fs::absolute(a, ea), ea);
    const fs::path cb = fs::weakly_canonical(fs::absolute(b, eb), eb);
    return !ea && !eb && ca == cb;
}

/// The kinds of file a command writes into its output folder (tables, reports, figures, pages).
bool outputKind(const fs::path& path) {
    std::string extension = path.extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* kind : {".csv", ".json", ".md", ".png", ".svg", ".html"}) {
        if (extension == kind) return true;
    }
    return false;
}

/// Whether `path`, or a folder it is in, is the folder `dir` (by inode, through any link).
bool isInside(const fs::path& path, const fs::path& dir) {
    std::error_code error;
    if (!fs::is_directory(dir, error)) return false;
    fs::path at = fs::absolute(path, error);
    if (error) return false;
    for (;;) {
        if (sameFile(at, dir)) return true;
        if (!at.has_relative_path() || at.parent_path() == at) return false;
        at = at.parent_path();
    }
}

std::string quoted(const std::string& path) {
    std::string out = "'";
    out += io::terminalText(path);
    out += '\'';
    return out;
}

/// Why an output file cannot be written into `folder`: a file on the way, or (unless the command
/// creates the folder: `created`) a folder that does not exist; empty when it can be.
std::string folderProblem(const fs::path& folder, bool created) {
    std::error_code error;
    fs::path at = fs::absolute(folder.empty() ? fs::path(".") : folder, error);
    if (error) return {};
    // the folder itself, then each folder on its way, up to the first that exists
    for (bool first = true;; first = false) {
        const fs::file_status status = fs::status(at, error);
        if (!error && fs::exists(status)) {
            if (fs::is_directory(status)) {
                return first || created ? std::string() : "the folder " + quoted(folder.string()) + " does not exist";
            }
            return first
                       ? quoted(folder.string()) + " is a file, not a folder"
                       : quoted(at.string()) + ", on the way to the folder " + quoted(folder.string()) + ", is a file";
        }
        if (!at.has_relative_path() || at.parent_path() == at) return {};
        at = at.parent_path();
    }
}

/// Whether `path` is inside `folder` by their names (made absolute and normal): a file the
/// command writes into an output folder it creates.
bool namedInside(const fs::path& path, const fs::path& folder) {
    std::error_code ep, ef;
    const fs::path p = fs::absolute(path, ep).lexically_normal();
    const fs::path f = fs::absolute(folder, ef).lexically_normal();
    if (ep || ef) return false;
    const fs::path relative = p.lexically_relative(f);
    return !relative.empty() && *relative.begin() != "..";
}

}  // namespace

void CommandPaths::input(const std::string& option, const std::string& path) {
    if (!path.empty()) paths_.push_back({option, path, CommandPath::Role::input});
}

void CommandPaths::output(const std::string& option, const std::string& path) {
    if (!path.empty()) paths_.push_back({option, path, CommandPath::Role::output});
}

void CommandPaths::outputStem(const std::string& option, const std::string& stem,
                              std::initializer_list<const char*> suffixes) {
    if (stem.empty()) return;
    for (const char* suffix : suffixes) paths_.push_back({option, stem + suffix, CommandPath::Role::output});
}

void CommandPaths::outputFolder(const std::string& option, const std::string& path) {
    if (!path.empty()) paths_.push_back({option, path, CommandPath::Role::output_folder});
}

void refuseOutputOverInput(const std::string& command, const CommandPaths& paths) {
    using Role = CommandPath::Role;
    const std::vector<CommandPath>& all = paths.paths();
    // every output file's folder exists (or is inside an output folder, which the command creates,
    // as requireOutputFolder checks), before any work
    for (const CommandPath& out : all) {
        if (out.role != Role::output) continue;
        const bool created = std::any_of(all.begin(), all.end(), [&](const CommandPath& other) {
            return other.role == Role::output_folder && namedInside(out.path, other.path);
        });
        if (const std::string problem = folderProblem(fs::path(out.path).parent_path(), created); !problem.empty()) {
            std::string message = command;
            message += ": ";
            message += out.option;
            message += ' ';
            message += quoted(out.path);
            message += ": ";
            message += problem;
            message += " (create it first)";
            throw Error(message);
        }
    }
    for (std::size_t a = 0; a < all.size(); ++a) {
        const CommandPath& out = all[a];
        if (out.role != Role::output) continue;
        for (const CommandPath& in : all) {
            if (in.role == Role::input && sameFile(out.path, in.path)) {
                throw Error(command + ": " + out.option + " " + quoted(out.path) + " is an input file (" + in.option +
                            " " + quoted(in.path) + "): writing it would replace it");
            }
        }
        // one file named by two outputs (two options, or two stems): the later would replace the earlier
        for (std::size_t b = 0; b < a; ++b) {
            const CommandPath& other = all[b];
            if (other.role == Role::output && sameOutput(out.path, other.path)) {
                const std::string what =
                    out.option == other.option
                        ? out.option + " names " + quoted(out.path) + " twice"
                        : out.option + " " + quoted(out.path) + " is also written by " + other.option;
                std::string message = command;
                message += ": ";
                message += what;
                message += ": one output would replace the other; give each its own file";
                throw Error(message);
            }
        }
    }
    // in the output folder, a file of a kind the command writes there (a record beside it is
    // read, not replaced; a folder of inputs holding the output folder is fine)
    for (const CommandPath& in : all) {
        if (in.role != Role::input) continue;
        for (const CommandPath& folder : all) {
            if (folder.role != Role::output_folder) continue;
            std::error_code error;
            const bool a_folder = fs::is_directory(in.path, error);
            if ((a_folder && sameFile(in.path, folder.path)) ||
                (!a_folder && outputKind(in.path) && isInside(in.path, folder.path))) {
                throw Error(command + ": " + in.option + " " + quoted(in.path) + " is inside the output folder " +
                            folder.option + " " + quoted(folder.path) +
                            ", where the command writes files of its kind: choose another folder");
            }
        }
    }
}

void requireOutputFolder(const std::string& path, const std::string& field) {
    if (path.empty()) return;
    std::error_code error;
    fs::path at = fs::absolute(path, error);
    if (error) return;
    // the path itself, then each folder on its way, up to the first that exists
    for (bool first = true;; first = false) {
        const fs::file_status status = fs::status(at, error);
        if (!error && fs::exists(status)) {
            if (fs::is_directory(status)) return;
            throw OptionError(
                field, quoted(path) + " is not a folder: " +
                           (first ? std::string("it is a file") : quoted(at.string()) + " on its way is a file"));
        }
        if (!at.has_relative_path() || at.parent_path() == at) return;
        at = at.parent_path();
    }
}

void createOutputFolder(const std::string& path, const std::string& field) {
    requireOutputFolder(path, field);
    std::error_code error;
    fs::create_directories(path, error);
    if (error || !fs::is_directory(path, error)) {
        throw OptionError(
            field, "cannot create the folder " + quoted(path) + (error ? ": " + error.message() : std::string()));
    }
}

std::string inFolder(const std::string& folder, const std::string& name) {
    return folder.empty() ? name : (fs::path(folder) / name).string();
}

std::string OutputFolder::path(const std::string& name) const {
    return name.empty() ? root_ : (fs::path(root_) / name).string();
}

void OutputFolder::folder(const std::string& name) {
    const std::string dir = path(name);
    std::error_code error;
    fs::create_directories(dir, error);
    if (wording_ == Wording::folder) {
        if (error) throw Error("cannot create the folder '" + dir + "': " + error.message());
    } else if (error || !fs::is_directory(dir)) {
        throw Error("cannot create output folder '" + dir + "'");
    }
}

void OutputFolder::table(const std::string& name, const io::Table& table) { io::writeCsvFile(path(name), table); }

void OutputFolder::text(const std::string& name, const std::string& text) { io::writeTextFile(path(name), text); }

void OutputFolder::figure(const std::string& stem, const render::Figure& figure) {
    render::renderFigure(figure, path(stem));
}

}  // namespace nocdyn::app
