#include "plants.hpp"

#include "nocdyn/error.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/shake.hpp"
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
