// `loads` of a spatial robot (loads_spatial.hpp).
#include "app/loads_spatial.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "app/inverse_dynamics_spatial.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/printable.hpp"
#include "nocdyn/spatial_reactions.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

/// The table's words for a joint's type, its code the index.
constexpr std::array<char, 4> kSpatialJointTypes{'R', 'P', 'U', 'S'};

double spatialTypeCode(char type) {
    const auto* at = std::find(kSpatialJointTypes.begin(), kSpatialJointTypes.end(), type);
    return static_cast<double>(at - kSpatialJointTypes.begin());
}

io::Table spatialLoadsTable(const spatial::Model& model, const SpatialLoadsResult& r) {
    io::Table t;
    t.columns = {"limb", "joint", "type", "peak_force", "peak_force_t"};
    for (const std::string& c : model.coordinates()) t.columns.push_back("peak_force_" + c);
    t.columns.insert(t.columns.end(), {"rms_force", "peak_moment", "peak_moment_t"});
    t.categories.assign(t.columns.size(), {});
    for (const char type : kSpatialJointTypes) t.categories[2].emplace_back(1, type);
    for (std::size_t j = 0; j < r.joint.size(); ++j) {
        for (std::size_t k = 0; k < r.joint[j].size(); ++k) {
            const SpatialJointLoad& l = r.joint[j][k];
            std::vector<double> row{static_cast<double>(j + 1), static_cast<double>(k + 1), spatialTypeCode(l.type),
                                    l.peak_force, l.peak_force_t};
            row.insert(row.end(), l.peak_force_pose.begin(), l.peak_force_pose.end());
            row.insert(row.end(), {l.rmsForce(), l.peak_moment, l.peak_moment_t});
            t.rows.push_back(std::move(row));
        }
    }
    return t;
}

std::string spatialJointName(const SpatialLoadsResult& r, std::size_t j, std::size_t k) {
    // a limb's name from the file, its control bytes escaped: it cannot drive the terminal
    return "limb " + std::to_string(j + 1) + " (" + text::printable(r.limb_names[j]) + ") joint " +
           std::to_string(k + 1);
}

std::string spatialLoadsText(const SpatialLoadsResult& r) {
    std::string text = text::format("%-28s %4s  %12s  %8s  %11s  %14s  %8s\n", "joint", "type", "peak |f| [N]",
                                    "at t [s]", "RMS |f| [N]", "peak |m| [N m]", "at t [s]");
    for (std::size_t j = 0; j < r.joint.size(); ++j) {
        for (std::size_t k = 0; k < r.joint[j].size(); ++k) {
            const SpatialJointLoad& l = r.joint[j][k];
            text += text::format("%-28s %4c  %12.4g  %8.4f  %11.4g  %14.4g  %8.4f\n", spatialJointName(r, j, k).c_str(),
                                 l.type, l.peak_force, l.peak_force_t, l.rmsForce(), l.peak_moment, l.peak_moment_t);
        }
    }
    const auto wj = static_cast<std::size_t>(r.worst_limb - 1), wk = static_cast<std::size_t>(r.worst_joint - 1);
    const SpatialJointLoad& w = r.joint[wj][wk];
    text += text::format("largest: %s (%c), %.4g N at t = %.4f s\n", spatialJointName(r, wj, wk).c_str(), w.type,
                         w.peak_force, w.peak_force_t);
    return text;
}

}  // namespace

double SpatialJointLoad::rmsForce() const {
    return samples > 0 ? std::sqrt(sum_squared_force / static_cast<double>(samples)) : 0.0;
}

SpatialLoadsResult runSpatialLoads(const spatial::Model& model, const spatial::Trajectory& trajectory,
                                   const SamplingOptions& sampling, Observer& observer) {
    SpatialLoadsResult out;
    spatial::Reactions reactions(model);
    for (int j = 0; j < model.limbs(); ++j) {
        const auto jj = static_cast<std::size_t>(j);
        out.limb_names.push_back(model.limb[jj].name);
        out.joint.emplace_back(reactions.joint[jj].size());
        for (SpatialJointLoad& l : out.joint.back()) l.peak_force_pose.assign(model.coordinates().size(), 0.0);
    }
    const InverseDynamicsResult run =
        streamSpatialTrajectory(model, trajectory, sampling, false, observer, {}, [&](const SpatialSample& s) {
            if (const Status status = spatial::jointReactions(model, s.data, reactions); !status) {
                throw Error(text::sampleTime(s.t) + ": " + spatial::describe(status, model));
            }
            for (std::size_t j = 0; j < out.joint.size(); ++j) {
                for (std::size_t k = 0; k < out.joint[j].size(); ++k) {
                    const spatial::JointReaction& r = reactions.joint[j][k];
                    SpatialJointLoad& l = out.joint[j][k];
                    const double f = r.force.norm(), m = r.moment.norm();
                    l.type = r.type;
                    if (l.samples == 0 || f > l.peak_force) {
                        l.peak_force = f;
                        l.peak_force_t = s.t;
                        for (std::size_t i = 0; i < l.peak_force_pose.size(); ++i)
                            l.peak_force_pose[i] = s.p(static_cast<Eigen::Index>(i));
                    }
                    if (l.samples == 0 || m > l.peak_moment) {
                        l.peak_moment = m;
                        l.peak_moment_t = s.t;
                    }
                    l.sum_squared_force += f * f;
                    ++l.samples;
                }
            }
        });
    out.samples = run.samples;
    // the worst joint: where the largest peak force of any joint occurs (the first in file order)
    double worst = -1.0;
    for (std::size_t j = 0; j < out.joint.size(); ++j) {
        for (std::size_t k = 0; k < out.joint[j].size(); ++k) {
            if (out.joint[j][k].peak_force > worst) {
                worst = out.joint[j][k].peak_force;
                out.worst_limb = static_cast<int>(j) + 1;
                out.worst_joint = static_cast<int>(k) + 1;
            }
        }
    }
    out.table = spatialLoadsTable(model, out);
    out.text = spatialLoadsText(out);
    return out;
}

LoadsResult runSpatialLoads(const LoadsOptions& options, Observer& observer) {
    if (options.envelope) {
        throw OptionError("envelope",
                          "is for planar robots only: a spatial robot (space: spatial) takes a trajectory file keyed "
                          "x, y, z (and roll, pitch, yaw)");
    }
    validate(options);
    const spatial::Model model(io::loadSpatialRobotDescription(options.robot.path, options.robot.set));
    const spatial::Trajectory trajectory = spatialTrajectoryOf(options, model.task_dimension);
    SpatialLoadsResult spatial = runSpatialLoads(model, trajectory, options, observer);
    LoadsResult out;
    out.worst_limb = spatial.worst_limb;
    out.worst_joint = spatial.worst_joint;
    out.table = std::move(spatial.table);
    out.text = std::move(spatial.text);
    return out;
}

}  // namespace nocdyn::app
