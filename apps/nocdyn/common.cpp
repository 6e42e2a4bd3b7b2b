#include "common.hpp"

#include "plants.hpp"
#include "progress.hpp"

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

/// Options that name a file or folder a command reads, and options that name a file it writes
/// (or, for --figure, the stem of STEM.png and STEM.svg).
constexpr const char* kInputOptions[] = {"--robot",       "ROBOT",          "--trajectory", "--record",
                                         "--record-y",    "--record-theta", "--forces",     "--prior",
                                         "--calibration", "--data",         "--motion"};
constexpr const char* kOutputFileOptions[] = {"--output", "--out", "--log", "--png", "--svg"};

bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
    std::error_code error;
    return std::filesystem::equivalent(a, b, error) && !error;
}

/// The kinds of file a command writes into its --out-dir (tables, reports, figures, pages).
bool outputKind(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* kind : {".csv", ".json", ".md", ".png", ".svg", ".html"}) {
        if (extension == kind) return true;
    }
    return false;
}

/// Whether `path`, or a folder it is in, is the folder `dir` (by inode, through any link).
bool isInside(const std::filesystem::path& path, const std::filesystem::path& dir) {
    std::error_code error;
    if (!std::filesystem::is_directory(dir, error)) return false;
    std::filesystem::path at = std::filesystem::absolute(path, error);
    if (error) return false;
    for (;;) {
        if (sameFile(at, dir)) return true;
        if (!at.has_relative_path() || at.parent_path() == at) return false;
        at = at.parent_path();
    }
}

std::string optionName(const CLI::Option& option) {
    return option.get_lnames().empty() ? option.get_name() : "--" + option.get_lnames().front();
}

}  // namespace

void refuseOutputOverInput(const CLI::App& command) {
    std::vector<std::pair<std::string, std::string>> inputs, files, folders;  // option, path
    // --out is the old spelling of --out-dir where a command has one, else of --output
    const bool out_is_folder = command.get_option_no_throw("--out-dir") != nullptr;
    for (const CLI::Option* option : command.get_options()) {
        std::string name = optionName(*option);
        if (name == "--out" && out_is_folder) name = "--out-dir";
        std::vector<std::string> values = option->results();
        if (values.empty() && !option->get_default_str().empty()) values = {option->get_default_str()};
        for (const std::string& value : values) {
            if (value.empty()) continue;
            if (std::find(std::begin(kInputOptions), std::end(kInputOptions), name) != std::end(kInputOptions))
                inputs.emplace_back(name, value);
            else if (std::find(std::begin(kOutputFileOptions), std::end(kOutputFileOptions), name) !=
                     std::end(kOutputFileOptions))
                files.emplace_back(name, value);
            else if (name == "--figure")
                files.insert(files.end(), {{name, value + ".png"}, {name, value + ".svg"}});
            else if (name == "--out-dir")
                folders.emplace_back(name, value);
        }
    }
    for (const auto& [in_option, input] : inputs) {
        for (const auto& [out_option, output] : files) {
            if (sameFile(output, input)) {
                throw Error(command.get_name() + ": " + out_option + " '" + io::terminalText(output) +
                            "' is an input file (" + in_option + " '" + io::terminalText(input) +
                            "'): writing it would replace it");
            }
        }
        // in the output folder, a file of a kind the command writes there (a record beside it
        // is read, not replaced; a folder of inputs holding the output folder is fine)
        for (const auto& [out_option, folder] : folders) {
            std::error_code error;
            const bool a_folder = std::filesystem::is_directory(input, error);
            if ((a_folder && sameFile(input, folder)) || (!a_folder && outputKind(input) && isInside(input, folder))) {
                throw Error(command.get_name() + ": " + in_option + " '" + io::terminalText(input) +
                            "' is inside the output folder " + out_option + " '" + io::terminalText(folder) +
                            "', where the command writes files of its kind: choose another folder");
            }
        }
    }
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

CLI::Option* addPlantOption(CLI::App& command, std::string& plant) {
    // what each plant is (report::makePlant)
    const char* help =
        "simbody (the independent model, integrated to its accuracy: about 0.4 s of motion per CPU "
        "second at 10 kHz), nocdyn (nocdyn's forward dynamics, error-controlled to 1e-10: about 17 s "
        "per CPU second) or nocdyn-rk4 (the same, one Runge-Kutta 4 step per controller tick: about "
        "26 s per CPU second; docs/validation.md, earthquake replay)";
    return command.add_option("--plant", plant, help)
        ->check(CLI::IsMember(std::vector<std::string>(std::begin(report::kPlantNames), std::end(report::kPlantNames))))
        ->capture_default_str();
}

/// An option's message as the command line spells its options: noise_pose -> --noise-pose.
std::string commandLineMessage(const app::OptionError& e) {
    static const std::regex snake(R"(\b([a-z]+(_[a-z]+)+)\b)");
    std::string message;
    std::regex_replace(std::back_inserter(message), e.message().begin(), e.message().end(), snake, "--$1");
    for (std::size_t at = 0; (at = message.find("--", at)) != std::string::npos; at += 2) {
        for (std::size_t k = at + 2;
             k < message.size() && (std::isalpha(static_cast<unsigned char>(message[k])) || message[k] == '_'); ++k) {
            if (message[k] == '_') message[k] = '-';
        }
    }
    std::string field = e.field();
    std::replace(field.begin(), field.end(), '_', '-');
    return "--" + field + ": " + message;
}

}  // namespace nocdyn::cli
