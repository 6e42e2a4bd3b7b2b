#include "app/shake_spatial_payload.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <nlohmann/json.hpp>

#include "nocdyn/text.hpp"

namespace nocdyn::app {

// this file's helpers under their own name (the folder compiles as unity files)
namespace spatial_specimen {

constexpr double kForceNoiseShare = 1e-4;   ///< of the largest effort limit: a load cell's 0.01 % FS
constexpr double kForceNoiseDefault = 1.0;  ///< [N] when no actuator has an effort limit

double forceNoise(const spatial::Model& model) {
    double largest = 0.0;
    for (const auto& [j, k] : model.actuator) {
        const double effort =
            model.limb[static_cast<std::size_t>(j)].freedoms[static_cast<std::size_t>(k)].limits.effort;
        if (std::isfinite(effort)) largest = std::max(largest, effort);
    }
    return largest > 0.0 ? kForceNoiseShare * largest : kForceNoiseDefault;
}

nlohmann::json matrix(const Eigen::Matrix3d& m) {
    return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
}

nlohmann::json vector(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace spatial_specimen

using spatial_specimen::matrix;
using spatial_specimen::vector;

SpatialSpecimen identifySpatialSpecimen(const SpatialRobotDescription& description, const spatial::Model& plant,
                                        const ShakeOptions& options, const spatial::LoopOptions& loop) {
    const auto start = std::chrono::steady_clock::now();
    const spatial::Model alone(description);
    spatial::PayloadExcitationOptions o;
    o.duration = options.excitation_duration;
    o.margin = options.margin;
    o.loop = loop;  // the replay's controller rate, error dynamics, hold and integration
    o.seed = options.seed;
    o.force_noise = spatial_specimen::forceNoise(alone);
    SpatialSpecimen out;
    out.truth.mass = options.payload_mass;
    out.duration = o.duration;
    out.force_noise = o.force_noise;
    // the excitation fitted with the specimen as weighed on the platform
    const spatial::Trajectory excitation = spatial::payloadExcitation(plant, o, &out.excitation_use);
    out.estimate = spatial::identifySpatialPayload(alone, spatial::excitePayload(plant, alone, excitation, o));
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

std::string withPayloadJson(const std::string& metrics_json, const SpatialSpecimen& specimen) {
    nlohmann::json json = nlohmann::json::parse(metrics_json);
    const spatial::SpatialPayloadEstimate& e = specimen.estimate;
    const spatial::PayloadVector truth = spatial::payloadParameters(specimen.truth);
    nlohmann::json names = nlohmann::json::array(), pi = nlohmann::json::array(), sd = nlohmann::json::array(),
                   pi_true = nlohmann::json::array();
    for (int i = 0; i < spatial::kPayloadParameters; ++i) {
        names.push_back(spatial::payloadParameterNames()[static_cast<std::size_t>(i)]);
        pi.push_back(e.parameters(i));
        sd.push_back(e.parameters_sd(i));
        pi_true.push_back(truth(i));
    }
    json["payload_estimate"] = {{"mass", e.payload.mass},
                                {"mass_sd", e.mass_sd},
                                {"com", vector(e.payload.com)},
                                {"com_sd", vector(e.com_sd)},
                                {"inertia", matrix(e.payload.inertia)},  // about its c.o.m., platform frame
                                {"inertia_sd", matrix(e.inertia_sd)},
                                {"parameter_names", names},
                                {"parameters", pi},
                                {"parameters_sd", sd},
                                {"true",
                                 {{"mass", specimen.truth.mass},
                                  {"com", vector(specimen.truth.com)},
                                  {"inertia", matrix(specimen.truth.inertia)},
                                  {"parameters", pi_true}}},
                                {"samples", e.samples},
                                {"force_noise", specimen.force_noise},
                                {"residual_rms", e.residual_rms},
                                {"condition", e.condition},
                                {"excitation_duration", specimen.duration},
                                {"excitation_limit_use",
                                 {{"ratio", specimen.excitation_use.ratio},
                                  {"what", specimen.excitation_use.what},
                                  {"t", specimen.excitation_use.t}}},
                                {"seconds", specimen.seconds}};
    return json.dump(2) + "\n";
}

std::string payloadSummary(const SpatialSpecimen& specimen) {
    const spatial::SpatialPayloadEstimate& e = specimen.estimate;
    const spatial::SpatialPayload& t = specimen.truth;
    std::string text = text::format(
        "specimen identified first (%.3g s of multi-sine excitation in six axes, %d samples, force noise %.3g N, "
        "worst limit use %.1f %% (%s), in %.3g s): m = %.5g +- %.2g kg (true %.5g)\n",
        specimen.duration, e.samples, specimen.force_noise, 100.0 * specimen.excitation_use.ratio,
        specimen.excitation_use.what.c_str(), specimen.seconds, e.payload.mass, e.mass_sd, t.mass);
    text += "  c.o.m. [m, platform frame]:";
    for (int i = 0; i < 3; ++i)
        text +=
            text::format(" %.4g +- %.2g (true %.4g)%s", e.payload.com(i), e.com_sd(i), t.com(i), i < 2 ? "," : "\n");
    text += "  inertia about the c.o.m. [kg m^2]:";
    const int rows[] = {0, 1, 2, 0, 0, 1}, cols[] = {0, 1, 2, 1, 2, 2};
    const char* names[] = {"xx", "yy", "zz", "xy", "xz", "yz"};
    for (int i = 0; i < 6; ++i) {
        text += text::format(" I_%s %.4g +- %.2g (true %.4g)%s", names[i], e.payload.inertia(rows[i], cols[i]),
                             e.inertia_sd(rows[i], cols[i]), t.inertia(rows[i], cols[i]), i < 5 ? "," : "\n");
    }
    text += "  the replay's controller model carries the specimen as identified\n";
    return text;
}

}  // namespace nocdyn::app
