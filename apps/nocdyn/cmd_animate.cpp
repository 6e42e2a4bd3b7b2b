// nocdyn animate: binds app::AnimateOptions; the application layer samples the motion and builds
// the page and the frame, and this command writes them (--output; --png, --svg).
#include <memory>
#include <string>

#include "app/animate.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "render/plot.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace animate_command {

struct Options : app::AnimateOptions {
    std::string output = "robot.html";  ///< the page; none with --frame unless given
    std::string png, svg;               ///< with --frame
};

void run(const Options& options) {
    TerminalObserver observer("nocdyn animate");
    const app::AnimateResult result = app::runAnimate(options, observer);
    observer.finish();
    if (result.frame) render::renderFigureFiles(*result.frame, options.png, options.svg);
    if (!options.output.empty()) io::writeTextFile(options.output, result.html);
}

}  // namespace animate_command

void addAnimateCommand(CLI::App& app) {
    auto options = std::make_shared<animate_command::Options>();
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
        "--svg); the page is then written only when --output is given. A two-DOF robot (motion: translation):\n"
        "the arms, forearms and the tool point along x, y (no theta column or motion). A spatial robot (space:\n"
        "spatial) is drawn in 3-D (three.js inlined; drag rotates, the wheel zooms): each limb through its joints,\n"
        "coloured by its actuator's force, the platform and the path of its point, along a trajectory file\n"
        "(--motion, --frame, --png and --svg are planar only).");
    addRobotOption(*command, options->robot);
    auto* trajectory = command->add_option("--trajectory", options->trajectory,
                                           "paper1, paper2 (eqs. 33-34), a trajectory file (YAML, harmonics) or "
                                           "samples (.csv: t and x,y,theta or ax,ay,alpha)");
    auto* motion = command->add_option("--motion", options->motion,
                                       "CSV with columns t,x,y,theta,tau1..taun (t,x,y,tau1..taun for a two-DOF "
                                       "robot; SI; other columns ignored), as "
                                       "written by simulate, control, inverse-dynamics or shake; u is recomputed "
                                       "from the pose. A --trajectory CSV with these columns is played so too");
    trajectory->excludes(motion);
    command
        ->add_option("--duration", options->duration,
                     "With --trajectory: seconds to sample [default: the file's duration, else 0.2]")
        ->check(within(app::kDurationRange))
        ->excludes(motion);
    command->add_option("--rate", options->rate, "With --trajectory: samples per second")
        ->check(within(app::kRateRange))
        ->capture_default_str()
        ->excludes(motion);
    command
        ->add_option("--slow-motion", options->slow_motion,
                     "Slow-motion factor K: 1 s of motion plays in K s (changeable on the page) [default: so "
                     "that the whole motion plays in about 10 s]")
        ->check(within(app::kSlowMotionRange));
    command
        ->add_option("--magnify", options->magnify,
                     "Displacements about the mean pose drawn this many times larger (changeable on the page)")
        ->check(within(app::kMagnifyRange))
        ->capture_default_str();
    auto* out = command->add_option("--output,-o", options->output, "HTML file to write")->capture_default_str();
    auto* old_out = addOldSpelling(*command, "--out", out, options->output);
    auto* frame = command->add_option("--frame", options->frame, "Draw the robot at this time [s] (nearest sample)")
                      ->check(within(app::kFrameRange));
    command->add_option("--png", options->png, "With --frame: PNG file to write")->needs(frame);
    command->add_option("--svg", options->svg, "With --frame: SVG file to write")->needs(frame);
    command->callback([options, out, old_out] {
        if (options->trajectory.empty() && options->motion.empty())
            throw Error("animate: give --trajectory or --motion");
        if (options->frame && options->png.empty() && options->svg.empty())
            throw Error("animate: --frame needs --png or --svg");
        // with --frame the page is written only when --output is given
        animate_command::Options run_options = *options;
        if (options->frame && out->count() + old_out->count() == 0) run_options.output.clear();
        animate_command::run(run_options);
    });
}

}  // namespace nocdyn::cli
