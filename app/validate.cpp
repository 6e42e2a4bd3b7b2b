#include "app/validate.hpp"

#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/validation/agreement.hpp"

namespace nocdyn::app {

ValidateResult runValidate(const ValidateOptions& options, Observer& observer) {
    validate(static_cast<const SamplingOptions&>(options));
    const RobotDescription robot = loadRobot(options.robot);
    const PoseTrajectory trajectory =
        trajectoryFor(Model(robot), io::trajectoryByNameOrFile(options.trajectory), options.trajectory);
    const auto times = sampleTimes(chooseDuration(options.duration, trajectory), options.rate);
    stopIfRequested(observer);
    const validation::EngineComparison comparison = validation::compareWithEngines(robot, trajectory, times);
    ValidateResult out;
    out.robot = robot.name;
    out.trajectory = trajectory.name;
    out.samples = times.size();
    out.table = validation::toTable(comparison);
    out.agreement = validation::agreementTable(comparison);
    return out;
}

}  // namespace nocdyn::app
