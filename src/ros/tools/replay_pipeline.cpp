// replay_pipeline: the whole localization (S-Graph, matcher, merger) on a scenario bag, from the
// core, synchronously and without ROS transport: deterministic and as fast as the machine goes.
// Prints the match and merge events, the time and distance to localize, the per-stage latency,
// the real-time factor and the peak RSS; writes the BIM-frame poses and the ground truth as TUM
// files and a JSON summary (scripts/evaluate.py, `make evaluate`, and debugging read them), with
// the evaluation's measures: every UNIQUE match against the true B_x_M, the map cloud against
// the BIM (replay_evaluation.h).
//
//   replay_pipeline BAG --building FILE.ifc|.agraph.json [--storey S] [--duration S]
//                   [--out-prefix PREFIX]   (writes PREFIX.pose_bim.tum, PREFIX.truth.tum,
//                                            PREFIX.odom.tum: odom <- base_link,
//                                            PREFIX.sgraph.tum: the final keyframes, map <- base,
//                                            PREFIX.sgraph_online.tum: map <- odom <- base at
//                                            each odometry reading, as sgraph_node's tf gives,
//                                            PREFIX.json)
//                   [--explain]  (the S-rooms against the BIM under the true motion)
//                   [--scan-search]  (the matcher's scan search on: scan_proposals)
//                   [--cloud-layout auto|velodyne|ouster|hesai|robosense|xyzi]  (as
//                                 sgraph_node's cloud_layout; default auto)
//                   [--hint T,X,Y,YAW_DEG,SIGMA_XY,SIGMA_YAW_DEG]  (a pose hint, as rviz's
//                                 "2D Pose Estimate": the robot at (X, Y, YAW) in bim, T s after
//                                 the bag's first message; docs/localization_services.md)
//                   [--deviations FILE.json]  (issue 21: each wall as built against the plan
//                                 under the final merge, deviation_report.h; exit 3 and no file
//                                 when the bag never localized)
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/PointCloud2.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "../lidar_conversions.h"
#include "../pose_conversions.h"
#include "bag_replay.h"
#include "deviation_report.h"
#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/agraph/ifc_conversion.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/pipeline/localization_pipeline.h"
#include "match_explanation.h"
#include "replay_evaluation.h"

namespace {

using namespace is_graphs;
using bag_replay::Percentile;
using bag_replay::WriteTum;

int Usage() {
  std::cerr
      << "usage: replay_pipeline BAG --building FILE [--storey S] [--duration S] "
         "[--out-prefix PREFIX] [--explain] [--scan-search] [--cloud-layout L] [--deviations FILE] "
         "[--hint T,X,Y,YAW_DEG,SIGMA_XY,SIGMA_YAW_DEG]\n";
  return 2;
}

nlohmann::json Stats(const std::vector<double>& v) {
  return {{"count", v.size()},
          {"median_ms", Percentile(v, 0.5)},
          {"p99_ms", Percentile(v, 0.99)},
          {"max_ms", Percentile(v, 1.0)}};
}

/// --hint T,X,Y,YAW_DEG,SIGMA_XY,SIGMA_YAW_DEG: (T, hint) or false when malformed.
bool ParseHint(const std::string& text, double* t, matching::PoseHint* hint) {
  std::vector<double> v;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    try {
      size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) return false;
    } catch (const std::exception&) {
      return false;
    }
  }
  if (v.size() != 6) return false;
  constexpr double kDeg = M_PI / 180.0;
  *t = v[0];
  hint->bim_T_base = {v[3] * kDeg, Eigen::Vector2d(v[1], v[2])};
  hint->covariance =
      Eigen::Vector3d(v[4] * v[4], v[4] * v[4], v[5] * kDeg * v[5] * kDeg).asDiagonal();
  hint->description = "--hint " + text;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return Usage();
  std::string bag_path = argv[1], building_path, storey, prefix, deviations_path;
  double max_duration = -1.0;
  bool explain = false, scan_search = false;
  std::optional<double> hint_at;  // s after the first message
  matching::PoseHint hint;
  ros_conversions::LidarCloudConfig cloud_config;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--explain") {
      explain = true;
      continue;
    }
    if (a == "--scan-search") {  // the matcher's scan_proposals on (experimental)
      scan_search = true;
      continue;
    }
    if (i + 1 >= argc) return Usage();
    if (a == "--building")
      building_path = argv[++i];
    else if (a == "--storey")
      storey = argv[++i];
    else if (a == "--duration")
      max_duration = std::stod(argv[++i]);
    else if (a == "--out-prefix")
      prefix = argv[++i];
    else if (a == "--hint") {
      double at = 0.0;
      if (!ParseHint(argv[++i], &at, &hint)) {
        std::cerr << "replay_pipeline: --hint must be T,X,Y,YAW_DEG,SIGMA_XY,SIGMA_YAW_DEG\n";
        return 2;
      }
      hint_at = at;
    } else if (a == "--deviations")
      deviations_path = argv[++i];
    else if (a == "--cloud-layout") {
      if (!bag_replay::ParseCloudLayout(argv[++i], &cloud_config)) {
        std::cerr << "replay_pipeline: --cloud-layout must be one of "
                  << ros_conversions::CloudLayoutChoices() << "\n";
        return 2;
      }
    } else
      return Usage();
  }
  if (building_path.empty()) return Usage();
  pipeline::PipelineConfig config;
  config.matcher.scan_proposals = scan_search;
  if (const auto e = config.Validate(); !e.empty()) {
    std::cerr << "replay_pipeline: " << e << "\n";
    return 2;
  }
  auto loaded = agraph::LoadBim(building_path);
  if (!loaded.ok()) {
    std::cerr << "replay_pipeline: " << loaded.error() << "\n";
    return 2;
  }
  agraph::AGraph building = loaded.value();
  if (!storey.empty()) {
    auto s = agraph::SelectStorey(building, storey);
    if (!s.ok()) {
      std::cerr << "replay_pipeline: " << s.error() << "\n";
      return 2;
    }
    building = s.value();
  }
  rosbag::Bag bag;
  try {
    bag.open(bag_path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    std::cerr << "replay_pipeline: " << bag_path << ": " << e.what() << "\n";
    return 2;
  }
  pipeline::LocalizationPipeline localization(config);
  if (const auto e = localization.SetAGraph(building); !e.empty()) {
    std::cerr << "replay_pipeline: unusable A-Graph: " << e << "\n";
    return 2;
  }
  const bag_replay::StaticFrames static_frames(bag);
  ros_conversions::LidarCloudReader cloud_reader(cloud_config);
  std::FILE* pose_file =
      prefix.empty() ? nullptr : std::fopen((prefix + ".pose_bim.tum").c_str(), "w");
  std::FILE* truth_file =
      prefix.empty() ? nullptr : std::fopen((prefix + ".truth.tum").c_str(), "w");
  std::FILE* odom_file = prefix.empty() ? nullptr : std::fopen((prefix + ".odom.tum").c_str(), "w");
  std::FILE* online_file =
      prefix.empty() ? nullptr : std::fopen((prefix + ".sgraph_online.tum").c_str(), "w");
  if (!prefix.empty() && (!pose_file || !truth_file || !odom_file || !online_file)) {
    std::cerr << "replay_pipeline: cannot write " << prefix << ".*\n";
    return 2;
  }

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  double first = -1.0, last = 0.0, walked = 0.0, localized_at = -1.0, walked_at = 0.0;
  Eigen::Vector3d last_position = Eigen::Vector3d::Constant(std::nan(""));
  int poses = 0;
  std::vector<sgraph::StampedPose> truths;
  bag_replay::MatchAudit audit(building);
  bool ever_merged = false;
  double hint_given = -1.0;
  for (const auto& m : rosbag::View(bag, rosbag::TopicQuery(bag_replay::SensorTopics()))) {
    const double t = m.getTime().toSec();
    if (first < 0.0) first = t;
    if (max_duration > 0.0 && t - first > max_duration) break;
    last = t;
    if (auto odom = m.instantiate<nav_msgs::Odometry>()) {
      const double stamp = odom->header.stamp.toSec();
      const Eigen::Isometry3d odom_T_base = ros_conversions::FromPose(odom->pose.pose);
      if (last_position.allFinite())
        walked += (odom_T_base.translation() - last_position).head<2>().norm();
      last_position = odom_T_base.translation();
      if (odom_file) WriteTum(odom_file, stamp, odom_T_base);
      if (hint_at && stamp - first >= *hint_at && hint_given < 0.0) {
        // The robot's pose in M at this instant, as sgraph_node's tf map -> odom -> base_link.
        hint.map_T_base = matching::PlanarPose(localization.builder().MapToOdom() * odom_T_base);
        hint_given = stamp;
        if (const auto e = localization.SetPoseHint(stamp, hint); !e.empty())
          std::cerr << "replay_pipeline: pose hint not used: " << e << "\n";
      }
      const auto pose = localization.AddOdometry(stamp, odom_T_base);
      if (online_file)
        WriteTum(online_file, stamp, localization.builder().MapToOdom() * odom_T_base);
      if (!pose) continue;
      if (localized_at < 0.0) localized_at = stamp, walked_at = walked;
      ++poses;
      if (pose_file) WriteTum(pose_file, stamp, *pose);
    } else if (auto cloud = m.instantiate<sensor_msgs::PointCloud2>()) {
      const auto scan = bag_replay::ReadCloud(cloud_reader, *cloud, "replay_pipeline");
      if (!scan.ok()) continue;
      localization.AddScan(scan.value(), static_frames.BaseT(cloud->header.frame_id));
      audit.Update(localization, truths, first);
      ever_merged = ever_merged || localization.localized();
    } else if (auto truth = m.instantiate<geometry_msgs::PoseStamped>()) {
      truths.push_back({truth->header.stamp.toSec(), ros_conversions::FromPose(truth->pose)});
      if (truth_file) WriteTum(truth_file, truths.back().stamp, truths.back().pose);
    }
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  if (pose_file) std::fclose(pose_file);
  if (truth_file) std::fclose(truth_file);
  if (odom_file) std::fclose(odom_file);
  if (online_file) std::fclose(online_file);

  const auto& times = localization.times();
  const sgraph::SGraph graph = localization.Snapshot();
  nlohmann::json out;
  out["bag"] = bag_path;
  out["building"] = building.building;
  out["first_stamp"] = first;
  out["bag_seconds"] = last - first;
  out["walked_m"] = walked;
  out["localized"] = localized_at >= 0.0;
  out["seconds_to_localize"] = localized_at < 0.0 ? -1.0 : localized_at - first;
  out["distance_to_localize"] = localized_at < 0.0 ? -1.0 : walked_at;
  out["poses"] = poses;
  out["keyframes"] = graph.keyframes.size();
  out["planes"] = graph.planes.size();
  out["rooms"] = graph.rooms.size();
  out["wall_seconds"] = wall;
  out["real_time_factor"] = (last - first) / wall;
  out["peak_rss_mib"] = bag_replay::PeakRssKb() / 1024.0;
  out["stages"] = {{"scan", Stats(times.scan)},
                   {"preprocess", Stats(times.preprocess)},
                   {"plane_extraction", Stats(times.extraction)},
                   {"association", Stats(times.association)},
                   {"rooms", Stats(times.rooms)},
                   {"optimization", Stats(times.optimization)},
                   {"matching", Stats(times.matching)},
                   {"merging", Stats(times.merging)}};
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : localization.events()) {
    const Eigen::Vector3d xi = geometry::ToXYYaw(e.bim_T_map);
    events.push_back({{"t", e.stamp - first},
                      {"revision", e.revision},
                      {"kind", e.kind},
                      {"status", matching::ToString(e.status)},
                      {"bim_x_map", {xi.x(), xi.y(), xi.z() * 180.0 / M_PI}},
                      {"storey", e.storey},
                      {"message", e.message}});
    std::string storey;
    for (const auto& s : building.storeys)
      if (e.kind == "match" && s.id == e.storey) storey = " storey '" + s.name + "'";
    std::printf("%7.1f s rev %4u %-9s %-9s B_x_M (%.2f, %.2f, %.1f deg) %s%s\n", e.stamp - first,
                e.revision, e.kind.c_str(), e.kind == "match" ? matching::ToString(e.status) : "",
                xi.x(), xi.y(), xi.z() * 180.0 / M_PI, e.message.c_str(), storey.c_str());
  }
  out["events"] = events;
  if (hint_at) {
    bool rejected = false;
    for (const auto& e : localization.events()) rejected = rejected || e.kind == "hint_rejected";
    out["hint"] = {{"t", hint_given < 0.0 ? -1.0 : hint_given - first},
                   {"rejected", rejected},
                   {"in_force_at_end", localization.HintInForce()},
                   {"seconds_to_localize_after_hint",
                    localized_at < 0.0 || hint_given < 0.0 ? -1.0 : localized_at - hint_given}};
  }
  nlohmann::json matches = nlohmann::json::array();  // every match: the scenario contracts
  for (const auto& m : localization.matches())
    matches.push_back({{"t", m.stamp - first},
                       {"status", matching::ToString(m.status)},
                       {"storey", m.storey},
                       {"hypotheses", m.hypotheses},
                       {"competing_storeys", m.competing_storeys}});
  out["matches"] = matches;
  out["unique_matches"] = audit.json();
  out["wrong_matches"] = audit.wrong();
  out["wrong_storey_matches"] = audit.wrong_storeys();
  out["localized_at_end"] = localization.localized();
  out["final_bim_x_map"] = bag_replay::XYYawDeg(localization.bim_T_map());
  out["map_cloud_error"] = bag_replay::MapCloudError(localization, building, ever_merged);
  out["odometry_rejected"] = localization.builder().odometry_rejected();
  out["odometry_bridged"] = localization.builder().odometry_bridged();
  std::printf(
      "UNIQUE matches %zu, wrong (> 0.5 m or 5 deg from the truth, or another storey) %d, of "
      "them on another storey %d\n",
      audit.json().size(), audit.wrong(), audit.wrong_storeys());
  std::printf(
      "odometry: %d messages skipped by the guard (NaN, glitch, out of order), %d steps "
      "bridged\n",
      localization.builder().odometry_rejected(), localization.builder().odometry_bridged());
  if (const auto& c = out["map_cloud_error"]; !c.is_null())
    std::printf("map cloud vs BIM wall-surfaces: RMSE %.3f m, median %.3f m (%d of %d points)\n",
                c["rmse_m"].get<double>(), c["median_m"].get<double>(), c["used"].get<int>(),
                c["points"].get<int>());
  std::printf("bag %.1f s, walked %.1f m; %s; keyframes %zu, planes %zu, rooms %zu\n", last - first,
              walked,
              localized_at < 0.0 ? "NOT localized"
                                 : ("localized after " + std::to_string(localized_at - first) +
                                    " s, " + std::to_string(walked_at) + " m")
                                       .c_str(),
              graph.keyframes.size(), graph.planes.size(), graph.rooms.size());
  std::printf("%-17s %7s %9s %9s %9s\n", "stage", "count", "median", "p99", "max [ms]");
  for (const auto& [name, s] : out["stages"].items())
    std::printf("%-17s %7d %9.2f %9.2f %9.2f\n", name.c_str(), s["count"].get<int>(),
                s["median_ms"].get<double>(), s["p99_ms"].get<double>(), s["max_ms"].get<double>());
  std::printf("real-time factor %.1fx (wall %.1f s), peak RSS %.1f MiB\n", (last - first) / wall,
              wall, bag_replay::PeakRssKb() / 1024.0);
  if (explain) bag_replay::ExplainMatch(building, graph, truths, config.matcher);
  if (!deviations_path.empty() &&
      !bag_replay::WriteDeviations(deviations_path, building, graph, localization))
    return 3;
  if (!prefix.empty()) {
    std::ofstream(prefix + ".json") << out.dump(2) << "\n";
    if (!bag_replay::WriteKeyframesTum(graph, prefix + ".sgraph.tum")) {
      std::cerr << "replay_pipeline: cannot write " << prefix << ".sgraph.tum\n";
      return 2;
    }
  }
  return 0;
}
