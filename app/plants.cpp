#include "app/plants.hpp"

#include <string>

#include "nocdyn/error.hpp"
#include "nocdyn/model.hpp"
#ifdef NOCDYN_HAS_SIMBODY
#include "nocdyn/validation/simbody_plant.hpp"
#endif

namespace nocdyn::app {

PlantKind defaultPlant() {
#ifdef NOCDYN_HAS_SIMBODY
    return PlantKind::simbody;
#else
    return PlantKind::nocdyn;
#endif
}

std::unique_ptr<RobotPlant> makePlant(PlantKind kind, const RobotDescription& robot, double accuracy) {
    switch (kind) {
        case PlantKind::nocdyn:
            return std::make_unique<SimulatorRobotPlant>(Model(robot));
        case PlantKind::nocdyn_rk4:
            return std::make_unique<RungeKuttaRobotPlant>(Model(robot));
        case PlantKind::simbody:
#ifdef NOCDYN_HAS_SIMBODY
            return std::make_unique<validation::SimbodyPlant>(robot, accuracy);
#else
            break;
#endif
    }
    (void)accuracy;
    throw Error("--plant " + std::string(nameOf(kind)) + ": not built in (use --plant nocdyn)");
}

}  // namespace nocdyn::app
