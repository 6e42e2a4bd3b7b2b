// nocdyn control: binds app::ControlOptions, writes the closed-loop table, the sensors' log and
// the tracking-error figure where asked, and prints the RMS and peak errors.
#include <cstdio>
#include <memory>

#include "app/control.hpp"
#include "app/pose_spatial.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"
#include "nocdyn/io/layouts.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace control_command {

struct Options : app::ControlOptions {
    std::string output, figure, log;
};

void run(Options options) {
    options.sensor_log = !options.log.empty();
    if (!options.figure.empty() && app::isSpatialRobot(options.robot)) {
        throw Error(options.robot.path + ": the tracking figure of a spatial robot is planar for now (--figure)");
    }
    TerminalObserver observer("nocdyn control");
    app::ControlResult result;
    result = app::runControl(options, observer);
    observer.finish();
    if (!options.output.empty()) writeTable(result.table, options.output);
    if (!options.log.empty()) io::writeCsvFile(options.log, result.log);
    if (!options.figure.empty()) renderFigure(app::trackingFigure(result), options.figure);
    std::fputs(result.text.c_str(), stdout);
}

}  // namespace control_command

void addControlCommand(CLI::App& app) {
    auto options = std::make_shared<control_command::Options>();
    CLI::App* command = app.add_subcommand(
        "control",
        "Closed-loop tracking of a platform trajectory by any robot (either form of robot file; none: the paper's\n"
        "prototype), in the platform coordinates p = [theta, x, y] measured from the plant (or through the encoders,\n"
        "--measure encoders). computed-torque: A_p^T tau = M_p(p) (ddp_d + Kd e' + Kp e) + h_p(p, dp), e = p_d - p,\n"
        "Kp = w^2, Kd = 2w, w = 2 pi f_n; pd: A_p^T tau = M_p(home) (Kp e + Kd e'); tau minimum-norm when redundant.\n"
        "Forces held between ticks, each clipped at its joint's effort. Prints RMS and peak errors.\n"
        "A two-DOF robot (motion: translation): p = [x, y], a trajectory keyed x, y, the plant nocdyn by default.\n"
        "A spatial robot (space: spatial): p = [x, y, z, roll, pitch, yaw] (or [x, y, z]) from a spatial trajectory\n"
        "file, on nocdyn's plant; CSV t, x_d.., x.., u1..un, tau1..taun.\n"
        "CSV: " +
            io::columnList(io::TableId::closed_loop) +
            ".\n"
            "Example: nocdyn control --trajectory paper1 --payload-mass 0.5 --payload-com 0.012 -0.007 --log log.csv");
    command
        ->add_option("--trajectory", options->trajectory,
                     "paper1, paper2 (eqs. 33-34), a trajectory file (YAML, harmonics) or samples (.csv: t and "
                     "x,y,theta or ax,ay,alpha)")
        ->required();
    addRobotOption(*command, options->robot);
    addChoiceOption(*command, "--controller", options->controller, "computed-torque or pd");
    CLI::Option* plant = addPlantOption(*command, options->plant);
    command->add_option("--rate", options->rate, "Controller rate [Hz]")
        ->check(within(app::kControllerRateRange))
        ->capture_default_str();
    command->add_option("--duration", options->duration, "Seconds [default: the file's duration, else 0.2]")
        ->check(within(app::kSimulatedDurationRange));
    command->add_option("--natural-frequency", options->natural_frequency, "f_n of the error dynamics [Hz]")
        ->check(within(app::kNaturalFrequencyRange))
        ->capture_default_str();
    command
        ->add_option("--payload-mass", options->payload_mass,
                     "Model mismatch: mass added to the plant's platform only [kg]")
        ->check(finiteIn(0.0, 1e6, "kg"));
    command
        ->add_option("--payload-inertia", options->payload_inertia,
                     "Model mismatch: the payload's inertia about its c.o.m., on the plant's platform only [kg m^2]")
        ->check(finiteIn(0.0, 1e12, "kg m^2"));
    command
        ->add_option("--payload-com", options->payload_com,
                     "The payload's c.o.m. X Y in the platform frame [m] (default 0 0, at C)")
        ->expected(2)
        ->check(within(app::kLengthRange));
    command
        ->add_option("--noise-pose", options->noise_pose,
                     "Std. dev. of the pose measurement noise [m for x, y; rad for theta]")
        ->check(finiteIn(0.0, 1.0, "m"));
    command->add_option("--noise-rate", options->noise_rate, "Std. dev. of the dp/dt measurement noise [m/s, rad/s]")
        ->check(finiteIn(0.0, 1e3, "m/s"));
    command
        ->add_option("--noise-tau", options->noise_tau, "Std. dev. of the force measurement noise in --log [N or N m]")
        ->check(finiteIn(0.0, 1e6, "N"));
    addChoiceOption(*command, "--measure", options->measure,
                    "What the controller measures. pose: the plant's pose and rate (a pose\n"
                    "sensor, + --noise-pose, --noise-rate); encoders: u and du (+ --noise-u, --noise-du) as a robot\n"
                    "without a pose sensor, the pose by the direct-kinematics tracker (the working mode, from the\n"
                    "reference's start) and dp/dt from A_p dp/dt = du (least squares when redundant)");
    command
        ->add_option("--log", options->log,
                     "The experiment's log as the sensors see it, CSV t,u1..un,tau1..taun "
                     "(u with --noise-u: with --measure encoders the very readings the controller used; tau the "
                     "applied force with --noise-tau, the force sensor's own noise), ready for `nocdyn identify`")
        ->check(nonEmptyPath());
    command
        ->add_option("--noise-u", options->noise_u,
                     "Std. dev. of the encoder noise in --log and, with --measure encoders, of the controller's "
                     "encoders [m or rad]")
        ->check(finiteIn(0.0, 1.0, "m"));
    command
        ->add_option("--noise-du", options->noise_du,
                     "Std. dev. of the encoder-rate noise with --measure encoders [m/s or rad/s]")
        ->check(finiteIn(0.0, 1e3, "m/s"));
    command->add_option("--seed", options->seed, "Noise seed")->capture_default_str();
    command->add_flag("--no-saturation", options->no_saturation, "Do not clip the forces at each joint's effort");
    command->add_option("--output,-o", options->output, "CSV: " + io::columnList(io::TableId::closed_loop) + " (SI)")
        ->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Tracking-error figure: writes STEM.png and STEM.svg")
        ->check(nonEmptyPath());
    command->callback([options, plant] {
        options->plant_given = plant->count() > 0;
        control_command::run(*options);
    });
}

}  // namespace nocdyn::cli
