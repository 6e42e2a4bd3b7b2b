#include "app/shake_records.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>

#include "app/options.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/ground_motion3.hpp"

namespace nocdyn::app {

/// The records named: files, and the *.AT2 files of folders (sorted by name).
std::vector<std::string> expandRecords(const std::vector<std::string>& names) {
    std::vector<std::string> out;
    for (const std::string& name : names) {
        std::error_code error;
        if (!std::filesystem::is_directory(name, error)) {
            out.push_back(name);
            continue;
        }
        std::vector<std::string> found;
        for (const auto& entry : std::filesystem::directory_iterator(name, error)) {
            std::string ext = entry.path().extension().string();
            for (char& c : ext) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
            if (entry.is_regular_file() && ext == ".AT2") found.push_back(entry.path().string());
        }
        if (error) throw OptionError("record", name + ": cannot list the folder: " + error.message());
        if (found.empty()) throw OptionError("record", name + ": the folder holds no .AT2 file");
        std::sort(found.begin(), found.end());
        out.insert(out.end(), found.begin(), found.end());
    }
    return out;
}

/// One folder name per record, safe and unique: the record's stem with every character but
/// letters, digits, '-' and '_' replaced by '_' (no separator, no "." or ".." and no hidden
/// folder), "record" when nothing is left, and "-2", "-3", ... after a name already taken
/// ignoring case (quake.AT2 and quake.at2 must not share a folder on any file system).
std::vector<std::string> recordFolders(const std::vector<RecordFiles>& records) {
    std::vector<std::string> out, taken;
    const auto lower = [](std::string text) {
        for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return text;
    };
    for (const RecordFiles& record : records) {
        // a file's stem; the shared name of a record's components as it is
        std::string name =
            record.files.size() == 1 ? std::filesystem::path(record.label).stem().string() : record.label;
        bool any = false;
        for (char& c : name) {
            const bool plain = std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_';
            if (!plain) c = '_';
            any = any || std::isalnum(static_cast<unsigned char>(c)) != 0;
        }
        if (!any) name = "record";
        if (name.size() > 100) name.resize(100);
        std::string chosen = name;
        for (int k = 2; std::find(taken.begin(), taken.end(), lower(chosen)) != taken.end(); ++k)
            chosen = name + "-" + std::to_string(k);
        taken.push_back(lower(chosen));
        out.push_back(chosen);
    }
    return out;
}

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
