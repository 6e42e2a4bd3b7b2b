#include "app/reproduce.hpp"

#include "app/outputs.hpp"
#include "report.hpp"

namespace nocdyn::app {

void validate(const ReproduceOptions& options) {
    if (options.out_dir.empty()) throw OptionError("out_dir", "expected a folder name");
    requireIn(options.closed_loop_duration, kClosedLoopDurationRange, "closed_loop_duration");
    requireIn(options.identification_duration, kIdentificationDurationRange, "identification_duration");
}

ReproduceResult runReproduce(const ReproduceOptions& options, Observer& observer) {
    validate(options);
    requireOutputFolder(options.out_dir, "out_dir");
    report::ReproduceOptions report;
    report.out = options.out_dir;
    report.closed_loop_duration = options.closed_loop_duration;
    report.identification_duration = options.identification_duration;
    ReproduceResult out;
    const int total = report::reproduceSections();
    report::reproduce(report, [&](const std::string& section) {
        stopIfRequested(observer);
        observer.step(section, ++out.sections, total);
    });
    out.folder = options.out_dir;
    out.summary = out.folder / "summary.md";
    return out;
}

}  // namespace nocdyn::app
