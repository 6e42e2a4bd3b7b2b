// What several sub-commands share: loading the robot and trajectory named on the command
// line, choosing the sampling, writing a table to a file or stdout.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json_fwd.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "app/options.hpp"
#include "app/outputs.hpp"
#include "app/table.hpp"
#include "nocdyn/choice.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/description.hpp"
#include "nocdyn/sim/plant.hpp"
#include "nocdyn/trajectory.hpp"
#include "render/plot.hpp"

namespace nocdyn::cli {

/// The commands draw figures and pages with the rendering module's functions.
using namespace nocdyn::render;

/// A CLI11 check: the argument is a finite decimal number in [lo, hi] (unit named in the
/// message, e.g. "Hz"); nan, inf and hex are refused. Any failure exits with status 2.
[[nodiscard]] CLI::Validator finiteIn(double lo, double hi, const std::string& unit);

/// finiteIn over an option's range as the application layer states it.
[[nodiscard]] inline CLI::Validator within(const app::Range& range) { return finiteIn(range.lo, range.hi, range.unit); }

/// A CLI11 check: the argument is a finite decimal number; nan, inf and hex are refused.
[[nodiscard]] CLI::Validator finiteNumber();

/// The one rule for floating options: every FLOAT option of every command of `app` refuses
/// nan, inf and hexadecimal (no option gives them a meaning).
void requireFiniteFloats(CLI::App& app);

/// The paths a command was given, each under its option: inputs (--robot, --trajectory,
/// --record, ...), output files (-o, --log, --png, --svg, --summary), stems (--figure: STEM.png
/// and STEM.svg; --frequency-map: also STEM.csv) and the output folder (--out-dir).
[[nodiscard]] app::CommandPaths commandPaths(const CLI::App& command);

/// app::refuseOutputOverInput over commandPaths: no output over an input or over another output
/// of the call. Called for every command once parsed.
void refuseOutputOverInput(const CLI::App& command);

/// Adds --quiet (-q) to a command: the one definition every command shares (progress.hpp's quiet()
/// reads it): nothing on standard error but errors and warnings, the results unchanged.
void addQuietOption(CLI::App& command);

/// A CLI11 check for a file name given on the command line: an empty one is refused (it would
/// otherwise mean standard output, the default when the option is absent).
[[nodiscard]] CLI::Validator nonEmptyPath();

/// Adds --robot and --set NAME=VALUE (any number of times) to a command, into its options'
/// RobotSource (path and overrides: nothing process-wide).
void addRobotOption(CLI::App& command, app::RobotSource& robot);

/// Adds --trajectory (required), --duration and --rate into the options' SamplingOptions.
void addSamplingOptions(CLI::App& command, app::SamplingOptions& sampling);

/// The output named by --output: a file written safely (io::OutputFile), or stdout when empty.
[[nodiscard]] io::OutputFile openOutput(const std::string& path);

/// A command's table row by row into CSV (io::CsvWriter formatting on a second thread while the
/// command computes): a file renamed into place only when committed, so an error leaves no
/// partial file, or stdout (the rows before an error).
class CsvSink final : public app::TableSink {
public:
    explicit CsvSink(io::OutputFile& out) : out_(out) {}
    void columns(const std::vector<std::string>& names) override {
        csv_ = std::make_unique<io::CsvWriter>(out_, names, /*background=*/true);
    }
    void row(std::span<const double> values) override { csv_->row(values); }
    void finish() {
        if (csv_) csv_->finish();
    }

private:
    io::OutputFile& out_;
    std::unique_ptr<io::CsvWriter> csv_;
};

/// Writes the table to `path`, or to stdout when the path is empty.
void writeTable(const io::Table& table, const std::string& path);

/// Prints text on stdout and flushes it; a failed write (a closed pipe, a full disk) is an Error.
void printText(std::string_view text);

/// Writes text to `path` (a unique temporary file, then renamed), or prints it when the path is
/// empty.
void writeText(const std::string& text, const std::string& path);

/// Adds an option choosing a value of the enum E by its name (nocdyn/choice.hpp): the words
/// accepted and the default shown are E's name table.
template <class E>
CLI::Option* addChoiceOption(CLI::App& command, const std::string& name, E& value, const std::string& help) {
    return command
        .add_option_function<std::string>(
            name, [&value](const std::string& word) { value = *choiceNamed<E>(word); }, help)
        ->check(CLI::IsMember(choiceNames<E>()))
        ->default_str(std::string(nameOf(value)));
}

/// The deprecation warning of addOldSpelling (also when --quiet: it is a warning).
void warnOldSpelling(const std::string& old_name, const std::string& new_name);

/// Adds `old_name`, the old spelling of the option `current` (one concept, one name across the
/// commands), accepted until the next release: hidden from --help, it sets the same variable
/// under the checks `current` has when this is called (so call it after them), warns
/// "nocdyn: warning: --f-min is deprecated: use --min-frequency" on standard error, and is refused
/// together with `current`. Its errors name it themselves (CLI11 gives a hidden option no name in
/// its own messages).
template <class T>
CLI::Option* addOldSpelling(CLI::App& command, const std::string& old_name, CLI::Option* current, T& variable) {
    const std::string new_name = "--" + current->get_lnames().front();
    // CLI11 2.1 lists an option's validators by index, in the order it runs them, and throws
    // past the last one
    std::vector<CLI::Validator> checks;
    for (int i = 0; i < 64; ++i) {
        try {
            checks.push_back(*current->get_validator(i));
        } catch (const CLI::OptionNotFound&) {
            break;
        }
    }
    return command.add_option(old_name, variable, "old spelling of " + new_name)
        ->group("")
        ->each([old_name, new_name, current, checks](const std::string& value) {
            if (current->count() > 0) throw CLI::ExcludesError(old_name, new_name);
            std::string word = value;
            for (const CLI::Validator& check : checks) {
                if (const std::string error = check(word); !error.empty()) {
                    throw CLI::ConversionError(old_name + ": " + error);
                }
            }
            warnOldSpelling(old_name, new_name);
        });
}

/// Adds --plant (PlantKind): every command that chooses a plant offers all three with this one
/// definition.
CLI::Option* addPlantOption(CLI::App& command, PlantKind& plant);

/// An application-layer message as the command line spells its options: `noise_pose` (an option
/// the message names) and a bare noise_pose that is an option of `command` (any snake_case word
/// when no command is given) become --noise-pose.
[[nodiscard]] std::string commandLineText(const std::string& message, const CLI::App* command = nullptr);

/// An application-layer option error as the command line spells its options: "--noise-u: ...
/// use --noise-pose and --noise-rate" for the field noise_u naming noise_pose and noise_rate.
[[nodiscard]] std::string commandLineMessage(const app::OptionError& e, const CLI::App* command = nullptr);

/// A matrix as JSON, an array of its rows (the reports' --json).
[[nodiscard]] nlohmann::json matrixJson(const Eigen::Ref<const Eigen::MatrixXd>& m);

/// A matrix as text, one "  [a  b  c]" line per row, each entry %.9e (the reports' text).
[[nodiscard]] std::string matrixText(const Eigen::Ref<const Eigen::MatrixXd>& m);

}  // namespace nocdyn::cli
