// agraph_node: loads a building's BIM (an IFC file, converted and cached, or an A-Graph file),
// builds and solves its A-Graph factor graph once, and publishes latched `a_graph`,
// `a_graph/markers` and `a_graph/cloud` in the BIM frame; and the building as a navigation map
// (`bim_map`, `bim_map/as_built`, service `locate`: bim_map_server.h, docs/navigation.md).
// Thin: the work is in is_graphs_core.
#include <diagnostic_updater/diagnostic_updater.h>
#include <is_graphs/AGraph.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/MarkerArray.h>

#include <cstdlib>
#include <optional>

#include "agraph_conversions.h"
#include "agraph_markers.h"
#include "bim_map_server.h"
#include "cloud_conversions.h"
#include "is_graphs/agraph/agraph_problem.h"
#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/agraph/ifc_conversion.h"
#include "is_graphs/geometry/surface_sampling.h"
#include "is_graphs/geometry/triangle_mesh.h"
#include "param_helpers.h"

namespace is_graphs {
namespace {

struct AGraphNodeParams {
  std::string bim_file;
  std::string storey;
  std::string frame_id{"bim"};
  bool optimize{true};
  agraph::IfcConversionConfig conversion;
  agraph::AGraphProblemConfig problem;
  geometry::SurfaceSamplingConfig sampling;
  ros_markers::AGraphMarkerStyle markers;
  ros_nav::BimMapParams map;
};

std::string DefaultCacheDir() {
  const char* ros_home = std::getenv("ROS_HOME");
  const char* home = std::getenv("HOME");
  const std::string base = ros_home ? ros_home : std::string(home ? home : "/tmp") + "/.ros";
  return base + "/is_graphs/cache";
}

AGraphNodeParams ReadParams(const ros::NodeHandle& pnh) {
  AGraphNodeParams p;
  p.bim_file = ros_params::RequireString(pnh, "bim_file");
  ros_params::Read(pnh, "storey", p.storey);
  ros_params::Read(pnh, "frame_id", p.frame_id);
  ros_params::Read(pnh, "optimize", p.optimize);
  p.conversion.cache_dir = DefaultCacheDir();
  ros_params::Read(pnh, "cache_dir", p.conversion.cache_dir);
  ros_params::Read(pnh, "python", p.conversion.python);
  ros_params::Read(pnh, "converter", p.conversion.converter);
  ros_params::Read(pnh, "cloud_density", p.sampling.points_per_square_metre);
  bool include_doors = false;
  ros_params::Read(pnh, "cloud_include_doors", include_doors);
  if (!include_doors) p.sampling.excluded_classes = {"IfcDoor"};
  ros_params::Read(pnh, "marker_layer_spacing", p.markers.layer_spacing);
  ros_params::Read(pnh, "map_resolution", p.map.grid.resolution);
  ros_params::Read(pnh, "map_slice_min", p.map.grid.slice_min);
  ros_params::Read(pnh, "map_slice_max", p.map.grid.slice_max);
  ros_params::Read(pnh, "map_margin", p.map.grid.margin);
  ros_params::Read(pnh, "map_storey", p.map.storey);
  ros_params::Read(pnh, "locate_door_standoff", p.map.places.door_standoff);
  ros_params::Read(pnh, "locate_wall_standoff", p.map.places.wall_standoff);
  if (p.frame_id.empty()) throw ros_params::ParamError("parameter '~frame_id' must not be empty");
  ros_params::ThrowIfInvalid("~cloud_density", p.sampling.Validate());
  ros_params::ThrowIfInvalid("A-Graph problem", p.problem.Validate());
  if (const std::string bad = p.map.grid.Validate(); !bad.empty())
    throw ros_params::ParamError("parameter '" +
                                 pnh.resolveName("map_" + bad.substr(0, bad.find(':'))) + "'" +
                                 bad.substr(bad.find(':')));
  if (const std::string bad = p.map.places.Validate(); !bad.empty())
    throw ros_params::ParamError("parameter '" +
                                 pnh.resolveName("locate_" + bad.substr(0, bad.find(':'))) + "'" +
                                 bad.substr(bad.find(':')));
  p.markers.frame_id = p.frame_id;
  p.map.frame_id = p.frame_id;
  return p;
}

/// The building's mesh, when the conversion wrote one (a_graph/cloud, bim_map's columns).
std::optional<geometry::TriangleMesh> LoadMesh(const agraph::AGraph& graph) {
  if (graph.mesh.empty()) {
    ROS_WARN(
        "agraph_node: the A-Graph names no mesh; a_graph/cloud stays empty, bim_map has walls "
        "only");
    return std::nullopt;
  }
  auto mesh = geometry::LoadObj(graph.mesh);
  if (!mesh.ok()) {
    ROS_WARN("agraph_node: %s; a_graph/cloud stays empty, bim_map has walls only",
             mesh.error().c_str());
    return std::nullopt;
  }
  return std::move(mesh).value();
}

int Run(ros::NodeHandle& nh, const AGraphNodeParams& params) {
  ROS_INFO("agraph_node: loading %s", params.bim_file.c_str());
  auto loaded = agraph::LoadBim(params.bim_file, params.conversion);
  if (!loaded.ok()) {
    ROS_FATAL("agraph_node: cannot load the BIM: %s", loaded.error().c_str());
    return EXIT_FAILURE;
  }
  agraph::AGraph graph = std::move(loaded).value();
  if (!params.storey.empty()) {
    auto selected = agraph::SelectStorey(graph, params.storey);
    if (!selected.ok()) {
      ROS_FATAL("agraph_node: parameter '~storey': %s", selected.error().c_str());
      return EXIT_FAILURE;
    }
    graph = std::move(selected).value();
  }
  for (const auto& warning : graph.warnings)
    ROS_WARN("agraph_node: conversion: %s", warning.c_str());
  if (graph.rooms.empty()) ROS_WARN("agraph_node: %s has no rooms", params.bim_file.c_str());

  if (params.optimize) {
    agraph::AGraphProblem problem(graph, params.problem);
    const auto summary = problem.Solve();
    problem.WriteBack(graph);
    ROS_INFO("agraph_node: A-Graph optimized: cost %.3g -> %.3g in %d iterations",
             summary.initial_cost, summary.final_cost, summary.iterations);
  }

  const ros::Time stamp = ros::Time::now();
  is_graphs::AGraph msg = ros_conversions::ToMsg(graph);
  msg.header.frame_id = params.frame_id;
  msg.header.stamp = stamp;
  msg.source_file = params.bim_file;

  visualization_msgs::MarkerArray markers = ros_markers::BuildAGraphMarkers(graph, params.markers);
  for (auto& m : markers.markers) m.header.stamp = stamp;

  const std::optional<geometry::TriangleMesh> mesh = LoadMesh(graph);
  sensor_msgs::PointCloud2 cloud =
      ros_conversions::ToCloudMsg(mesh ? geometry::SampleSurface(*mesh, params.sampling).points
                                       : std::vector<Eigen::Vector3d>{},
                                  params.frame_id);
  cloud.header.stamp = stamp;

  ros::Publisher graph_pub = nh.advertise<is_graphs::AGraph>("a_graph", 1, /*latch=*/true);
  ros::Publisher marker_pub =
      nh.advertise<visualization_msgs::MarkerArray>("a_graph/markers", 1, /*latch=*/true);
  ros::Publisher cloud_pub = nh.advertise<sensor_msgs::PointCloud2>("a_graph/cloud", 1, true);
  graph_pub.publish(msg);
  marker_pub.publish(markers);
  cloud_pub.publish(cloud);
  ros_nav::BimMapServer bim_map(nh, graph, mesh ? &*mesh : nullptr, params.map);
  ROS_INFO_STREAM("agraph_node: published (latched) " << cloud.width << " cloud points and\n"
                                                      << agraph::Summarize(graph));
  // /diagnostics: what was loaded (a failed load never gets here: FATAL and exit).
  diagnostic_updater::Updater diagnostics;
  diagnostics.setHardwareID("is_graphs");
  diagnostics.add("A-Graph", [&](diagnostic_updater::DiagnosticStatusWrapper& d) {
    using diagnostic_msgs::DiagnosticStatus;
    if (graph.rooms.empty())
      d.summary(DiagnosticStatus::WARN, "the A-Graph has no rooms: nothing to match");
    else
      d.summaryf(graph.warnings.empty() ? DiagnosticStatus::OK : DiagnosticStatus::WARN,
                 "'%s': %zu rooms, %zu wall-surfaces, %zu conversion warnings",
                 graph.building.c_str(), graph.rooms.size(), graph.surfaces.size(),
                 graph.warnings.size());
    d.add("file", params.bim_file);
    d.add("storey", params.storey);
    d.add("rooms", graph.rooms.size());
    d.add("wall-surfaces", graph.surfaces.size());
    d.add("doorways", graph.doorways.size());
    d.add("conversion warnings", graph.warnings.size());
    d.add("cloud points", cloud.width);
  });
  ros::Timer diagnostics_timer =
      nh.createTimer(ros::Duration(1.0), [&](const ros::TimerEvent&) { diagnostics.update(); });
  ros::spin();
  return EXIT_SUCCESS;
}

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  ros::init(argc, argv, "agraph_node");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    const auto params = is_graphs::ReadParams(pnh);
    return is_graphs::Run(nh, params);
  } catch (const is_graphs::ros_params::ParamError& e) {
    ROS_FATAL("agraph_node: %s", e.what());
    return EXIT_FAILURE;
  }
}
