// Sub-commands of `nocdyn`. Each adds itself to the application; its callback runs the
// command and throws nocdyn::Error for anything the user must be told about.
#pragma once

#include <CLI/CLI.hpp>

namespace nocdyn::app {
struct ShakeOptions;
}  // namespace nocdyn::app

namespace nocdyn::cli {

void addPoseCommand(CLI::App& app);
void addInverseDynamicsCommand(CLI::App& app);
void addReproduceCommand(CLI::App& app);
void addForwardKinematicsCommand(CLI::App& app);
void addSimulateCommand(CLI::App& app);
void addControlCommand(CLI::App& app);
void addEnvelopeCommand(CLI::App& app);
void addWorkspaceCommand(CLI::App& app);
void addConvertCommand(CLI::App& app);
void addAnimateCommand(CLI::App& app);
void addShakeCommand(CLI::App& app);
/// shake's --x-azimuth and --per-axis-scale (shake_six_dof_options.cpp).
void addShakeComponentOptions(CLI::App& command, app::ShakeOptions& options);
void addDriveIterationOptions(CLI::App& command, app::ShakeOptions& options);
void addRegressorCommand(CLI::App& app);
void addIdentifyCommand(CLI::App& app);
void addExciteCommand(CLI::App& app);
void addLoadsCommand(CLI::App& app);
void addDesignCommand(CLI::App& app);
void addFrequencyResponseCommand(CLI::App& app);
#ifdef NOCDYN_HAS_ENGINES
void addValidateCommand(CLI::App& app);
#endif

}  // namespace nocdyn::cli
