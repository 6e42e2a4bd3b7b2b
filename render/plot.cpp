#include "render/plot.hpp"

#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/io/output.hpp"
#include "nocdyn/text.hpp"

extern char** environ;

namespace nocdyn::render {

namespace {

// Every text in the script is a single-quoted gnuplot string: there gnuplot performs no
// backslash processing, no backquote (command) substitution and no @macro expansion, and a
// quote is written twice. Only printable characters are kept (any other byte, such as a
// newline that would end the command, becomes '?'), so a text can never leave its string.

/// Length of the well-formed UTF-8 sequence of a printable character (U+00A0 and up) at
/// text[at], or 0.
std::size_t printableUtf8Length(const std::string& text, std::size_t at) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned lead = byte(at);
    const std::size_t length = lead >= 0xF0 && lead <= 0xF4  ? 4
                               : lead >= 0xE0                ? 3
                               : lead >= 0xC2 && lead < 0xE0 ? 2
                                                             : 0;
    if (length == 0 || at + length > text.size()) return 0;
    unsigned code = lead & (0x7Fu >> length);
    for (std::size_t k = 1; k < length; ++k) {
        if ((byte(at + k) & 0xC0) != 0x80) return 0;
        code = (code << 6) | (byte(at + k) & 0x3F);
    }
    const unsigned smallest[] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < smallest[length] || code < 0xA0 || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
    return length;
}

std::string quoted(const std::string& text) {
    std::string out = "'";
    for (std::size_t k = 0; k < text.size();) {
        const char c = text[k];
        if (c >= 0x20 && c < 0x7F) {
            out += c == '\'' ? "''" : std::string(1, c);
            ++k;
        } else if (const std::size_t n = printableUtf8Length(text, k); n > 0) {
            out.append(text, k, n);
            k += n;
        } else {
            out += '?';
            ++k;
        }
    }
    return out + "'";
}

/// The script; gnuplot writes the figure to its standard output (no file name reaches it).
std::string script(const Figure& figure, const std::string& terminal) {
    std::ostringstream gp;
    const int height = figure.height > 0 ? figure.height : 380 * static_cast<int>(figure.panels.size()) + 60;
    gp << "set terminal " << terminal << " size " << figure.width << "," << height << "\n";
    gp << "set grid\nset key outside right top\nset tics nomirror\n";
    std::string number;
    for (std::size_t p = 0; p < figure.panels.size(); ++p) {
        for (std::size_t s = 0; s < figure.panels[p].series.size(); ++s) {
            const PlotSeries& series = figure.panels[p].series[s];
            gp << "$d" << p << "_" << s << " << EOD\n";
            for (std::size_t k = 0; k < series.x.size(); ++k) {
                number = text::format("%.10g %.10g", series.x[k], series.y[k]);
                gp << number;
                for (const std::vector<double>& column : series.extra) {
                    number = text::format(" %.10g", k < column.size() ? column[k] : 0.0);
                    gp << number;
                }
                gp << "\n";
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
        gp << (panel.equal_axes ? "set size ratio -1\n" : "set size noratio\n");
        gp << (panel.equal_axes || panel.key_below ? "set key below horizontal\n" : "set key outside right top\n");
        gp << "plot ";
        for (std::size_t s = 0; s < panel.series.size(); ++s) {
            gp << (s ? ", " : "") << "$d" << p << "_" << s << " using 1:2";
            for (std::size_t c = 0; c < panel.series[s].extra.size(); ++c) gp << ":" << c + 3;
            gp << " with " << panel.series[s].style << " title " << quoted(panel.series[s].label);
        }
        gp << "\n";
    }
    gp << "unset multiplot\n";
    return gp.str();
}

/// Runs `gnuplot -d` (no initialisation files) with the script on its standard input (an
/// anonymous memory file, never a path) and its standard output writing `out`.
void runGnuplot(const std::string& text, int out_fd, const std::string& out_path) {
    const int script_fd = memfd_create("nocdyn-figure.gp", MFD_CLOEXEC);
    if (script_fd < 0) throw Error(std::string("cannot hold the gnuplot script: ") + std::strerror(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{script_fd};
    for (std::size_t done = 0; done < text.size();) {
        const ssize_t n = ::write(script_fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw Error(std::string("cannot hold the gnuplot script: ") + std::strerror(errno));
        done += static_cast<std::size_t>(n);
    }
    if (::lseek(script_fd, 0, SEEK_SET) != 0) throw Error("cannot rewind the gnuplot script");

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, script_fd, STDIN_FILENO);
    posix_spawn_file_actions_adddup2(&actions, out_fd, STDOUT_FILENO);
    char program[] = "gnuplot";
    char defaults[] = "-d";
    char* argv[] = {program, defaults, nullptr};
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) {
        throw Error("cannot run gnuplot to draw figures: install it (apt-get install gnuplot-nox)");
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) throw Error("gnuplot failed on '" + out_path + "'");
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw Error("gnuplot failed on '" + out_path + "'");
}

}  // namespace

AxisUnit axisUnit(double peak, const std::string& base) {
    peak = std::abs(peak);
    if (!std::isfinite(peak) || peak >= 1.0) return {1.0, base};
    const bool metres = base == "m";
    const struct {
        double factor;
        const char* prefix;
    } prefixes[] = {{1e3, "m"}, {1e6, "{/Symbol m}"}, {1e9, "n"}};
    for (const auto& p : prefixes) {
        if (!metres && p.factor > 1e6) break;
        if (peak * p.factor >= 1.0) return {p.factor, std::string(p.prefix) + base};
    }
    if (peak == 0.0) return {1.0, base};
    const int exponent = static_cast<int>(std::floor(std::log10(peak)));
    return {std::pow(10.0, -exponent), "10^{" + std::to_string(exponent) + "} " + base};
}

std::string literalText(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (std::strchr("\\@_^{}&~", c) != nullptr && c != '\0') out += '\\';
        out += c;
    }
    return out;
}

void renderFigure(const Figure& figure, const std::string& stem) {
    renderFigureFiles(figure, stem + ".png", stem + ".svg");
}

std::string wellFormedSvg(std::string_view svg) {
    std::string out;
    out.reserve(svg.size());
    for (std::size_t k = 0; k < svg.size(); ++k) {
        const char c = svg[k];
        if (c == '&') {
            // an entity (&name; or &#digits;) stays; any other '&' is a character of text
            std::size_t e = k + 1;
            if (e < svg.size() && svg[e] == '#') ++e;
            while (e < svg.size() && e - k <= 12 && std::isalnum(static_cast<unsigned char>(svg[e])) != 0) ++e;
            const bool entity = e < svg.size() && svg[e] == ';' && e > k + 1;
            out += entity ? "&" : "&amp;";
        } else if (c == '>' && k >= 2 && svg[k - 1] == ']' && svg[k - 2] == ']') {
            out += "&gt;";
        } else {
            out += c;
        }
    }
    return out;
}

void renderFigureFiles(const Figure& figure, const std::string& png, const std::string& svg) {
    if (!png.empty()) {
        io::OutputFile out(png);
        runGnuplot(script(figure, "pngcairo enhanced font 'Sans,11'"), out.descriptor(), out.path());
        out.commit();
    }
    if (!svg.empty()) {
        // gnuplot writes into an anonymous memory file; its SVG is then made well-formed
        io::OutputFile out(svg);
        const int fd = memfd_create("nocdyn-figure.svg", MFD_CLOEXEC);
        if (fd < 0) throw Error(std::string("cannot hold the SVG figure: ") + std::strerror(errno));
        struct Closer {
            int fd;
            ~Closer() { ::close(fd); }
        } closer{fd};
        runGnuplot(script(figure, "svg enhanced dynamic font 'Sans,11'"), fd, out.path());
        std::string text;
        if (::lseek(fd, 0, SEEK_SET) != 0) throw Error("cannot read the SVG figure back");
        char buffer[65536];
        for (;;) {
            const ssize_t n = ::read(fd, buffer, sizeof buffer);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) throw Error(std::string("cannot read the SVG figure back: ") + std::strerror(errno));
            if (n == 0) break;
            text.append(buffer, static_cast<std::size_t>(n));
            if (text.size() > (std::size_t{256} << 20)) throw Error("the SVG figure is larger than 256 MiB");
        }
        out.write(wellFormedSvg(text));
        out.commit();
    }
}

}  // namespace nocdyn::render
