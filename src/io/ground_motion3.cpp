// Three-component ground-motion records (see ground_motion3.hpp).
#include "nocdyn/io/ground_motion3.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <utility>

#include "file_util.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::io {

namespace {

std::string upperCase(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

std::string_view trimmed(std::string_view text) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())) != 0) text.remove_prefix(1);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())) != 0) text.remove_suffix(1);
    return text;
}

bool endsWith(const std::string& text, std::string_view tail) {
    return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

std::string fileName(const std::string& path) { return std::filesystem::path(path).filename().string(); }

/// Two azimuths [deg] 90 degrees apart (mod 180), to a millionth of a degree.
bool orthogonal(double a, double b) {
    const double d = std::fmod(std::abs(a - b), 180.0);
    return std::abs(d - 90.0) <= 1e-6;
}

/// cos and sin of an angle in degrees, exact at the multiples of 90 degrees (an azimuth of 180
/// and one of 270 put each component on one table axis, with no 6e-17 of the other).
std::pair<double, double> cosSinDegrees(double degrees) {
    const double turn = std::fmod(degrees, 360.0);
    const double quarter = turn / 90.0;
    if (quarter == std::round(quarter)) {
        switch ((static_cast<int>(std::round(quarter)) + 4) % 4) {
            case 0:
                return {1.0, 0.0};
            case 1:
                return {0.0, 1.0};
            case 2:
                return {-1.0, 0.0};
            default:
                return {0.0, -1.0};
        }
    }
    const double radians = turn * std::numbers::pi / 180.0;
    return {std::cos(radians), std::sin(radians)};
}

}  // namespace

double TableMotion::duration() const { return ax.empty() ? 0.0 : dt * static_cast<double>(ax.size() - 1); }

std::optional<ComponentDirection> componentDirection(std::string_view event_line) {
    const std::size_t comma = event_line.rfind(',');
    std::string_view last = trimmed(comma == std::string_view::npos ? event_line : event_line.substr(comma + 1));
    // the older files' station note after it: "090 (CDMG STATION 89509)"
    if (const std::size_t open = last.find('('); open != std::string_view::npos && last.back() == ')')
        last = trimmed(last.substr(0, open));
    const std::string field = upperCase(last);
    if (field == "UP") return ComponentDirection{true, 0.0, 1.0};
    if (field == "DWN" || field == "DOWN") return ComponentDirection{true, 0.0, -1.0};
    // an azimuth: digits only ("90", "090", "360"), as the database writes it
    if (field.empty() || field.size() > 3 || !std::all_of(field.begin(), field.end(), [](char c) {
            return std::isdigit(static_cast<unsigned char>(c)) != 0;
        }))
        return std::nullopt;
    const auto azimuth = detail::parseDecimal(field);
    if (!azimuth || *azimuth > 360.0) return std::nullopt;
    return ComponentDirection{false, *azimuth, 1.0};
}

TableMotion combineComponents(const std::vector<GroundMotionRecord>& components, std::optional<double> x_azimuth) {
    struct Found {
        const GroundMotionRecord* record;
        ComponentDirection direction;
    };
    std::vector<Found> horizontal;
    std::optional<Found> vertical;
    for (const GroundMotionRecord& c : components) {
        const std::optional<ComponentDirection> direction = componentDirection(c.event);
        if (!direction) {
            throw Error(c.source + ":2: the component's orientation is not at the end of the line ('" +
                        terminalText(std::string_view(c.event).substr(0, 80)) +
                        "'): expected an azimuth 0-360 [deg], UP or DWN after the last comma");
        }
        if (direction->vertical) {
            if (vertical) {
                throw Error(c.source + ": a second vertical component (" + vertical->record->source +
                            " is one): a record has one");
            }
            vertical = Found{&c, *direction};
        } else {
            horizontal.push_back({&c, *direction});
        }
    }
    if (horizontal.size() != 2) {
        std::string names;
        for (const Found& h : horizontal) names += (names.empty() ? "" : ", ") + h.record->source;
        throw Error("a three-component record needs two horizontal components, found " +
                    std::to_string(horizontal.size()) + (names.empty() ? std::string() : " (" + names + ")"));
    }
    // the first horizontal: the smaller azimuth as written (180 before 270, 090 before 360)
    std::sort(horizontal.begin(), horizontal.end(),
              [](const Found& a, const Found& b) { return a.direction.azimuth < b.direction.azimuth; });
    const Found& h1 = horizontal[0];
    const Found& h2 = horizontal[1];
    if (!orthogonal(h1.direction.azimuth, h2.direction.azimuth)) {
        throw Error(h2.record->source + ": azimuth " + text::shortest(h2.direction.azimuth) +
                    " is not at 90 degrees from " + h1.record->source + "'s " + text::shortest(h1.direction.azimuth) +
                    ": the horizontal components must be orthogonal");
    }
    TableMotion out;
    out.dt = h1.record->dt;
    std::vector<const Found*> all = {&h1, &h2};
    if (vertical) all.push_back(&*vertical);
    std::size_t n = 0;
    for (const Found* f : all) {
        if (f->record->dt != out.dt) {
            throw Error(f->record->source + ": time step " + text::shortest(f->record->dt) + " s differs from " +
                        h1.record->source + "'s " + text::shortest(out.dt) + " s");
        }
        out.sources.push_back(f->record->source);
        n = std::max(n, f->record->acceleration.size());
    }
    for (const Found* f : all) {
        const std::size_t m = f->record->acceleration.size();
        if (m < n) {
            out.notes.push_back(fileName(f->record->source) + " has " + std::to_string(m) + " samples, the longest " +
                                std::to_string(n) + ": padded with zeros after " +
                                text::shortest(out.dt * static_cast<double>(m - 1)) + " s");
        }
    }
    out.x_azimuth = x_azimuth.value_or(h1.direction.azimuth);
    if (!std::isfinite(out.x_azimuth) || out.x_azimuth < -360.0 || out.x_azimuth > 360.0) {
        throw Error("x azimuth " + text::shortest(out.x_azimuth) + ": expected degrees from -360 to 360");
    }
    const auto at = [](const Found& f, std::size_t k) {
        const std::vector<double>& a = f.record->acceleration;
        return k < a.size() ? a[k] : 0.0;
    };
    // a_x = a_1 cos(alpha_1 - beta_x) + ..., a_y = a_1 sin(beta_x - alpha_1) + ...
    const auto [c1, s1] = cosSinDegrees(out.x_azimuth - h1.direction.azimuth);
    const auto [c2, s2] = cosSinDegrees(out.x_azimuth - h2.direction.azimuth);
    out.ax.resize(n);
    out.ay.resize(n);
    out.az.assign(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
        const double a1 = at(h1, k);
        const double a2 = at(h2, k);
        out.ax[k] = a1 * c1 + a2 * c2;
        out.ay[k] = a1 * s1 + a2 * s2;
        if (vertical) out.az[k] = vertical->direction.sign * at(*vertical, k);
    }
    out.has_vertical = vertical.has_value();
    out.name = componentGroup(h1.record->source);
    return out;
}

std::string componentGroup(const std::string& path) {
    std::string stem = std::filesystem::path(path).stem().string();
    const std::string up = upperCase(stem);
    // a trailing -hor1, -hor2, -ver (the repository's labels), then the orientation
    std::size_t end = up.size();
    for (const std::string_view label : {"-HOR1", "-HOR2", "_HOR1", "_HOR2", "-VER", "_VER"}) {
        if (endsWith(up.substr(0, end), label)) {
            end -= label.size();
            break;
        }
    }
    bool stripped = false;
    for (const std::string_view word : {"UP", "DWN", "DOWN"}) {
        if (endsWith(up.substr(0, end), word)) {
            end -= word.size();
            stripped = true;
            break;
        }
    }
    if (!stripped) {
        std::size_t digits = 0;
        while (digits < 3 && digits < end && std::isdigit(static_cast<unsigned char>(up[end - 1 - digits])) != 0)
            ++digits;
        end -= digits;
    }
    if (end > 0 && (up[end - 1] == '-' || up[end - 1] == '_')) --end;
    return end == 0 ? stem : stem.substr(0, end);
}

std::vector<std::pair<std::string, std::vector<std::string>>> groupComponents(const std::vector<std::string>& paths) {
    std::map<std::string, std::vector<std::string>> groups;
    for (const std::string& p : paths) groups[componentGroup(p)].push_back(p);
    std::vector<std::pair<std::string, std::vector<std::string>>> out;
    out.reserve(groups.size());
    for (auto& [name, files] : groups) {
        std::sort(files.begin(), files.end());
        out.emplace_back(name, std::move(files));
    }
    return out;
}

}  // namespace nocdyn::io
