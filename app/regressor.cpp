#include "app/regressor.hpp"

#include <cstdio>
#include "nocdyn/io/escape.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

void validate(const RegressorOptions& options) { requireIn(options.samples, kRegressorSamplesRange, "samples"); }

RegressorResult runRegressor(const RegressorOptions& options, Observer& /*observer*/) {
    validate(options);
    // a two-DOF robot too: tau = Y pi over its two actuators (regressor.hpp)
    const Model model(loadRobot(options.robot));
    RegressorResult out;
    out.base = baseParameters(model, options);
    out.pi = standardParameters(model);
    out.text = "# standard parameters (robot file values)\n";
    if (model.task_dimension == 2) {
        out.text +=
            "# a two-DOF robot (motion: translation): the platform is a point mass at the tool point that never "
            "turns, so of its parameters only platform.m acts on the forces (a payload: its mass only)\n";
    }
    std::string line;
    for (int c = 0; c < parameterCount(model); ++c) {
        out.names.push_back(parameterName(model, c));
        out.units.push_back(parameterUnit(model, c));
        line = text::format("%-28s %15.9g %s\n", io::terminalText(out.names.back()).c_str(), out.pi(c),
                            out.units.back().c_str());
        out.text += line;
    }
    out.text += describeBaseParameters(model, out.base);
    return out;
}

}  // namespace nocdyn::app
