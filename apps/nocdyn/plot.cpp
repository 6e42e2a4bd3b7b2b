#include "plot.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "nocdyn/error.hpp"

extern char** environ;

namespace nocdyn::cli {

namespace {

std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

std::string script(const Figure& figure, const std::string& terminal, const std::string& output) {
    std::ostringstream gp;
    const int height = figure.height > 0 ? figure.height : 380 * static_cast<int>(figure.panels.size()) + 60;
    gp << "set terminal " << terminal << " size " << figure.width << "," << height << "\n";
    gp << "set output " << quoted(output) << "\n";
    gp << "set grid\nset key outside right top\nset tics nomirror\n";
    char number[64];
    for (std::size_t p = 0; p < figure.panels.size(); ++p) {
        for (std::size_t s = 0; s < figure.panels[p].series.size(); ++s) {
            const PlotSeries& series = figure.panels[p].series[s];
            gp << "$d" << p << "_" << s << " << EOD\n";
            for (std::size_t k = 0; k < series.x.size(); ++k) {
                std::snprintf(number, sizeof number, "%.10g %.10g\n", series.x[k], series.y[k]);
                gp << number;
            }
            gp << "EOD\n";
        }
    }
    gp << "set multiplot layout " << figure.panels.size() << ",1 title " << quoted(figure.title) << "\n";
    for (std::size_t p = 0; p < figure.panels.size(); ++p) {
        const PlotPanel& panel = figure.panels[p];
        gp << "set title " << quoted(panel.title) << "\n";
        gp << "set xlabel " << quoted(panel.xlabel) << "\nset ylabel " << quoted(panel.ylabel) << "\n";
        gp << (panel.log_x ? "set logscale x\n" : "unset logscale x\n");
        gp << (panel.log_y ? "set logscale y\n" : "unset logscale y\n");
        gp << "plot ";
        for (std::size_t s = 0; s < panel.series.size(); ++s) {
            gp << (s ? ", " : "") << "$d" << p << "_" << s << " using 1:2 with " << panel.series[s].style
               << " title " << quoted(panel.series[s].label);
        }
        gp << "\n";
    }
    gp << "unset multiplot\nset output\n";
    return gp.str();
}

void runGnuplot(const std::string& script_path) {
    char program[] = "gnuplot";
    std::string path_copy = script_path;
    char* argv[] = {program, path_copy.data(), nullptr};
    pid_t pid = 0;
    if (posix_spawnp(&pid, "gnuplot", nullptr, nullptr, argv, environ) != 0) {
        throw Error("cannot run gnuplot to draw figures: install it (apt-get install gnuplot-nox)");
    }
    int status = 0;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        throw Error("gnuplot failed on " + script_path);
    }
}

}  // namespace

void renderFigure(const Figure& figure, const std::string& stem) {
    const std::string script_path = stem + ".gp";
    for (const auto& [terminal, extension] :
         {std::pair<std::string, std::string>{"pngcairo enhanced font 'Sans,11'", ".png"},
          std::pair<std::string, std::string>{"svg enhanced dynamic font 'Sans,11'", ".svg"}}) {
        {
            std::ofstream out(script_path);
            if (!out) throw Error("cannot write '" + script_path + "'");
            out << script(figure, terminal, stem + extension);
        }
        runGnuplot(script_path);
    }
    std::error_code ignored;
    std::filesystem::remove(script_path, ignored);
}

}  // namespace nocdyn::cli
