#include "common.hpp"

#include "progress.hpp"

#include <nlohmann/json.hpp>
#include <unistd.h>
#include <cstdio>
#include <algorithm>
#include <chrono>
#include <charconv>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <regex>
#include <iostream>
#include <sstream>
#include <string_view>
#include <utility>

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/examples.hpp"

namespace nocdyn::cli {

CLI::Validator nonEmptyPath() {
    return CLI::Validator(
        [](std::string& input) -> std::string {
            return input.empty() ? std::string("an empty file name (leave the option out for standard output)")
                                 : std::string();
        },
        "PATH", "non-empty path");
}

CLI::Validator finiteIn(double lo, double hi, const std::string& unit) {
    std::ostringstream range;
    range.precision(6);
    range << "[" << lo << ", " << hi << "]" << (unit.empty() ? "" : " ") << unit;
    const std::string accepted = range.str();
    return CLI::Validator(
        [lo, hi, accepted](std::string& input) -> std::string {
            std::string_view text = input;
            if (!text.empty() && text.front() == '+') text.remove_prefix(1);
            double value = 0.0;
            const auto [end, error] =
                std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::general);
            const bool number = !text.empty() && error == std::errc{} && end == text.data() + text.size();
            if (!number || !std::isfinite(value) || value < lo || value > hi) {
                return "must be a finite number in " + accepted + ", got '" + input + "'";
            }
            return {};
        },
        accepted);
}

CLI::Validator finiteNumber() {
    return CLI::Validator(
        [](std::string& input) -> std::string {
            std::string_view text = input;
            if (!text.empty() && text.front() == '+') text.remove_prefix(1);
            double value = 0.0;
            const auto [end, error] =
                std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::general);
            const bool number = !text.empty() && error == std::errc{} && end == text.data() + text.size();
            if (!number || !std::isfinite(value))
                return "must be a finite decimal number (no nan, inf or hexadecimal), got '" + input + "'";
            return {};
        },
        "");
}

void requireFiniteFloats(CLI::App& app) {
    for (CLI::App* command : app.get_subcommands({})) {
        for (CLI::Option* option : command->get_options()) {
            // CLI11 names the type of a double or std::optional<double> option FLOAT (then its
            // checks: "FLOAT:FLOAT in [0 - 1]")
            if (option->get_type_name().rfind("FLOAT", 0) == 0) option->check(finiteNumber());
        }
    }
}

namespace {

/// Options that name a file or folder a command reads, options that name a file it writes, and
/// options that name the stem of files it writes (with their suffixes).
constexpr const char* kInputOptions[] = {"--robot",       "ROBOT",          "--trajectory", "--record",
                                         "--record-y",    "--record-theta", "--forces",     "--prior",
                                         "--calibration", "--data",         "--motion"};
constexpr const char* kOutputFileOptions[] = {"--output", "--out", "--log", "--png", "--svg", "--summary"};

std::string optionName(const CLI::Option& option) {
    return option.get_lnames().empty() ? option.get_name() : "--" + option.get_lnames().front();
}

template <std::size_t N>
bool among(const std::string& name, const char* const (&names)[N]) {
    return std::find(std::begin(names), std::end(names), name) != std::end(names);
}

}  // namespace

app::CommandPaths commandPaths(const CLI::App& command) {
    app::CommandPaths paths;
    // --out is the old spelling of --out-dir where a command has one, else of --output
    const bool out_is_folder = command.get_option_no_throw("--out-dir") != nullptr;
    for (const CLI::Option* option : command.get_options()) {
        std::string name = optionName(*option);
        if (name == "--out" && out_is_folder) name = "--out-dir";
        std::vector<std::string> values = option->results();
        if (values.empty() && !option->get_default_str().empty()) values = {option->get_default_str()};
        for (const std::string& value : values) {
            if (among(name, kInputOptions))
                paths.input(name, value);
            else if (among(name, kOutputFileOptions))
                paths.output(name, value);
            else if (name == "--figure")
                paths.outputStem(name, value, {".png", ".svg"});
            else if (name == "--frequency-map")
                paths.outputStem(name, value, {".csv", ".png", ".svg"});
            else if (name == "--out-dir")
                paths.outputFolder(name, value);
        }
    }
    return paths;
}

void refuseOutputOverInput(const CLI::App& command) {
    app::refuseOutputOverInput(command.get_name(), commandPaths(command));
}

void warnOldSpelling(const std::string& old_name, const std::string& new_name) {
    std::fprintf(stderr, "nocdyn: warning: %s is deprecated: use %s (the old spelling goes in the next release)\n",
                 old_name.c_str(), new_name.c_str());
    std::fflush(stderr);
}

void addQuietOption(CLI::App& command) {
    command.add_flag_callback(
        "--quiet,-q", [] { setQuiet(true); },
        "Nothing on standard error but errors and warnings (no progress line, no 'wrote FILE' line, no\n"
        "summary line); the results unchanged: every file, and a table or JSON printed on standard output");
}

void addRobotOption(CLI::App& command, app::RobotSource& robot) {
    command
        .add_option("--robot", robot.path, "Robot file (YAML); default: the paper's prototype (robots/paper-3prr.yaml)")
        ->check(CLI::ExistingFile);
    command
        .add_option_function<std::vector<std::string>>(
            "--set",
            [&robot](const std::vector<std::string>& assignments) {
                for (const std::string& text : assignments) {
                    try {
                        app::addOverride(robot.set, io::parseParameterAssignment(text));
                    } catch (const Error& e) {
                        throw CLI::ValidationError("--set", e.what());
                    }
                }
            },
            "NAME=VALUE: a parameter the robot file declares (parameters:), overridden; repeatable")
        ->type_name("NAME=VALUE");
}

void addSamplingOptions(CLI::App& command, app::SamplingOptions& sampling) {
    command
        .add_option("--trajectory", sampling.trajectory,
                    "paper1, paper2 (eqs. 33-34), a trajectory file (YAML, harmonics) or samples (.csv: t and "
                    "x,y,theta or ax,ay,alpha)")
        ->required();
    command.add_option("--duration", sampling.duration, "Seconds to sample [default: the file's duration, else 0.2]")
        ->check(within(app::kDurationRange));
    command.add_option("--rate", sampling.rate, "Samples per second")
        ->check(within(app::kRateRange))
        ->capture_default_str();
}

io::OutputFile openOutput(const std::string& path) {
    return path.empty() ? io::OutputFile::standardOutput() : io::OutputFile(path);
}

void writeTable(const io::Table& table, const std::string& path) {
    io::OutputFile out = openOutput(path);
    io::writeCsv(out, table);
    out.commit();
}

void printText(std::string_view text) {
    std::cout << text;
    std::cout.flush();
    if (!std::cout) throw Error("cannot write to standard output");
}

void writeText(const std::string& text, const std::string& path) {
    if (path.empty()) {
        printText(text);
    } else {
        io::writeTextFile(path, text);
    }
}

CLI::Option* addPlantOption(CLI::App& command, PlantKind& plant) {
    // what each plant is (app::makePlant)
    const char* help =
        "simbody (the independent model, integrated to its accuracy: about 0.4 s of motion per CPU "
        "second at 10 kHz), nocdyn (nocdyn's forward dynamics, error-controlled to 1e-10: about 17 s "
        "per CPU second) or nocdyn-rk4 (the same, one Runge-Kutta 4 step per controller tick: about "
        "26 s per CPU second; docs/validation.md, earthquake replay)";
    return addChoiceOption(command, "--plant", plant, help);
}

namespace {

/// The field name noise_pose as the command line spells it, --noise-pose.
std::string dashed(const std::string& field) {
    std::string option = "--";
    option += field;
    std::replace(option.begin(), option.end(), '_', '-');
    return option;
}

}  // namespace

std::string commandLineText(const std::string& message, const CLI::App* command) {
    // `name`: an option named by the application layer
    static const std::regex quoted(R"(`([a-z0-9_]+)`)");
    // a bare snake_case word: an option when the command has one by that name (or, with no
    // command known, always)
    static const std::regex snake(R"(\b[a-z]+(_[a-z]+)+\b)");
    std::string out;
    auto at = message.cbegin();
    for (std::sregex_iterator m(message.begin(), message.end(), quoted), end; m != end; ++m) {
        out.append(at, (*m)[0].first);
        out += dashed((*m)[1].str());
        at = (*m)[0].second;
    }
    out.append(at, message.cend());
    std::string result;
    at = out.cbegin();
    for (std::sregex_iterator m(out.begin(), out.end(), snake), end; m != end; ++m) {
        result.append(at, (*m)[0].first);
        const std::string option = dashed((*m)[0].str());
        const bool is_option = command == nullptr || command->get_option_no_throw(option) != nullptr;
        const bool already = (*m)[0].first - out.cbegin() >= 2 && *((*m)[0].first - 1) == '-';
        result += is_option && !already ? option : (*m)[0].str();
        at = (*m)[0].second;
    }
    result.append(at, out.cend());
    return result;
}

std::string commandLineMessage(const app::OptionError& e, const CLI::App* command) {
    return dashed(e.field()) + ": " + commandLineText(e.message(), command);
}

nlohmann::json matrixJson(const Eigen::Ref<const Eigen::MatrixXd>& m) {
    nlohmann::json rows = nlohmann::json::array();
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
        nlohmann::json row = nlohmann::json::array();
        for (Eigen::Index k = 0; k < m.cols(); ++k) row.push_back(m(i, k));
        rows.push_back(row);
    }
    return rows;
}

std::string matrixText(const Eigen::Ref<const Eigen::MatrixXd>& m) {
    std::string out;
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
        out += "  [";
        for (Eigen::Index k = 0; k < m.cols(); ++k) out += text::format("%s% .9e", k ? "  " : "", m(i, k));
        out += "]\n";
    }
    return out;
}

}  // namespace nocdyn::cli
