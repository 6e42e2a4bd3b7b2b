#include "app/regressor.hpp"

#include <cstdio>
#include "nocdyn/io/escape.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

void validate(const RegressorOptions& options) { requireIn(options.samples, kRegressorSamplesRange, "samples"); }

RegressorResult runRegressor(const RegressorOptions& options, Observer& /*observer*/) {
    validate(options);
    const Model model(loadRobot(options.robot));
    BaseParameterOptions base_options;
    base_options.samples = options.samples;
    base_options.seed = options.seed;
    RegressorResult out;
    out.base = baseParameters(model, base_options);
    out.pi = standardParameters(model);
    out.text = "# standard parameters (robot file values)\n";
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
