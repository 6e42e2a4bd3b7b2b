// `envelope` of a spatial robot (envelope.hpp, spatial_envelope.hpp).
#include <cstddef>
#include <numbers>
#include <string>

#include "app/envelope.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

/// The points as the envelope's table (io::TableId::envelope, without first_natural_frequency).
io::Table spatialEnvelopeTable(const std::vector<spatial::EnvelopePoint>& points,
                               const std::vector<std::string>& coordinates) {
    io::Table table;
    // axis and limit as words: the pose coordinates, and EnvelopeLimit in order
    table.categories = {coordinates, {}, {}, {"range", "velocity", "effort", "workspace", "none", "resonance"}};
    table.columns = io::columnNames(io::TableId::envelope, {.optional = false});
    for (const spatial::EnvelopePoint& p : points) {
        table.rows.push_back({static_cast<double>(p.axis), p.frequency, p.amplitude, static_cast<double>(p.limit),
                              static_cast<double>(p.limb + 1), static_cast<double>(p.joint + 1),
                              static_cast<double>(p.actuator + 1), p.kinematic_amplitude, p.peak_effort_ratio, p.peak_u,
                              p.peak_tau});
    }
    return table;
}

}  // namespace

EnvelopeResult runSpatialEnvelope(const EnvelopeOptions& options, Observer& observer) {
    if (options.amplification != kDefaultAmplification) {
        throw OptionError("amplification",
                          "applies to planar robots only (a spatial robot file declares no compliance, so the "
                          "envelope has no resonance bound)");
    }
    const spatial::Model model(io::loadSpatialRobotDescription(options.robot.path, options.robot.set));
    const nocdyn::EnvelopeOptions envelope = libraryEnvelopeOptions(options, observer);
    EnvelopeResult out;
    out.robot = model.name;
    out.coordinates = model.coordinates();
    out.spatial_points = spatial::operatingEnvelope(model, envelope);
    out.table = spatialEnvelopeTable(out.spatial_points, out.coordinates);
    out.resonance.task_dimension = model.task_dimension;
    out.resonance.reason = "a spatial robot file declares no compliance";
    out.summary = "third bound (first natural frequency): unknown, " + out.resonance.reason;
    return out;
}

std::string spatialEnvelopeText(const EnvelopeResult& result) {
    std::string text = "axis   f [Hz]    amplitude        limit      peak |tau|/effort  where\n";
    for (const spatial::EnvelopePoint& p : result.spatial_points) {
        const bool angle = p.axis >= 3;
        std::string where = "-";
        if (p.actuator >= 0) {
            where = text::format("actuator %d (limb %d, joint %d)", p.actuator + 1, p.limb + 1, p.joint + 1);
        } else if (p.limb >= 0) {
            where = p.joint >= 0 ? text::format("limb %d, joint %d (passive)", p.limb + 1, p.joint + 1)
                                 : text::format("limb %d", p.limb + 1);
        }
        text += text::format("%-5s  %8.3f  %10.5g %-4s  %-9s  %8.3f           %s\n",
                             result.coordinates[static_cast<std::size_t>(p.axis)].c_str(), p.frequency,
                             angle ? p.amplitude * 180.0 / std::numbers::pi : p.amplitude * 1e3, angle ? "deg" : "mm",
                             limitName(p.limit), p.peak_effort_ratio, where.c_str());
    }
    return text;
}

}  // namespace nocdyn::app
