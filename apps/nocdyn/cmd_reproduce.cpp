// nocdyn reproduce: the options, the progress line and the closing line around the report
// module's reproduce() (report/report.hpp).
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "progress.hpp"
#include "report.hpp"

namespace nocdyn::cli {

namespace {

struct ReproduceOptions {
    report::ReproduceOptions report;
    bool quiet = false;  ///< nothing on stdout, no progress line
};

void run(const ReproduceOptions& options) {
    if (!parameterOverrides().empty()) throw Error("--set needs --robot: the built-in prototype has no parameters");
    // about two minutes in all: one progress line on a terminal names the section running
    Steps steps("nocdyn reproduce", report::reproduceSections(), options.quiet);
    // --quiet: the sections' console lines (the replay's timing) go nowhere
    std::ostringstream discarded;
    std::streambuf* const console = options.quiet ? std::cout.rdbuf(discarded.rdbuf()) : nullptr;
    struct Restore {
        explicit Restore(std::streambuf* saved) : buffer(saved) {}
        Restore(const Restore&) = delete;
        Restore& operator=(const Restore&) = delete;
        ~Restore() {
            if (buffer != nullptr) std::cout.rdbuf(buffer);
        }
        std::streambuf* buffer;
    } restore{console};
    report::reproduce(options.report, [&](const std::string& section) { steps.next(section); });
    steps.finish();
    if (options.quiet) return;
    const std::filesystem::path out(options.report.out);
    std::cout << "nocdyn reproduce: wrote " << (out / "summary.md").string() << ", CSV files and figures in "
              << out.string() << "/\n";
}

}  // namespace

void addReproduceCommand(CLI::App& app) {
    auto options = std::make_shared<ReproduceOptions>();
    CLI::App* command = app.add_subcommand(
        "reproduce",
        "The main job: reproduce the paper's results for its prototype. Both paper trajectories over\n"
        "0.2 s at 10 kHz: one CSV each, figures like the paper's Figs. 5 and 6 (motor displacements and\n"
        "forces, PNG and SVG, drawn by gnuplot, with the Simbody curves overlaid and their difference\n"
        "plotted), and summary.md with: peak stroke and force per actuator against the actuator limits;\n"
        "the measured agreement with Simbody and MuJoCo; the forward-dynamics round trip; closed-loop\n"
        "computed-torque and PD control on the Simbody plant; the operating envelope (stroke and force);\n"
        "and the example robots of other architectures (3-RRR, 3-RPR, redundant 4-RRR) against both engines;\n"
        "and the payload identification experiment, simulated on the Simbody plant (identification/).");
    command->add_option("--out-dir", options->report.out, "Output folder (created if missing)")->capture_default_str();
    command->add_option("--out", options->report.out)->group("");  // the old spelling, hidden
    command
        ->add_option("--closed-loop-duration", options->report.closed_loop_duration,
                     "Seconds of each closed-loop run on a Simbody plant (the paper's trajectories and the\n"
                     "example robots; about 0.3-0.6 ms of CPU per 10 kHz tick). A shorter run is a quick check of\n"
                     "the same code, its peak errors over less of the trajectory")
        ->check(CLI::Range(1e-3, 10.0))
        ->capture_default_str();
    command
        ->add_option("--identification-duration", options->report.identification_duration,
                     "Seconds of data of each identification experiment (designed excitation with and without\n"
                     "slider friction, paper trajectories 1 and 2; 10 kHz on the Simbody plant). A shorter run\n"
                     "is a quick check of the same code, its estimates from less data")
        ->check(CLI::Range(0.01, 60.0))
        ->capture_default_str();
    command->add_flag("--quiet,-q", options->quiet,
                      "Print nothing on stdout and no progress line (results in the folder; errors still on stderr)");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
