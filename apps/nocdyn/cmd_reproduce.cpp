// nocdyn reproduce: the paper's results (Section V, Figs. 5 and 6) and the project's own
// checks on them, written to one folder with a summary.md.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/prr3/sampling.hpp"
#include "plot.hpp"

namespace nocdyn::cli {

namespace {

constexpr double kDuration = 0.2;   // s, as in the paper's figures
constexpr double kRate = 10000.0;   // Hz

struct ReproduceOptions {
    std::string out = "results";
};

PlotPanel jointPanel(const prr3::InverseDynamicsSeries& series, bool forces) {
    PlotPanel panel;
    panel.title = forces ? "(b) Motor forces" : "(a) Motor displacements";
    panel.xlabel = "t [s]";
    panel.ylabel = forces ? "{/Symbol t}_j [N]" : "u_j [mm]";
    for (int j = 0; j < prr3::kLimbs; ++j) {
        PlotSeries line;
        line.label = (forces ? "{/Symbol t}_" : "u_") + std::to_string(j + 1);
        line.x = series.t;
        for (std::size_t k = 0; k < series.t.size(); ++k) {
            line.y.push_back(forces ? series.tau[k](j) : series.u[k](j) * 1e3);
        }
        line.style = "lines lw 2";
        panel.series.push_back(std::move(line));
    }
    return panel;
}

/// Both paper trajectories: CSV, figures in the spirit of Figs. 5 and 6, and the peak
/// stroke and force against the actuator limits.
void reproduceTrajectories(const prr3::Model& model, const std::filesystem::path& out, std::ostream& summary) {
    const RobotParameters& robot = model.parameters;
    summary << "## Paper trajectories 1 and 2 (eqs. 33-34): inverse dynamics\n\n"
            << "Sampled over " << kDuration << " s at " << kRate / 1000 << " kHz. Actuator limits: total stroke "
            << robot.stroke * 1e3 << " mm (+-" << robot.stroke * 0.5e3 << " mm about the reference posture), peak force "
            << robot.peak_force << " N.\n\n"
            << "| trajectory | actuator | u range [mm] | peak abs(u) / half stroke | peak abs(tau) [N] | peak abs(tau) / peak force |\n"
            << "| --- | --- | --- | --- | --- | --- |\n";
    const auto times = prr3::sampleTimes(kDuration, kRate);
    struct Case {
        const char* name;
        PoseTrajectory trajectory;
        const char* figure;
    };
    for (const Case& c : {Case{"paper1", paperTrajectory1(), "Fig. 5"}, Case{"paper2", paperTrajectory2(), "Fig. 6"}}) {
        const auto series = prr3::sampleInverseDynamics(model, c.trajectory, times, prr3::LimitPolicy::record);
        io::writeCsvFile((out / (std::string(c.name) + ".csv")).string(), prr3::toTable(series));
        Figure displacements{std::string(c.name) + ": motor displacements (cf. the paper's " + c.figure + "a)",
                             {jointPanel(series, false)}};
        renderFigure(displacements, (out / (std::string(c.name) + "_displacements")).string());
        Figure forces{std::string(c.name) + ": motor forces (cf. the paper's " + c.figure + "b)", {jointPanel(series, true)}};
        renderFigure(forces, (out / (std::string(c.name) + "_forces")).string());
        for (int j = 0; j < prr3::kLimbs; ++j) {
            double lo = 0.0, hi = 0.0;
            for (const auto& u : series.u) {
                lo = std::min(lo, u(j));
                hi = std::max(hi, u(j));
            }
            char row[256];
            std::snprintf(row, sizeof row, "| %s | %d | %+.3f .. %+.3f | %.1f %% | %.2f | %.1f %% |\n", c.name, j + 1,
                          lo * 1e3, hi * 1e3, 100.0 * series.peak_stroke[j] / (0.5 * robot.stroke),
                          series.peak_force[j], 100.0 * series.peak_force[j] / robot.peak_force);
            summary << row;
        }
        for (const std::string& violation : series.limit_violations) summary << "\nLimit exceeded: " << violation << "\n";
    }
    summary << "\nFiles: `paper1.csv`, `paper2.csv` (columns t,x,y,theta,u1..u3,du1..du3,ddu1..ddu3,tau1..tau3,kinetic);"
            << " figures `paper{1,2}_displacements.{png,svg}` and `paper{1,2}_forces.{png,svg}`.\n\n";
}

void run(const ReproduceOptions& options) {
    const std::filesystem::path out(options.out);
    std::error_code error;
    std::filesystem::create_directories(out, error);
    if (error || !std::filesystem::is_directory(out)) throw Error("cannot create output folder '" + options.out + "'");
    const prr3::Model model{RobotParameters{}};
    std::ostringstream summary;
    summary << "# nocdyn reproduce: the paper's 3-PRR results\n\n"
            << "Robot: the paper's prototype (`robots/paper-3prr.yaml`, eq. 32 and Table I, SI units).\n\n";
    reproduceTrajectories(model, out, summary);
    io::writeTextFile((out / "summary.md").string(), summary.str());
    std::cout << "nocdyn reproduce: wrote " << (out / "summary.md").string() << ", CSV files and figures in "
              << out.string() << "/\n";
}

}  // namespace

void addReproduceCommand(CLI::App& app) {
    auto options = std::make_shared<ReproduceOptions>();
    CLI::App* command = app.add_subcommand(
        "reproduce",
        "The main job: reproduce the paper's results for its prototype. Both paper trajectories over\n"
        "0.2 s at 10 kHz: one CSV each, figures like the paper's Figs. 5 and 6 (motor displacements and\n"
        "forces, PNG and SVG, drawn by gnuplot) and summary.md with peak stroke and force per actuator\n"
        "against the actuator limits.");
    command->add_option("--out", options->out, "Output folder (created if missing)")->capture_default_str();
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
