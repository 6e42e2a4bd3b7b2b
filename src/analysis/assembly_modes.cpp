// The real assembly modes of a 6-UPS robot by PHCpack's blackbox solver (assembly_modes.hpp):
// the system in Study's parameters written to a private temporary folder, `phc -b` run there
// with posix_spawn (no shell) under a time limit, its solution list read back, each real
// solution polished by Newton on the pose and checked by the inverse kinematics.
#include "nocdyn/analysis/assembly_modes.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <thread>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "nocdyn/error.hpp"

namespace nocdyn::spatial {

namespace {

namespace fs = std::filesystem;

constexpr int kUnknowns = 8;                          ///< e0..e3, g0..g3
constexpr std::uintmax_t kMaxFileBytes = 64u << 20u;  ///< phc's files are read up to this size
constexpr std::size_t kMaxLineChars = 4096;           ///< a longer line in a solution list is an error
constexpr long kMaxSolutions = 100000;                ///< a list announcing more is an error
constexpr double kPoseClosure = 1e-13;                ///< Newton's leg-length residual, relative to 1 + max L
constexpr double kSameMode = 1e-7;                    ///< two modes closer than this (m, rotation entries) are one
/// The names phc reads the unknowns by (e and i are taken by its numbers): e0..e3 as q0..q3.
constexpr std::array<const char*, kUnknowns> kNames = {"q0", "q1", "q2", "q3", "g0", "g1", "g2", "g3"};
/// The scaling hyperplane c . e = 1: fixed, generic (no rotation of interest has c . e = 0 but
/// by coincidence), with c . e = 1 at the identity.
constexpr std::array<double, 4> kScale = {1.0, 0.5413, -0.3271, 0.2719};

/// One leg: base point a (the U's), platform point b in the platform frame, length L.
struct Leg {
    Eigen::Vector3d a, b;
    double L = 0.0;
};

/// Left and right multiplication by a quaternion [w, x, y, z]: p q = L(p) q = R(q) p.
Eigen::Matrix4d leftProduct(double w, const Eigen::Vector3d& v) {
    Eigen::Matrix4d m;
    m << w, -v.x(), -v.y(), -v.z(), v.x(), w, -v.z(), v.y(), v.y(), v.z(), w, -v.x(), v.z(), -v.y(), v.x(), w;
    return m;
}
Eigen::Matrix4d rightProduct(double w, const Eigen::Vector3d& v) {
    Eigen::Matrix4d m;
    m << w, -v.x(), -v.y(), -v.z(), v.x(), w, v.z(), -v.y(), v.y(), -v.z(), w, v.x(), v.z(), v.y(), -v.x(), w;
    return m;
}

/// A number as phc reads it: the shortest decimal that reads back to the same double.
std::string number(double v) {
    std::array<char, 64> buffer{};
    const auto [end, ec] =
        std::to_chars(buffer.data(), buffer.data() + buffer.size(), v, std::chars_format::scientific);
    if (ec != std::errc()) throw Error("assembly modes: cannot write the number " + std::to_string(v));
    return std::string(buffer.data(), end);
}

/// The quadratic form x^T Q x (x = [e; g], Q symmetric) as a polynomial.
std::string quadratic(const Eigen::Matrix<double, 8, 8>& Q) {
    std::string out;
    for (int r = 0; r < kUnknowns; ++r) {
        for (int c = r; c < kUnknowns; ++c) {
            const double v = r == c ? Q(r, c) : 2.0 * Q(r, c);
            if (v == 0.0) continue;
            out += v < 0.0 ? " - " : " + ";
            out += number(std::abs(v));
            out += std::string("*") + kNames[static_cast<std::size_t>(r)] + "*" + kNames[static_cast<std::size_t>(c)];
        }
    }
    return out.empty() ? std::string(" 0") : out;
}

/// phc's input: leg i as |M_i e + 2 g|^2 - L_i^2 |e|^2 with M_i e = e b_i - a_i e, Study's
/// quadric e . g = 0 and the scaling c . e = 1.
std::string polynomialSystem(const std::array<Leg, 6>& legs) {
    // eight equations: six legs, Study's quadric, the scaling
    std::string text = "8\n";
    for (const Leg& leg : legs) {
        const Eigen::Matrix4d M = rightProduct(0.0, leg.b) - leftProduct(0.0, leg.a);
        Eigen::Matrix<double, 8, 8> Q = Eigen::Matrix<double, 8, 8>::Zero();
        Q.topLeftCorner<4, 4>() = M.transpose() * M - leg.L * leg.L * Eigen::Matrix4d::Identity();
        Q.bottomLeftCorner<4, 4>() = 2.0 * M;
        Q.topRightCorner<4, 4>() = 2.0 * M.transpose();
        Q.bottomRightCorner<4, 4>() = 4.0 * Eigen::Matrix4d::Identity();
        Q = (0.5 * (Q + Q.transpose())).eval();
        text += quadratic(Q) + ";\n";
    }
    text += " q0*g0 + q1*g1 + q2*g2 + q3*g3;\n";
    for (std::size_t k = 0; k < 4; ++k) {
        text += (kScale[k] < 0.0 ? " - " : " + ") + number(std::abs(kScale[k])) + "*" + kNames[k];
    }
    text += " - 1;\n";
    return text;
}

/// A private temporary folder, removed with everything in it when it goes.
class TemporaryFolder {
public:
    TemporaryFolder() {
        std::error_code ec;
        fs::path base = fs::temp_directory_path(ec);
        if (ec) base = "/tmp";
        std::string pattern = (base / "nocdyn-phc-XXXXXX").string();
        std::vector<char> buffer(pattern.begin(), pattern.end());
        buffer.push_back('\0');
        if (::mkdtemp(buffer.data()) == nullptr) {
            throw Error("assembly modes: cannot make a temporary folder in " + base.string() + ": " +
                        std::strerror(errno));
        }
        path_ = buffer.data();
    }
    ~TemporaryFolder() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    [[nodiscard]] const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

bool executableFile(const fs::path& p) {
    struct stat st {};
    return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0;
}

/// A file's text, refused past kMaxFileBytes.
std::string readBounded(const fs::path& p, const char* what) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(p, ec);
    if (ec) throw Error(std::string("assembly modes: phc wrote no ") + what + " (" + p.filename().string() + ")");
    if (size > kMaxFileBytes) {
        throw Error(std::string("assembly modes: phc's ") + what + " is larger than " +
                    std::to_string(kMaxFileBytes >> 20u) + " MB");
    }
    std::ifstream in(p, std::ios::binary);
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(size));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text;
}

/// The last non-empty line of phc's log, printable characters only, at most 200 of them.
std::string lastLine(const fs::path& log) {
    std::string text;
    try {
        text = readBounded(log, "log");
    } catch (const Error&) {
        return {};
    }
    std::istringstream in(text);
    std::string line, last;
    while (std::getline(in, line)) {
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    }
    std::string out;
    for (const char c : last) {
        if (out.size() >= 200) break;
        out += (c >= 32 && c < 127) ? c : '?';
    }
    return out;
}

/// Runs `phc -b [-t1] [-0seed] input output` in `folder`; its wall and CPU time into `result`.
void runPhc(const std::string& executable, const fs::path& folder, const HomotopyOptions& options,
            HomotopyModes& result) {
    std::vector<std::string> arguments = {executable, "-b"};
    if (options.polyhedral) arguments.emplace_back("-t1");
    if (options.seed != 0) arguments.push_back("-0" + std::to_string(options.seed));
    arguments.emplace_back("input");
    arguments.emplace_back("output");
    std::vector<char*> argv;
    argv.reserve(arguments.size() + 1);
    for (std::string& a : arguments) argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string log = (folder / "log").string();

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = -1;
    const auto start = std::chrono::steady_clock::now();
    const int spawned = ::posix_spawn(&pid, executable.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) {
        throw Error("assembly modes: cannot run " + executable + ": " + std::strerror(spawned));
    }
    const auto elapsed = [&]() {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    int status = 0;
    struct rusage usage {};
    for (;;) {
        const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
        if (done == pid) break;
        if (done < 0 && errno == EINTR) continue;
        if (done < 0) {  // SIGCHLD ignored by the host process: the child is reaped already
            status = 0;
            break;
        }
        if (elapsed() > options.timeout) {
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            std::ostringstream message;
            message << "assembly modes: phc did not finish within " << options.timeout << " s and was stopped";
            throw Error(message.str());
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    result.seconds = elapsed();
    result.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    if (WIFSIGNALED(status)) {
        throw Error("assembly modes: phc ended by signal " + std::to_string(WTERMSIG(status)));
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
        const std::string last = lastLine(folder / "log");
        throw Error("assembly modes: phc failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")" +
                    (last.empty() ? std::string() : ": " + last));
    }
}

std::string trim(const std::string& s) {
    const auto begin = s.find_first_not_of(" \t\r");
    if (begin == std::string::npos) return {};
    const auto end = s.find_last_not_of(" \t\r");
    return s.substr(begin, end - begin + 1);
}

std::optional<double> parseNumber(const std::string& text) {
    const std::string t = trim(text);
    if (t.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
    return v;
}

/// The lines of a text, each at most kMaxLineChars long (else an error naming `what`).
std::vector<std::string> lines(const std::string& text, const char* what) {
    std::vector<std::string> out;
    std::size_t begin = 0;
    while (begin < text.size()) {
        std::size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        out.push_back(text.substr(begin, std::min(end - begin, kMaxLineChars + 1)));
        if (out.back().size() > kMaxLineChars) {
            throw Error(std::string("assembly modes: phc's ") + what + ": line " + std::to_string(out.size()) +
                        " is longer than " + std::to_string(kMaxLineChars) + " characters");
        }
        begin = end + 1;
    }
    return out;
}

/// "N 8" after a "THE SOLUTIONS :" line: the count N.
std::optional<long> listHeader(const std::vector<std::string>& text, std::size_t& k) {
    while (k < text.size() && trim(text[k]).empty()) ++k;
    if (k >= text.size()) return std::nullopt;
    std::istringstream in(text[k]);
    long count = -1, dimension = -1;
    std::string rest;
    if (!(in >> count >> dimension) || (in >> rest) || count < 0 || count > kMaxSolutions || dimension != kUnknowns) {
        return std::nullopt;
    }
    ++k;
    return count;
}

using Solution = std::array<std::complex<double>, kUnknowns>;

/// The solution list phc appends to its input file: "THE SOLUTIONS :", "N 8", then N blocks
/// "solution k : ...", ..., "the solution for t :", eight lines "name : re im", "== err ...".
std::vector<Solution> parseSolutions(const std::string& input_text) {
    const std::vector<std::string> text = lines(input_text, "solution list");
    std::size_t k = 0;
    while (k < text.size() && trim(text[k]).rfind("THE SOLUTIONS", 0) != 0) ++k;
    if (k == text.size()) throw Error("assembly modes: phc wrote no solution list");
    ++k;
    const std::optional<long> count = listHeader(text, k);
    if (!count) throw Error("assembly modes: phc's solution list: unreadable count line " + std::to_string(k + 1));
    std::vector<Solution> solutions;
    while (k < text.size() && static_cast<long>(solutions.size()) < *count) {
        if (trim(text[k]) != "the solution for t :") {
            ++k;
            continue;
        }
        ++k;
        Solution s{};
        std::array<bool, kUnknowns> seen{};
        for (int v = 0; v < kUnknowns; ++v, ++k) {
            const std::string where = "phc's solution list: line " + std::to_string(k + 1);
            if (k >= text.size()) throw Error("assembly modes: " + where + ": the list ends in a solution");
            const std::string& line = text[k];
            const auto colon = line.find(':');
            if (colon == std::string::npos) throw Error("assembly modes: " + where + ": expected 'name : re im'");
            const std::string name = trim(line.substr(0, colon));
            const auto it = std::find_if(kNames.begin(), kNames.end(), [&](const char* n) { return name == n; });
            if (it == kNames.end()) {
                std::string message = "assembly modes: " + where + ": unknown variable '";
                message += name.substr(0, 40);
                message += "'";
                throw Error(message);
            }
            const auto index = static_cast<std::size_t>(it - kNames.begin());
            if (seen[index]) throw Error(("assembly modes: " + where + ": ").append(name).append(" given twice"));
            seen[index] = true;
            std::istringstream values(line.substr(colon + 1));
            std::string re, im, rest;
            if (!(values >> re >> im) || (values >> rest)) {
                throw Error("assembly modes: " + where + ": expected two numbers");
            }
            const std::optional<double> x = parseNumber(re), y = parseNumber(im);
            if (!x || !y) throw Error("assembly modes: " + where + ": a number phc wrote cannot be read");
            s[index] = {*x, *y};
        }
        solutions.push_back(s);
    }
    if (static_cast<long>(solutions.size()) != *count) {
        throw Error("assembly modes: phc's solution list announces " + std::to_string(*count) + " solutions and has " +
                    std::to_string(solutions.size()));
    }
    return solutions;
}

/// The paths phc tracked: the mixed volume for the polyhedral homotopy ("mixed volume : N"),
/// else the count of the last "THE SOLUTIONS :" list of its output file (every path's end).
int trackedPaths(const std::string& output_text, bool polyhedral) {
    const std::vector<std::string> text = lines(output_text, "output");
    int paths = 0;
    for (std::size_t k = 0; k < text.size(); ++k) {
        if (polyhedral) {
            const std::string line = trim(text[k]);
            if (line.rfind("mixed volume :", 0) != 0) continue;
            const std::optional<double> count = parseNumber(line.substr(14));
            if (count && *count >= 0.0 && *count <= kMaxSolutions) paths = static_cast<int>(*count);
            continue;
        }
        if (trim(text[k]).rfind("THE SOLUTIONS", 0) != 0) continue;
        std::size_t next = k + 1;
        if (const std::optional<long> count = listHeader(text, next)) paths = static_cast<int>(*count);
    }
    return paths;
}

/// Newton on the pose (p, R) for |p + R b_i - a_i| = L_i: row i of the Jacobian [n_i; (R b_i) x n_i]
/// over (dp, dw), R <- exp(dw) R. False when it does not converge.
bool polish(const std::array<Leg, 6>& legs, Eigen::Vector3d& p, Eigen::Matrix3d& R) {
    double scale = 1.0;
    for (const Leg& leg : legs) scale = std::max(scale, 1.0 + leg.L);
    for (int iteration = 0; iteration < 40; ++iteration) {
        Eigen::Matrix<double, 6, 6> J;
        Eigen::Matrix<double, 6, 1> f;
        for (int i = 0; i < 6; ++i) {
            const Leg& leg = legs[static_cast<std::size_t>(i)];
            const Eigen::Vector3d Rb = R * leg.b, v = p + Rb - leg.a;
            const double length = v.norm();
            if (!(length > 0.0)) return false;
            const Eigen::Vector3d n = v / length;
            f(i) = length - leg.L;
            J.row(i) << n.transpose(), Rb.cross(n).transpose();
        }
        const double residual = f.cwiseAbs().maxCoeff();
        if (!std::isfinite(residual)) return false;
        const Eigen::Matrix<double, 6, 1> step = Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>>(J).solve(-f);
        if (!step.allFinite()) return residual <= kPoseClosure * scale;
        p += step.head<3>();
        const Eigen::Vector3d w = step.tail<3>();
        if (w.norm() > 0.0) R = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * R;
        if (residual <= kPoseClosure * scale && step.cwiseAbs().maxCoeff() <= 1e-12 * scale) return true;
    }
    // the last residual
    double residual = 0.0;
    for (const Leg& leg : legs) residual = std::max(residual, std::abs((p + R * leg.b - leg.a).norm() - leg.L));
    return residual <= kPoseClosure * scale;
}

Eigen::Matrix3d axisRotation(const Eigen::Vector3d& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

double wrap(double angle) { return std::atan2(std::sin(angle), std::cos(angle)); }

/// The joint variables of a U-P-S limb that put its S point at s with the platform turned by
/// D_R from home, the P at u: the U's second angle from a1 . Rot(a2, t2) w = a1 . (s - a) (w the
/// leg at home with the P at u; of its two roots the nearer to 0), its first turning Rot(a2,
/// t2) w onto s - a about a1, the S's angles from Rx Ry Rz = (R_U)^T D_R. False when the U
/// cannot point the leg there.
bool seedLimb(const Limb& limb, const Eigen::Vector3d& s, const Eigen::Matrix3d& D_R, double u, FreedomVector& q) {
    const Freedom &f1 = limb.freedoms[0], &f2 = limb.freedoms[1], &fp = limb.freedoms[2], &fs = limb.freedoms[3];
    const Eigen::Vector3d a1 = f1.axis, a2 = f2.axis;
    const Eigen::Vector3d w = fs.point - f1.point + u * fp.axis, v = s - f1.point;
    const double P = a1.dot(w) - a2.dot(w) * a1.dot(a2), Qs = a1.dot(a2.cross(w)), C = a2.dot(w) * a1.dot(a2);
    const double T = a1.dot(v) - C, rho = std::hypot(P, Qs);
    const double tolerance = 1e-9 * (1.0 + w.norm());
    double t2 = 0.0;
    if (rho > tolerance) {
        const double c = T / rho;
        if (std::abs(c) > 1.0 + 1e-9) return false;
        const double phase = std::atan2(Qs, P), spread = std::acos(std::clamp(c, -1.0, 1.0));
        const double r1 = wrap(phase + spread), r2 = wrap(phase - spread);
        t2 = std::abs(r1) <= std::abs(r2) ? r1 : r2;
    } else if (std::abs(T) > tolerance) {
        return false;
    }
    const Eigen::Vector3d x = axisRotation(a2, t2) * w;
    const Eigen::Vector3d x_n = x - a1 * a1.dot(x), v_n = v - a1 * a1.dot(v);
    const double t1 = std::atan2(a1.dot(x_n.cross(v_n)), x_n.dot(v_n));
    const Eigen::Matrix3d M = (axisRotation(a1, t1) * axisRotation(a2, t2)).transpose() * D_R;
    q.resize(6);
    q << t1, t2, u, std::atan2(-M(1, 2), M(2, 2)), std::atan2(M(0, 2), std::hypot(M(1, 2), M(2, 2))),
        std::atan2(-M(0, 1), M(0, 0));
    return true;
}

}  // namespace

std::string findPhc(const std::string& executable) {
    if (!executable.empty()) return executableFile(executable) ? executable : std::string();
    const char* path = std::getenv("PATH");
    if (path == nullptr) return {};
    std::string folders(path);
    std::size_t begin = 0;
    while (begin <= folders.size()) {
        std::size_t end = folders.find(':', begin);
        if (end == std::string::npos) end = folders.size();
        const std::string folder = folders.substr(begin, end - begin);
        if (!folder.empty()) {
            const fs::path candidate = fs::path(folder) / "phc";
            if (executableFile(candidate)) return candidate.string();
        }
        begin = end + 1;
    }
    return {};
}

bool isUpsHexapod(const Model& model, std::string* reason) {
    const auto refuse = [&](const std::string& why) {
        if (reason != nullptr) *reason = why;
        return false;
    };
    if (model.task_dimension != 6) return refuse("the platform does not have motion full");
    if (model.limbs() != 6) return refuse(std::to_string(model.limbs()) + " limbs, not 6");
    if (model.actuators != 6) return refuse(std::to_string(model.actuators) + " actuators, not 6");
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const std::string name = "limb " + std::to_string(j + 1) + " (" + limb.name + ")";
        const auto& f = limb.freedoms;
        const bool ups = limb.size() == 6 && f[0].revolute && f[1].revolute && f[0].joint == f[1].joint &&
                         !f[2].revolute && f[2].joint == f[0].joint + 1 && f[2].actuator >= 0 && f[3].revolute &&
                         f[4].revolute && f[5].revolute && f[3].joint == f[2].joint + 1 && f[4].joint == f[3].joint &&
                         f[5].joint == f[3].joint && f[0].actuator < 0 && f[1].actuator < 0 && f[3].actuator < 0 &&
                         f[4].actuator < 0 && f[5].actuator < 0;
        if (!ups) return refuse(name + " is not a U, an actuated P and an S");
    }
    return true;
}

HomotopyModes homotopyModes(const Model& model, const ActuatorVector& u, const HomotopyOptions& options) {
    std::string reason;
    if (!isUpsHexapod(model, &reason)) {
        throw Error("assembly modes: " + model.name + " is not a 6-UPS robot (a U at the base, the actuated P, an S " +
                    "at the platform in each of six limbs): " + reason);
    }
    if (u.size() != model.actuators) {
        throw Error("assembly modes: " + std::to_string(u.size()) + " actuator values for " +
                    std::to_string(model.actuators) + " actuators");
    }
    if (!u.allFinite()) throw Error("assembly modes: an actuator value is not finite");
    if (!(options.timeout > 0.0) || !(options.imaginary_tolerance > 0.0) || !(options.u_tolerance > 0.0)) {
        throw Error("assembly modes: the timeout and tolerances must be positive");
    }
    // the legs: a the U point, b the S point in the platform frame, L = |r + u d| (r the leg at home)
    std::array<Leg, 6> legs;
    const Eigen::Vector3d p_home = model.home.head<3>();
    for (int a = 0; a < model.actuators; ++a) {
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a)];
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        Leg& leg = legs[static_cast<std::size_t>(j)];
        leg.a = limb.freedoms[0].point;
        leg.b = model.home_rotation.transpose() * (limb.freedoms[3].point - p_home);
        leg.L = (limb.freedoms[3].point - leg.a + u(a) * limb.freedoms[static_cast<std::size_t>(k)].axis).norm();
        if (!(leg.L > 1e-9)) {
            throw Error("assembly modes: limb " + std::to_string(j + 1) + " (" + limb.name +
                        ") has length 0 at u = " + number(u(a)));
        }
        // the equations hold L^2 |e|^2 and their squares stay finite
        if (!std::isfinite(leg.L * leg.L * leg.L * leg.L)) {
            throw Error("assembly modes: limb " + std::to_string(j + 1) + " (" + limb.name +
                        ") is too long at u = " + number(u(a)));
        }
    }

    HomotopyModes result;
    result.executable = findPhc(options.executable);
    if (result.executable.empty()) {
        throw Error(options.executable.empty()
                        ? std::string("assembly modes need PHCpack's phc on PATH (Debian package phcpack: "
                                      "apt-get install phcpack)")
                        : "assembly modes: " + options.executable + " is not an executable file (PHCpack's phc, " +
                              "Debian package phcpack)");
    }
    std::vector<Solution> solutions;
    {
        const TemporaryFolder folder;
        {
            std::ofstream input(folder.path() / "input", std::ios::binary);
            input << polynomialSystem(legs);
            if (!input.flush()) throw Error("assembly modes: cannot write phc's input in " + folder.path().string());
        }
        runPhc(result.executable, folder.path(), options, result);
        solutions = parseSolutions(readBounded(folder.path() / "input", "solution list"));
        result.paths = trackedPaths(readBounded(folder.path() / "output", "output"), options.polyhedral);
    }
    result.solutions = static_cast<int>(solutions.size());

    // the verification model: the modes near a singularity are modes too
    Model check = model;
    check.max_condition = std::numeric_limits<double>::infinity();
    Data data(check);
    for (const Solution& s : solutions) {
        bool real = true;
        for (const std::complex<double>& z : s)
            real = real && std::abs(z.imag()) <= options.imaginary_tolerance * (1.0 + std::abs(z.real()));
        if (!real) continue;
        ++result.real_solutions;
        // R from e, the position t = 2 g e* / |e|^2
        const Eigen::Quaterniond e(s[0].real(), s[1].real(), s[2].real(), s[3].real());
        const Eigen::Quaterniond g(s[4].real(), s[5].real(), s[6].real(), s[7].real());
        const double norm = e.squaredNorm();
        if (!(norm > 0.0)) {
            ++result.rejected;
            continue;
        }
        Eigen::Matrix3d R = e.normalized().toRotationMatrix();
        Eigen::Vector3d p = 2.0 * (g * e.conjugate()).vec() / norm;
        if (!polish(legs, p, R)) {
            ++result.rejected;
            continue;
        }
        // R = Rz(yaw) Ry(pitch) Rx(roll); pitch = +-90 degrees is no pose of the file's kind
        const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
        if (!(std::abs(std::cos(pitch)) > 1e-9)) {
            ++result.rejected;
            continue;
        }
        TaskVector pose(6);
        pose << p, std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0));
        const Eigen::Matrix3d D_R = rotation(pose(3), pose(4), pose(5)) * model.home_rotation.transpose();
        bool seeded = true;
        for (int j = 0; j < 6 && seeded; ++j) {
            const auto a = static_cast<std::size_t>(std::find_if(model.actuator.begin(), model.actuator.end(),
                                                                 [&](const auto& x) { return x.first == j; }) -
                                                    model.actuator.begin());
            const Leg& leg = legs[static_cast<std::size_t>(j)];
            LimbData& ld = data.limb[static_cast<std::size_t>(j)];
            seeded =
                seedLimb(model.limb[static_cast<std::size_t>(j)], p + R * leg.b, D_R, u(static_cast<int>(a)), ld.q);
            ld.closed = seeded;
        }
        if (!seeded || !inverseKinematics(check, data, pose)) {
            ++result.rejected;
            continue;
        }
        const double u_error = (data.u - u).cwiseAbs().maxCoeff();
        if (!(u_error <= options.u_tolerance)) {
            ++result.rejected;
            continue;
        }
        const bool known = std::any_of(result.modes.begin(), result.modes.end(), [&](const HomotopyMode& m) {
            const Eigen::Matrix3d R_m = rotation(m.pose(3), m.pose(4), m.pose(5));
            return (m.pose.head<3>() - p).cwiseAbs().maxCoeff() <= kSameMode * (1.0 + p.norm()) &&
                   (R_m - R).cwiseAbs().maxCoeff() <= kSameMode;
        });
        if (!known) {
            conditionNumbers(check, data);
            result.modes.push_back({pose, u_error, data.actuation_condition});
        }
    }
    // nearest to home first: position distance plus the rotation angle from home
    const auto distance = [&](const HomotopyMode& m) {
        const Eigen::Matrix3d turn = rotation(m.pose(3), m.pose(4), m.pose(5)) * model.home_rotation.transpose();
        return (m.pose.head<3>() - p_home).norm() + Eigen::AngleAxisd(turn).angle();
    };
    std::sort(result.modes.begin(), result.modes.end(),
              [&](const HomotopyMode& x, const HomotopyMode& y) { return distance(x) < distance(y); });
    return result;
}

}  // namespace nocdyn::spatial
