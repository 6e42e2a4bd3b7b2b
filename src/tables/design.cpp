// Families of robots for design sweeps, the designs table and its journal (io/design.hpp).
#include "nocdyn/tables/design.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "../io/file_util.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::tables {

// the io layer's tables, files and quoting, below this one
using io::columnNames;
using io::LayoutSizes;
using io::Parameter;
using io::ParameterSet;
using io::parseRobotDescription;
using io::robotFileParameters;
using io::TableId;
using io::writeTextFile;

namespace {

std::string number(double value) {
    if (std::isnan(value)) return {};
    return text::shortest(value);
}

/// A CSV field: quoted (quotes doubled) when it holds a comma, quote or line break.
std::string field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"') out += '"';
        out += (c == '\r' || c == '\n') ? ' ' : c;
    }
    return out + "\"";
}

/// Splits one CSV line (quoted fields as `field` writes them); false when malformed.
bool splitLine(const std::string& line, std::vector<std::string>& fields) {
    fields.clear();
    std::string current;
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                current += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                current += c;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            fields.push_back(current);
            current.clear();
        } else {
            current += c;
        }
    }
    fields.push_back(current);
    return !quoted;
}

ParameterSet overridesOf(const DesignFamily& family, const std::vector<double>& point) {
    ParameterSet set = family.fixed;
    for (std::size_t k = 0; k < family.ranges.size(); ++k) set.push_back({family.ranges[k].name, point.at(k)});
    return set;
}

std::string header(const std::vector<std::string>& columns) {
    std::string line;
    for (const std::string& c : columns) {
        if (!line.empty()) line += ',';
        line += field(c);
    }
    return line + "\n";
}

}  // namespace

void checkDesignFamily(const DesignFamily& family) {
    const ParameterSet declared = robotFileParameters(family.text, family.source, family.fixed);
    for (const DesignRange& r : family.ranges) {
        bool found = false;
        for (const Parameter& p : declared) found = found || p.name == r.name;
        if (!found) {
            std::string list;
            for (const Parameter& p : declared) list += (list.empty() ? "" : ", ") + p.name;
            throw Error(family.source + ": varied parameter '" + r.name +
                        "' is not declared (parameters: " + (list.empty() ? std::string("none") : list) + ")");
        }
    }
}

RobotDescription designRobot(const DesignFamily& family, const std::vector<double>& point) {
    return parseRobotDescription(family.text, family.source, overridesOf(family, point));
}

DesignEvaluation evaluateFamilyDesign(const DesignFamily& family, const std::vector<double>& point,
                                      const std::vector<DesignMetric>& metrics, const DesignOptions& options) {
    RobotDescription robot;
    try {
        robot = designRobot(family, point);
    } catch (const Error& e) {
        DesignEvaluation result;
        result.values.assign(metrics.size(), std::nan(""));
        result.reason = e.what();
        return result;
    }
    return evaluateDesign(robot, metrics, options);
}

std::vector<std::string> designColumns(const std::vector<DesignRange>& ranges,
                                       const std::vector<DesignMetric>& metrics) {
    LayoutSizes sizes;
    for (const DesignRange& r : ranges) sizes.parameters.push_back(r.name);
    for (const DesignMetric& m : metrics) sizes.metrics.push_back(m.name());
    return columnNames(TableId::design, sizes);
}

std::string designCsvRow(const DesignRecord& record) {
    // designs numbered from 1 where a person reads them (record.index is 0-based)
    std::string line = std::to_string(record.index + 1);
    for (const double v : record.point) line.append(",").append(number(v));
    for (const double v : record.evaluation.values) line.append(",").append(number(v));
    line += record.evaluation.feasible ? ",true," : ",false,";
    line += field(record.evaluation.reason);
    return line + "\n";
}

void writeDesignTable(const std::string& path, const std::vector<std::string>& columns,
                      const std::vector<DesignRecord>& records) {
    std::string text = header(columns);
    for (const DesignRecord& r : records) text += designCsvRow(r);
    writeTextFile(path, text);
}

std::string fingerprint(const std::string& text) {
    std::uint64_t h = 14695981039346656037ULL;
    for (const char c : text) {
        h ^= static_cast<unsigned char>(c);
        h *= 1099511628211ULL;
    }
    return text::format("%016llx", static_cast<unsigned long long>(h));
}

DesignJournal::DesignJournal(const std::string& path, const std::string& signature,
                             const std::vector<std::string>& columns, std::size_t parameters, std::size_t metrics)
    : path_(path) {
    const std::string first = "# nocdyn design journal " + signature + "\n";
    std::string kept = first + header(columns);
    if (std::filesystem::exists(path)) {
        const std::string text = io::detail::readRegularFile(path, "design journal", std::size_t{1} << 30);
        if (text.compare(0, kept.size(), kept) != 0) {
            throw Error(path +
                        ": a journal of another sweep (robot file, ranges, metrics or options differ); "
                        "remove it or choose another output directory");
        }
        std::size_t at = kept.size();
        std::vector<std::string> fields;
        const std::size_t width = 1 + parameters + metrics + 2;
        while (at < text.size()) {
            const std::size_t end = text.find('\n', at);
            if (end == std::string::npos) break;  // an unfinished last line: evaluated again
            const std::string line = text.substr(at, end - at);
            at = end + 1;
            if (!splitLine(line, fields) || fields.size() != width) break;
            DesignRecord r;
            bool ok = true;
            const auto value = [&](const std::string& s) {
                if (s.empty()) return std::nan("");
                const auto v = io::detail::parseDecimal(s);
                ok = ok && v.has_value();
                return v.value_or(0.0);
            };
            const double number = value(fields[0]);  // from 1, as designs.csv
            if (!(number >= 1.0)) break;
            r.index = static_cast<std::size_t>(number) - 1;
            for (std::size_t k = 0; k < parameters; ++k) r.point.push_back(value(fields[1 + k]));
            for (std::size_t k = 0; k < metrics; ++k) r.evaluation.values.push_back(value(fields[1 + parameters + k]));
            r.evaluation.feasible = fields[1 + parameters + metrics] == "true";
            r.evaluation.reason = fields.back();
            if (!ok) break;
            previous_.push_back(std::move(r));
            kept += line + "\n";
        }
    }
    // the kept lines through a temporary file renamed into place, then appended to
    writeTextFile(path, kept);
    out_.open(path, std::ios::app | std::ios::binary);
    if (!out_) throw Error("cannot append to the design journal '" + path + "'");
}

void DesignJournal::append(const DesignRecord& record) {
    out_ << designCsvRow(record);
    out_.flush();
    if (!out_) throw Error("cannot append to the design journal '" + path_ + "'");
}

}  // namespace nocdyn::tables
