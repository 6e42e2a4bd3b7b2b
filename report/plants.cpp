#include "plants.hpp"

#include "nocdyn/error.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/shake.hpp"
#ifdef NOCDYN_HAS_SIMBODY
#include "simbody_plant.hpp"
#endif

namespace nocdyn::report {

std::string defaultPlantName() {
#ifdef NOCDYN_HAS_SIMBODY
    return "simbody";
#else
    return "nocdyn";
#endif
}

CLI::Option* addPlantOption(CLI::App& command, std::string& plant) {
    return command
        .add_option("--plant", plant,
                    "simbody (the independent model, integrated to its accuracy), nocdyn (nocdyn's forward "
                    "dynamics, error-controlled to 1e-10) or nocdyn-rk4 (the same, one Runge-Kutta 4 step per "
                    "controller tick: about twice as fast)")
        ->check(CLI::IsMember({"simbody", "nocdyn", "nocdyn-rk4"}))
        ->capture_default_str();
}

std::unique_ptr<RobotPlant> makePlant(const std::string& name, const RobotDescription& robot, double accuracy) {
    if (name == "nocdyn") return std::make_unique<SimulatorRobotPlant>(Model(robot));
    if (name == "nocdyn-rk4") return std::make_unique<RungeKuttaRobotPlant>(Model(robot));
#ifdef NOCDYN_HAS_SIMBODY
    if (name == "simbody") return std::make_unique<SimbodyPlant>(robot, accuracy);
#endif
    (void)accuracy;
    throw Error("--plant " + name + ": not built in (use --plant nocdyn)");
}

}  // namespace nocdyn::report
