// libFuzzer harness of the general robot-file reader (either form): any text either becomes a
// description from which a Model is built (or is refused by it with nocdyn::Error) and whose
// inverse dynamics at home are finite on both paths, and whose general form written back reads
// back the same; or it is refused with nocdyn::Error. When the file declares compliance (joint
// stiffness, elastic bodies), K and the lumped and elastodynamic frequencies at home are finite
// or refused by a Status or nocdyn::Error: accepted compliance never gives NaN or infinity.
// Anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(bytes), size);
    std::optional<nocdyn::Model> model;
    try {
        model.emplace(nocdyn::io::parseRobotDescription(text, "fuzz.yaml"));
    } catch (const nocdyn::Error&) {
        return 0;
    }
    nocdyn::Data full(*model), lean(*model);
    const nocdyn::Pose p = model->home;
    const nocdyn::Twist dp(0.1, 0.01, -0.01), ddp(1.0, 0.1, 0.1);
    const nocdyn::Status a = nocdyn::inverseDynamics(*model, full, p, dp, ddp);
    const nocdyn::Status b = nocdyn::inverseDynamicsFast(*model, lean, p, dp, ddp);
    if (a.ok() != b.ok()) std::abort();
    if (a && !(full.I.allFinite() && full.C.allFinite() && full.tau.allFinite() && lean.tau.allFinite())) std::abort();
    const nocdyn::StiffnessModel compliance(*model);
    if (compliance.any) {
        nocdyn::Data data(*model);
        nocdyn::StiffnessData K;
        nocdyn::LumpedModes modes;
        if (nocdyn::stiffnessAndModes(*model, compliance, data, p, K, modes)) {
            if (!(K.K.allFinite() && modes.frequency.allFinite() && modes.shape.allFinite())) std::abort();
            if (compliance.any_elastic) {
                nocdyn::ElastodynamicModes elastic;
                try {
                    if (nocdyn::elastodynamicModes(*model, compliance, data, elastic) &&
                        !(elastic.frequency.allFinite() && elastic.shape.allFinite())) {
                        std::abort();
                    }
                } catch (const nocdyn::Error&) {
                }
            }
        }
    }
    const std::string back = nocdyn::io::descriptionToYaml(model->description);
    if (nocdyn::io::descriptionToYaml(nocdyn::io::parseRobotDescription(back, "back.yaml")) != back) std::abort();
    return 0;
}
