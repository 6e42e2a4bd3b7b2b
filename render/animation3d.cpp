// The 3-D animation page of a spatial robot (animation3d.hpp).
#include "render/animation3d.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"
#include "render/page_data.hpp"

namespace nocdyn::render {

// The page around its data (render/animation3d.html with three.js, its OrbitControls and
// render/animation3d.js in its scripts), embedded at build time (render/CMakeLists.txt): the
// page is kPage3dHead, the data's JSON, kPage3dTail.
extern const char* const kPage3dHead;
extern const char* const kPage3dTail;

namespace {

/// The listed joints of a limb drawn as its chain: every R, U and S joint (a P joint has no
/// point of its own: it slides along the segment between its neighbours), base to platform.
std::vector<int> drawnJoints(const spatial::Limb& limb) {
    std::vector<int> joints;
    if (limb.freedoms.empty()) return joints;
    const int listed = limb.freedoms.back().joint + 1;
    for (int j = 0; j < listed; ++j) {
        int freedoms = 0;
        bool prismatic = false;
        for (const spatial::Freedom& f : limb.freedoms) {
            if (f.joint != j) continue;
            ++freedoms;
            prismatic = prismatic || !f.revolute;
        }
        if (!(freedoms == 1 && prismatic)) joints.push_back(j);
    }
    return joints;
}

/// Appends a point in micrometres: integers keep the page small and exact to well under a pixel.
void appendMicrometres(const Eigen::Vector3d& x, std::vector<long long>& out) {
    for (int i = 0; i < 3; ++i) out.push_back(std::llround(x(i) * 1e6));
}

/// One frame's points: per limb its drawn joints, then the platform point.
void appendFrame(const spatial::Data& data, const std::vector<std::vector<int>>& chains, std::vector<long long>& out) {
    for (std::size_t j = 0; j < chains.size(); ++j) {
        for (const int joint : chains[j]) {
            appendMicrometres(data.limb[j].joint_point[static_cast<std::size_t>(joint)], out);
        }
    }
    appendMicrometres(data.position, out);
}

}  // namespace

std::string spatialAnimationPage(const spatial::Model& model, const SpatialMotionSamples& motion,
                                 const AnimationOptions& options) {
    const std::size_t N = motion.t.size();
    if (N == 0 || motion.p.size() != N) throw Error("no samples to animate");
    const int n = motion.actuators;
    const auto nn = static_cast<std::size_t>(n);
    const double t_end = motion.t.back();
    const double duration = N > 1 ? t_end - motion.t.front() : 0.0;
    double slow = options.slow_motion;
    if (!(slow > 0.0)) slow = std::max(1.0, std::round(10.0 / std::max(duration, 1e-9)));

    std::vector<std::vector<int>> chains;
    for (const spatial::Limb& limb : model.limb) chains.push_back(drawnJoints(limb));

    // frames: evenly spread samples, the first and the last included
    const std::size_t F = std::min(N, kMaxAnimationFrames);
    spatial::Data data(model);
    std::vector<long long> points;
    std::vector<double> frame_t, frame_tau;
    for (std::size_t i = 0; i < F; ++i) {
        const std::size_t k = F > 1 ? (i * (N - 1) + (F - 1) / 2) / (F - 1) : 0;
        if (const Status status = spatial::inverseKinematics(model, data, motion.p[k]); !status) {
            throw Error(motion.source + ": " + text::sampleTime(motion.t[k]) + ": " + spatial::describe(status, model));
        }
        appendFrame(data, chains, points);
        frame_t.push_back(motion.t[k]);
        for (std::size_t a = 0; a < nn; ++a) frame_tau.push_back(motion.tau[k * nn + a]);
    }
    const std::size_t stride = points.size() / F;

    // the mean pose: the centre of the magnified displacements (the first frame if out of reach)
    spatial::TaskVector mean = spatial::TaskVector::Zero(motion.p.front().size());
    for (const spatial::TaskVector& p : motion.p) mean += p / static_cast<double>(N);
    std::vector<long long> reference;
    if (spatial::inverseKinematics(model, data, mean)) {
        appendFrame(data, chains, reference);
    } else {
        reference.assign(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(stride));
        (void)spatial::inverseKinematics(model, data, motion.p.front());
    }
    // the platform polygon: its joints in the order of their angle about the platform point,
    // in the platform's own frame (data holds a pose of the motion)
    std::vector<int> around(model.limb.size());
    std::iota(around.begin(), around.end(), 0);
    std::vector<double> angle(model.limb.size(), 0.0);
    for (std::size_t j = 0; j < chains.size(); ++j) {
        if (chains[j].empty()) continue;
        const Eigen::Vector3d local =
            data.R.transpose() * (data.limb[j].joint_point[static_cast<std::size_t>(chains[j].back())] - data.position);
        angle[j] = std::atan2(local.y(), local.x());
    }
    std::stable_sort(around.begin(), around.end(), [&](int a, int b) {
        return angle[static_cast<std::size_t>(a)] < angle[static_cast<std::size_t>(b)];
    });

    std::vector<double> peak_tau;
    const std::string plots = detail::plotsJson(motion.t, motion.u, motion.tau, n, peak_tau);

    // what comes from files (names) goes through nlohmann::json, then scriptSafe
    nlohmann::json meta;
    meta["robot"] = model.name;
    meta["source"] = motion.source;
    meta["samples"] = N;
    meta["duration"] = duration;
    meta["tEnd"] = t_end;
    meta["slowMotion"] = slow;
    meta["magnify"] = options.magnify;
    meta["warnings"] = motion.warnings;
    meta["translation"] = model.task_dimension == 3;
    nlohmann::json limbs = nlohmann::json::array(), actuators = nlohmann::json::array();
    std::size_t offset = 0;
    for (std::size_t j = 0; j < chains.size(); ++j) {
        const spatial::Limb& limb = model.limb[j];
        std::string letters;
        for (const int joint : chains[j]) {
            const auto freedoms = std::count_if(limb.freedoms.begin(), limb.freedoms.end(),
                                                [&](const spatial::Freedom& f) { return f.joint == joint; });
            letters += freedoms == 3 ? 'S' : freedoms == 2 ? 'U' : 'R';
        }
        int actuator = -1;
        for (const spatial::Freedom& f : limb.freedoms) {
            if (f.actuator >= 0) {
                actuator = f.actuator;
                break;
            }
        }
        limbs.push_back({{"name", limb.name}, {"at", offset}, {"joints", letters}, {"actuator", actuator}});
        offset += 3 * chains[j].size();
    }
    for (int a = 0; a < n; ++a) {
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a)];
        const spatial::Freedom& f = model.limb[static_cast<std::size_t>(j)].freedoms[static_cast<std::size_t>(k)];
        nlohmann::json entry = {{"limb", model.limb[static_cast<std::size_t>(j)].name},
                                {"unit", f.revolute ? "rad" : "m"},
                                {"forceUnit", f.revolute ? "N m" : "N"},
                                {"peakTau", peak_tau[static_cast<std::size_t>(a)]}};
        entry["effort"] = std::isfinite(f.limits.effort) ? nlohmann::json(f.limits.effort) : nlohmann::json(nullptr);
        actuators.push_back(entry);
    }
    meta["limbs"] = limbs;
    meta["around"] = around;
    meta["actuators"] = actuators;
    meta["stride"] = stride;

    std::string json =
        detail::scriptSafe(meta.dump(-1, ' ', /*ensure_ascii=*/true, nlohmann::json::error_handler_t::replace));
    json.pop_back();  // the closing brace: the numeric arrays follow
    json += ",\"reference\":";
    detail::appendArray(json, reference, 0);
    json += ",\"frames\":{\"t\":";
    detail::appendArray(json, frame_t, 17);
    json += ",\"points\":";
    detail::appendArray(json, points, 0);
    json += ",\"tau\":";
    detail::appendArray(json, frame_tau, 17);
    json += "},\"plots\":";
    json += plots;
    json += '}';
    std::string page = kPage3dHead;
    page += json;
    page += kPage3dTail;
    return page;
}

}  // namespace nocdyn::render
