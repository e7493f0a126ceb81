#pragma once
// replay_pipeline --deviations: each wall as built against the plan under the final merge
// (merging::ClassifyWalls, issue 21) and each door or opening present or closed
// (merging::ClassifyDoorways), as JSON for scripts/deviation_report.py (make report).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/merging/doorway_status.h"
#include "is_graphs/merging/wall_deviations.h"
#include "is_graphs/pipeline/localization_pipeline.h"

namespace is_graphs {
namespace bag_replay {

/// Writes `path` (through a temporary file: never half-written). False, with a message, when
/// the run never localized (nothing to place the S-Graph in the BIM with) or the file fails.
inline bool WriteDeviations(const std::string& path, const agraph::AGraph& building,
                            const sgraph::SGraph& graph,
                            const pipeline::LocalizationPipeline& localization) {
  if (!localization.localized()) {
    std::cerr
        << "replay_pipeline: not localized at the end of the bag: no deviations to report "
           "(the S-Graph was never placed in the BIM; is it the right building and storey?)\n";
    return false;
  }
  const merging::WallDeviationConfig config;
  const auto walls = merging::ClassifyWalls(building, graph, localization.bim_T_map(), config);
  nlohmann::json out;
  out["building"] = building.building;
  out["config"] = {{"planned_offset", config.planned_offset},
                   {"planned_angle_deg", config.planned_angle_deg}};
  out["bim_x_map"] = {geometry::ToXYYaw(localization.bim_T_map()).x(),
                      geometry::ToXYYaw(localization.bim_T_map()).y(),
                      geometry::ToXYYaw(localization.bim_T_map()).z()};
  nlohmann::json list = nlohmann::json::array();
  int unnamed = 0;
  for (const auto& w : walls) {
    unnamed += w.wall_id >= 0 && w.guid.empty();
    list.push_back({{"wall_id", w.wall_id},
                    {"guid", w.guid},
                    {"name", w.name},
                    {"status", merging::ToString(w.status)},
                    {"offset_m", w.offset},
                    {"angle_deg", w.angle * 180.0 / M_PI},
                    {"sigma_m", w.sigma},
                    {"start", {w.start.x(), w.start.y()}},
                    {"end", {w.end.x(), w.end.y()}},
                    {"normal", {w.normal.x(), w.normal.y()}},
                    {"length_m", (w.end - w.start).norm()},
                    {"s_planes", w.s_planes},
                    {"rays_through", w.rays_through},
                    {"height_m", w.height}});
  }
  if (unnamed > 0)
    std::cerr << "replay_pipeline: warning: " << unnamed
              << " walls have no IFC GlobalId: reported by A-Graph wall id\n";
  out["walls"] = list;
  nlohmann::json doors = nlohmann::json::array();
  for (const auto& d : merging::ClassifyDoorways(building, graph, localization.bim_T_map(), config,
                                                 merging::DoorwayDeviationConfig{}))
    doors.push_back({{"doorway_id", d.doorway_id},
                     {"guid", d.guid},
                     {"name", d.name},
                     {"kind", agraph::ToString(d.kind)},
                     {"wall_id", d.wall_id},
                     {"status", merging::ToString(d.status)},
                     {"position", {d.position.x(), d.position.y()}},
                     {"width_m", d.width},
                     {"walked_through", d.walked_through},
                     {"rays_through", d.rays_through},
                     {"blocked_views", d.blocked_views},
                     {"s_doorways", d.s_doorways},
                     {"s_planes", d.s_planes}});
  out["doorways"] = doors;
  nlohmann::json keyframes = nlohmann::json::array();
  for (const auto& k : graph.keyframes) {
    const Eigen::Vector3d p = localization.bim_T_map() * k.pose.translation();
    keyframes.push_back({k.stamp, p.x(), p.y()});
  }
  out["path"] = keyframes;  // the keyframes in B under the final merge: stamp, x, y
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    f << out.dump(2) << "\n";
    if (!f) {
      std::cerr << "replay_pipeline: cannot write " << tmp << "\n";
      return false;
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::cerr << "replay_pipeline: cannot write " << path << "\n";
    return false;
  }
  return true;
}

}  // namespace bag_replay
}  // namespace is_graphs
