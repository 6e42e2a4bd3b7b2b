#include "app/reproduce.hpp"

#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <system_error>

#include "app/outputs.hpp"
#include "app/reproduce_sections.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/examples.hpp"

namespace nocdyn::app {

namespace {

/// How many sections runReproduce runs (8, or 9 with both engines built in).
constexpr int kReproduceSections =
#ifdef NOCDYN_HAS_ENGINES
    9;
#else
    8;
#endif

}  // namespace

void validate(const ReproduceOptions& options) {
    if (options.out_dir.empty()) throw OptionError("out_dir", "expected a folder name");
    requireIn(options.closed_loop_duration, kClosedLoopDurationRange, "closed_loop_duration");
    requireIn(options.identification_duration, kIdentificationDurationRange, "identification_duration");
}

ReproduceResult runReproduce(const ReproduceOptions& options, Observer& observer, FileSink& out) {
    validate(options);
    requireOutputFolder(options.out_dir, "out_dir");
    ReproduceResult result;
    const auto next = [&](const std::string& section) {
        stopIfRequested(observer);
        observer.step(section, ++result.sections, kReproduceSections);
    };
    out.folder("");
    const RobotDescription robot = io::exampleRobot("paper-3prr");  // the paper's prototype, expanded by io
    std::ostringstream summary;
    summary << "# nocdyn reproduce: the paper's 3-PRR results\n\n"
            << "Robot: the paper's prototype (`robots/paper-3prr.yaml`, eq. 32 and Table I, SI units).\n\n";
    next("the paper's trajectories");
    reproduceTrajectories(robot, out, summary);
    next("animations");
    reproduceAnimations(out, summary);
    next("forward-dynamics round trip");
    reproduceRoundTrip(robot, summary);
    next("closed-loop control on the Simbody plant");
    reproduceControl(robot, out, summary, options.closed_loop_duration);
    next("operating envelope");
    reproduceEnvelope(robot, out, summary);
    next("workspace");
    reproduceWorkspace(robot, out, summary);
    next("El Centro replay");
    reproduceShake(out, summary);
#ifdef NOCDYN_HAS_ENGINES
    next("example robots against Simbody and MuJoCo");
    reproduceExampleRobots(out, summary, options.closed_loop_duration);
#endif
    next("payload identification experiment");
    reproduceIdentification(out, summary, options.identification_duration);
    out.text("summary.md", summary.str());
    result.folder = options.out_dir;
    result.summary = result.folder / "summary.md";
    return result;
}

}  // namespace nocdyn::app
