#include "app/shake_records.hpp"

#include <algorithm>
#include <filesystem>
#include <map>

#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/ground_motion3.hpp"

namespace nocdyn::app {

std::vector<RecordFiles> groupRecordFiles(const std::vector<std::string>& files) {
    // the files of each shared name, in the order first met
    std::vector<std::string> names;
    std::map<std::string, std::vector<std::string>> members;
    for (const std::string& f : files) {
        const std::string name = io::componentGroup(f);
        if (members.find(name) == members.end()) names.push_back(name);
        members[name].push_back(f);
    }
    std::vector<RecordFiles> out;
    out.reserve(files.size());
    for (const std::string& name : names) {
        const std::vector<std::string>& group = members[name];
        bool components = group.size() == 2 || group.size() == 3;
        for (std::size_t i = 0; components && i < group.size(); ++i)
            components = io::componentDirection(io::readAt2File(group[i]).event).has_value();
        if (components) {
            out.push_back({name, group});
        } else {
            for (const std::string& f : group) out.push_back({f, {f}});
        }
    }
    return out;
}

GroundRecord readComponents(const RecordFiles& record, double window, std::vector<std::string>& notes,
                            std::optional<double> x_azimuth) {
    std::vector<io::GroundMotionRecord> components;
    components.reserve(record.files.size());
    for (const std::string& f : record.files) components.push_back(io::readAt2File(f));
    io::TableMotion motion = io::combineComponents(components, x_azimuth);
    for (std::string& note : motion.notes) notes.push_back(record.label + ": " + note);
    if (motion.has_vertical) {
        notes.push_back(record.label + ": " + std::filesystem::path(motion.sources.back()).filename().string() +
                        ": the vertical component is not replayed (a planar table moves in x and y)");
    }
    GroundRecord out;
    out.dt = motion.dt;
    out.ax = std::move(motion.ax);
    out.ay = std::move(motion.ay);
    if (window > 0.0) {
        const std::size_t n = std::min(out.ax.size(), static_cast<std::size_t>(window / out.dt) + 1);
        out.ax.resize(n);
        out.ay.resize(n);
    }
    const auto still = [](const std::vector<double>& a) {
        return std::all_of(a.begin(), a.end(), [](double v) { return v == 0.0; });
    };
    if (still(out.ax) && still(out.ay)) {
        throw Error(record.label + ": every horizontal acceleration" + (window > 0.0 ? " of the window" : "") +
                    " is zero: no ground motion to replay");
    }
    return out;
}

}  // namespace nocdyn::app
