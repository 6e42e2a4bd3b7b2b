// `nocdyn shake`'s options for records given as their components and for six-DOF tables (a
// hexapod replaying a three-component record), and the drive iteration's gain and tolerance,
// apart from cmd_shake.cpp.
#include "app/shake.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace nocdyn::cli {

void addShakeComponentOptions(CLI::App& command, app::ShakeOptions& options) {
    command
        .add_option("--x-azimuth", options.x_azimuth,
                    "A record given as its components: the table's x azimuth [deg clockwise from north] (default: "
                    "the first horizontal's); y is at x's azimuth minus 90 (counter-clockwise seen from above), z up")
        ->check(within(app::kAzimuthRange));
    command.add_flag("--per-axis-scale", options.per_axis_scale,
                     "A six-DOF table: each of x, y, z scaled to its own limit (then the three by one factor), "
                     "not one amplitude scale for all three");
}

void addDriveIterationOptions(CLI::App& command, app::ShakeOptions& options) {
    command.add_option("--iteration-gain", options.iteration_gain, "Drive-signal iteration gain")
        ->check(within(app::kIterationGainRange))
        ->capture_default_str();
    command
        .add_option("--iteration-tolerance", options.iteration_tolerance,
                    "Drive-signal iteration: stop after a pass that lowers the RMS error by less than this share "
                    "of the best pass's")
        ->check(within(app::kIterationToleranceRange))
        ->capture_default_str();
}

}  // namespace nocdyn::cli
