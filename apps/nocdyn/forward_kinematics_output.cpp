#include "forward_kinematics_output.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <numbers>

#include "nocdyn/io/escape.hpp"

namespace nocdyn::cli {

void printSpatialForwardKinematics(const app::SpatialForwardKinematicsResult& r, bool json) {
    if (json) {
        nlohmann::json out;
        out["robot"] = r.robot;
        out["u"] = r.u;
        out["within_limits"] = r.outside == 0;
        out["method"] = r.method;
        out["complete"] = r.complete;
        out["starts"] = r.starts;
        out["solutions_found"] = r.solutions.size();
        nlohmann::json list = nlohmann::json::array();
        for (const app::SpatialForwardKinematicsSolution& s : r.solutions) {
            nlohmann::json pose = nlohmann::json::object();
            for (std::size_t i = 0; i < r.coordinates.size(); ++i) pose[r.coordinates[i]] = s.pose[i];
            list.push_back({{"pose", pose},
                            {"working", s.working},
                            {"home_branches", s.home_branches},
                            {"u_error", s.u_error},
                            {"condition", s.condition}});
        }
        out["solutions"] = list;
        std::cout << out.dump(2) << "\n";
        return;
    }
    std::printf("robot %s (spatial), u =", io::terminalText(r.robot).c_str());
    for (std::size_t a = 0; a < r.u.size(); ++a) {
        std::printf("%s %+.9g %s", a == 0 ? " [" : ",", r.u[a], r.revolute[a] ? "rad" : "m");
    }
    std::printf(r.outside > 0 ? "] (u%d beyond its joint's range)\n" : "]\n", r.outside);
    if (r.complete) {
        std::printf("real solutions: %zu (%s: every assembly mode)\n", r.solutions.size(), r.method.c_str());
    } else {
        std::printf("real solutions found: %zu (%s from %d seeds: there may be others)\n", r.solutions.size(),
                    r.method.c_str(), r.starts);
    }
    int index = 0;
    for (const app::SpatialForwardKinematicsSolution& s : r.solutions) {
        std::printf("%d.", ++index);
        for (std::size_t i = 0; i < r.coordinates.size(); ++i) {
            if (i < 3) {
                std::printf("%s %s = %+.9f mm", i ? "," : "", r.coordinates[i].c_str(), s.pose[i] * 1e3);
            } else {
                std::printf(", %s = %+.9f deg", r.coordinates[i].c_str(), s.pose[i] * 180.0 / std::numbers::pi);
            }
        }
        std::printf("%s\n", s.working ? "  [working mode]" : (s.home_branches ? "" : "  [not on the home branches]"));
        std::printf("   u recomputed from the pose within %.1e, condition %.3g\n", s.u_error, s.condition);
    }
    if (std::none_of(r.solutions.begin(), r.solutions.end(), [](const auto& s) { return s.working; })) {
        std::printf("no working mode: none of these has every limb on its home branch\n");
    }
}

}  // namespace nocdyn::cli
