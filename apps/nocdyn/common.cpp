#include "common.hpp"

#include "nocdyn/io/robot_yaml.hpp"

namespace nocdyn::cli {

void addRobotOption(CLI::App& command, std::string& robot_path) {
    command.add_option("--robot", robot_path, "Robot file (YAML); default: the paper's prototype (robots/paper-3prr.yaml)")
        ->check(CLI::ExistingFile);
}

void addTrajectoryOptions(CLI::App& command, TrajectoryOptions& options) {
    command.add_option("--trajectory", options.trajectory, "paper1, paper2 (eqs. 33-34) or a trajectory file (YAML)")
        ->required();
    addRobotOption(command, options.robot);
    command.add_option("--duration", options.duration, "Seconds to sample [default: the file's duration, else 0.2]")
        ->check(CLI::PositiveNumber);
    command.add_option("--rate", options.rate, "Samples per second")->check(CLI::PositiveNumber)->capture_default_str();
    command.add_option("--output,-o", options.output, "CSV file to write [default: stdout]");
}

RobotParameters loadRobotOrDefault(const std::string& path) {
    if (path.empty()) return RobotParameters{};
    return io::loadRobot(path);
}

double chooseDuration(const std::optional<double>& requested, const PoseTrajectory& trajectory) {
    if (requested) return *requested;
    if (trajectory.duration) return *trajectory.duration;
    return 0.2;
}

io::OutputFile openOutput(const std::string& path) {
    return path.empty() ? io::OutputFile::standardOutput() : io::OutputFile(path);
}

void writeTable(const io::Table& table, const std::string& path) {
    io::OutputFile out = openOutput(path);
    io::writeCsv(out, table);
    out.commit();
}

}  // namespace nocdyn::cli
