// nocdyn animate: the robot moving along a trajectory or a recorded motion, as one
// self-contained HTML page, and static frames as PNG and SVG.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>
#include <memory>
#include <optional>

#include "animation.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"

namespace nocdyn::cli {

namespace {

struct AnimateOptions {
    std::string robot, trajectory, motion;
    std::optional<double> duration;
    double rate = 10000.0;
    double slow_motion = 0.0;
    double magnify = 1.0;
    std::string out = "robot.html";
    std::optional<double> frame;
    std::string png, svg;
};

/// Refuses an output that is one of the inputs (the same file by any path or link): writing it
/// would replace the very data it is drawn from.
void requireNotAnInput(const AnimateOptions& options, bool out_given) {
    const std::string outputs[][2] = {
        {"--png", options.png}, {"--svg", options.svg}, {"--output", out_given ? options.out : ""}};
    for (const auto& [option, path] : outputs) {
        if (path.empty()) continue;
        for (const std::string& input : {options.robot, options.trajectory, options.motion}) {
            std::error_code error;
            if (!input.empty() && std::filesystem::equivalent(path, input, error)) {
                throw Error("animate: " + option + " '" + path + "' is an input file (" + input +
                            "): writing it would replace it");
            }
        }
    }
}

/// Whether `path` is a CSV of a recorded motion with its forces (its header has t, x, y, theta
/// and tau1: what simulate, control, inverse-dynamics and shake write), not a trajectory's samples.
bool recordedMotion(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension != ".csv") return false;
    std::ifstream in(path);
    std::string header;
    if (!in || !std::getline(in, header)) return false;
    std::vector<std::string> names;
    std::stringstream fields(header);
    for (std::string name; std::getline(fields, name, ',');) {
        if (!name.empty() && name.back() == '\r') name.pop_back();
        names.push_back(name);
    }
    const auto has = [&](const char* name) { return std::find(names.begin(), names.end(), name) != names.end(); };
    return has("t") && has("x") && has("y") && has("theta") && has("tau1");
}

void run(const AnimateOptions& options, bool out_given, bool sampling_given) {
    requireNotAnInput(options, out_given);
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    MotionSamples motion;
    // a recorded motion given as --trajectory (a replay's shake.csv): played as --motion, forces and all
    const bool recorded = !options.trajectory.empty() && recordedMotion(options.trajectory);
    if (recorded && sampling_given) {
        throw Error("animate: --trajectory " + options.trajectory +
                    " is a recorded motion (t, x, y, theta, tau1..): it is played as recorded, without --duration "
                    "or --rate");
    }
    if (!options.motion.empty() || recorded) {
        motion = motionFromCsv(model, recorded ? options.trajectory : options.motion);
    } else {
        const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
        motion = motionFromTrajectory(model, trajectory, chooseDuration(options.duration, trajectory), options.rate);
    }
    for (const std::string& warning : motion.warnings)
        std::cerr << "nocdyn: warning: " << io::terminalText(warning) << "\n";
    if (options.frame) {
        renderFigureFiles(frameFigure(model, motion, *options.frame), options.png, options.svg);
        if (!out_given) return;
    }
    io::writeTextFile(options.out, animationPage(model, motion, {options.slow_motion, options.magnify}));
}

}  // namespace

void addAnimateCommand(CLI::App& app) {
    auto options = std::make_shared<AnimateOptions>();
    CLI::App* command = app.add_subcommand(
        "animate",
        "The robot in motion as one self-contained HTML page (inline script and canvas; nothing is fetched\n"
        "when it is viewed): every limb, joint and rail (its stroke from the joint limits), the platform and\n"
        "its operation point C drawn to scale, with play, pause, a time slider, speed, slow-motion and\n"
        "magnification controls, each actuator's force as a bar coloured by its fraction of the effort limit,\n"
        "and the plots of u and tau (min and max of every bucket of samples) with a cursor at the current\n"
        "time. The motion is a trajectory (inverse dynamics at --rate over --duration) or a CSV written by\n"
        "simulate, control or inverse-dynamics (--motion). At most 2000 frames are embedded; 0.2 s at 10 kHz\n"
        "gives a page of about 0.4 MB. --frame T draws the sample nearest to T with gnuplot instead (--png,\n"
        "--svg); the page is then written only when --output is given.");
    addRobotOption(*command, options->robot);
    auto* trajectory = command->add_option("--trajectory", options->trajectory,
                                           "paper1, paper2 (eqs. 33-34), a trajectory file (YAML, harmonics) or "
                                           "samples (.csv: t and x,y,theta or ax,ay,alpha)");
    auto* motion = command->add_option("--motion", options->motion,
                                       "CSV with columns t,x,y,theta,tau1..taun (SI; other columns ignored), as "
                                       "written by simulate, control, inverse-dynamics or shake; u is recomputed "
                                       "from the pose. A --trajectory CSV with these columns is played so too");
    trajectory->excludes(motion);
    command
        ->add_option("--duration", options->duration,
                     "With --trajectory: seconds to sample [default: the file's duration, else 0.2]")
        ->check(finiteIn(kMinDuration, kMaxDuration, "s"))
        ->excludes(motion);
    command->add_option("--rate", options->rate, "With --trajectory: samples per second")
        ->check(finiteIn(kMinRate, kMaxRate, "Hz"))
        ->capture_default_str()
        ->excludes(motion);
    command
        ->add_option("--slow-motion", options->slow_motion,
                     "Slow-motion factor K: 1 s of motion plays in K s (changeable on the page) [default: so "
                     "that the whole motion plays in about 10 s]")
        ->check(finiteIn(1.0, 1e6, ""));
    command
        ->add_option("--magnify", options->magnify,
                     "Displacements about the mean pose drawn this many times larger (changeable on the page)")
        ->check(finiteIn(0.0, 1e4, ""))
        ->capture_default_str();
    auto* out = command->add_option("--output,-o", options->out, "HTML file to write")->capture_default_str();
    auto* old_out = command->add_option("--out", options->out)->group("");  // the old spelling, hidden
    auto* frame = command->add_option("--frame", options->frame, "Draw the robot at this time [s] (nearest sample)")
                      ->check(finiteIn(-1e6, 1e6, "s"));
    command->add_option("--png", options->png, "With --frame: PNG file to write")->needs(frame);
    command->add_option("--svg", options->svg, "With --frame: SVG file to write")->needs(frame);
    command->callback([options, command, out, old_out] {
        if (options->trajectory.empty() && options->motion.empty()) {
            throw Error("animate: give --trajectory or --motion");
        }
        if (options->frame && options->png.empty() && options->svg.empty()) {
            throw Error("animate: --frame needs --png or --svg");
        }
        (void)command;
        run(*options, out->count() + old_out->count() > 0, command->count("--duration") + command->count("--rate") > 0);
    });
}

}  // namespace nocdyn::cli
