#include "app/inverse_dynamics.hpp"

#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/tables/tables.hpp"

namespace nocdyn::app {

InverseDynamicsResult runInverseDynamics(const InverseDynamicsOptions& options, TableSink& table, Observer& observer) {
    validate(options);
    const Model model(loadRobot(options.robot));
    const PoseTrajectory trajectory =
        trajectoryFor(model, trajectoryOf(options), options.given_trajectory ? "" : options.trajectory);
    const SampleGrid grid = sampleGrid(chooseDuration(options.duration, trajectory), options.rate);
    requireRateAboveNyquist(trajectory, grid.rate);
    const auto policy = options.allow_limits ? LimitPolicy::record : LimitPolicy::error;
    std::vector<std::string> columns = tables::inverseDynamicsColumns(model.actuators, model.task_dimension);
    if (options.reactions) {
        for (std::string& name : tables::reactionColumns(model.limbs)) columns.push_back(std::move(name));
    }
    table.columns(columns);
    std::vector<double> row;
    Meter meter(observer, static_cast<double>(grid.count) / grid.rate, "s");
    InverseDynamicsResult out;
    out.summary =
        options.reactions
            ? streamInverseDynamicsWithReactions(model, trajectory, grid, policy,
                                                 [&](const InverseDynamicsSample& sample, const Reactions& r) {
                                                     tables::inverseDynamicsRow(sample, row, model.task_dimension);
                                                     tables::appendReactions(r, model.limbs, row);
                                                     table.row(row);
                                                     meter(sample.t);
                                                 })
            : streamInverseDynamics(model, trajectory, grid, policy, [&](const InverseDynamicsSample& sample) {
                  tables::inverseDynamicsRow(sample, row, model.task_dimension);
                  table.row(row);
                  meter(sample.t);
              });
    out.samples = grid.count;
    for (const std::string& violation : out.summary.limit_violations) observer.warning(violation);
    return out;
}

}  // namespace nocdyn::app
