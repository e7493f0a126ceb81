// SGraphBuilder: the optimization off the scan path, and what is read out of the graph.
#include <algorithm>
#include <set>

#include "is_graphs/sgraph/backend_window.h"
#include "is_graphs/sgraph/cloud_filter.h"
#include "is_graphs/sgraph/floor_node.h"
#include "is_graphs/sgraph/sgraph_builder.h"

namespace is_graphs {
namespace sgraph {

BackendProblem SGraphBuilder::MakeProblem() const {
  BackendProblem problem;
  for (const auto& p : planes_) problem.planes.push_back(p.plane);
  problem.rooms = rooms_;
  problem.floor = floor_;
  problem.odometry_scale = odometry_scale_;
  SelectWindow(keyframes_, observations_, backend_, problem);  // the keyframes, observations
  return problem;
}

BackendSummary SGraphBuilder::Optimize() {
  std::lock_guard<std::mutex> one_at_a_time(optimize_mutex_);
  BackendProblem problem;
  std::uint64_t generation;
  size_t num_keyframes, num_planes, num_rooms;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    problem = MakeProblem();
    generation = generation_;
    num_keyframes = keyframes_.size();
    num_planes = planes_.size();
    num_rooms = rooms_.size();
    optimized_keyframes_ = static_cast<int>(num_keyframes);
  }
  if (num_keyframes == 0) {
    BackendSummary empty;
    empty.message = "no keyframes";
    return empty;
  }
  const BackendSummary summary = OptimizeSGraph(problem, backend_);

  std::lock_guard<std::mutex> lock(mutex_);
  if (generation != generation_ || !summary.usable) return summary;
  // What was added while Ceres ran moves with the newest optimized keyframe.
  const Eigen::Isometry3d delta =
      problem.keyframes.back().pose * keyframes_[num_keyframes - 1].pose.inverse();
  for (const auto& k : problem.keyframes) {  // the window's part (ids are indices)
    if (problem.constant_keyframes.count(k.id)) continue;
    if (k.id >= 0 && static_cast<size_t>(k.id) < num_keyframes && keyframes_[k.id].id == k.id)
      keyframes_[k.id].pose = k.pose;
  }
  for (size_t i = num_keyframes; i < keyframes_.size(); ++i)
    keyframes_[i].pose = delta * keyframes_[i].pose;
  for (size_t i = 0; i < planes_.size(); ++i) {
    MapPlane& p = planes_[i];
    if (i < num_planes) {
      p.plane.plane = problem.planes[i].plane;
    } else {
      p.plane.plane = p.plane.plane.Transformed(delta);
      p.start = delta * p.start;
      p.end = delta * p.end;
    }
    p.start = p.plane.plane.Project(p.start);
    p.end = p.plane.plane.Project(p.end);
    p.plane.start = p.start.head<2>();
    p.plane.end = p.end.head<2>();
    p.plane.orientation = geometry::ClassifyOrientation(p.plane.plane.normal);
  }
  for (size_t i = 0; i < num_rooms && i < rooms_.size(); ++i) {
    // Keep a corridor upgraded meanwhile as it is; move centres of unchanged rooms.
    if (rooms_[i].type == problem.rooms[i].type) rooms_[i].center = problem.rooms[i].center;
  }
  if (floor_.present && problem.floor.present) floor_.center = problem.floor.center;
  odometry_scale_ = problem.odometry_scale;
  map_T_odom_ = keyframes_.back().pose * keyframes_.back().odom_pose.inverse();
  ++revision_;
  return summary;
}

SGraph SGraphBuilder::Snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  SGraph graph;
  graph.revision = revision_;
  graph.stamp = keyframes_.empty() ? 0.0 : keyframes_.back().stamp;
  graph.keyframes = keyframes_;
  for (const auto& p : planes_)
    if (p.merged_into < 0) graph.planes.push_back(p.plane);
  graph.observations = observations_;
  graph.odometry_scale = odometry_scale_;
  const double height = FloorHeight();
  for (size_t i = 0; i < rooms_.size(); ++i) {
    const BackendRoom& r = rooms_[i];
    Room room;
    room.id = r.id;
    room.type = r.type;
    room.center = Eigen::Vector3d(r.center.x(), r.center.y(), height);
    room.planes = r.planes;
    room.keyframes = room_keyframes_[i];
    const double sigma = r.type == RoomType::kRoom && !r.rectangular ? backend_.polygon_room_sigma
                                                                     : backend_.room_sigma;
    room.information = Eigen::Matrix3d::Identity() / (sigma * sigma);
    graph.rooms.push_back(room);
  }
  if (floor_.present) graph.floors.push_back(MakeFloor(graph.rooms, height));
  if (floor_.present && !graph.floors.empty()) graph.floors.back().center.head<2>() = floor_.center;
  if (levels_.size() > 1) SplitFloorsByLevel(&graph, height);
  graph.doorways = DetectDoorways(graph, frontend_.doorways);
  for (auto& d : graph.doorways)
    if (d.width <= 0.0) d.width = DoorwayWidthLocked(d, graph);
  return graph;
}

void SGraphBuilder::SplitFloorsByLevel(SGraph* graph, double ground_floor) const {
  // One floor per level, at the level's height less the robot's standing height on level 0
  // (the first floor plane's height under its first keyframe): the body stands as high above
  // every floor. Rooms on the floor of their level.
  const double standing = levels_.Height(0) - ground_floor;
  std::vector<std::vector<Room>> by_level(levels_.size());
  for (auto& room : graph->rooms) {
    const int level = LevelOfRoom(*graph, room);
    if (level <= 0 || level >= levels_.size()) {
      if (level == 0) by_level[0].push_back(room);
      continue;
    }
    room.center.z() = levels_.Height(level) - standing;
    by_level[level].push_back(room);
  }
  const std::vector<Floor> before = graph->floors;
  graph->floors.clear();
  for (int level = 0; level < levels_.size(); ++level) {
    const double height = level == 0 ? ground_floor : levels_.Height(level) - standing;
    Floor floor = MakeFloor(by_level[level], height);
    floor.id = level;
    if (level == 0 && !before.empty()) floor.center.head<2>() = before.back().center.head<2>();
    graph->floors.push_back(floor);
  }
}

double SGraphBuilder::DoorwayWidthLocked(const Doorway& doorway, const SGraph& graph) const {
  // The crossed planes (the wall's faces), and the points of the keyframes around the crossing
  // steps that lie on them between knee and head height: the gap among them is the doorway.
  std::vector<const Plane*> faces;
  for (const auto& p : graph.planes)
    if (std::count(doorway.planes.begin(), doorway.planes.end(), p.id)) faces.push_back(&p);
  if (faces.empty()) return 0.0;
  const Eigen::Vector3d n = faces.front()->plane.normal;
  const Eigen::Vector2d along = Eigen::Vector2d(-n.y(), n.x()).normalized();
  const DoorwayConfig& c = frontend_.doorways;
  const double reach = c.max_width + 0.5;
  std::set<size_t> near;  // keyframe indices: each step's two ends and one more either side
  for (int id : doorway.keyframes) {
    const auto k = std::find_if(keyframes_.begin(), keyframes_.end(),
                                [&](const Keyframe& x) { return x.id == id; });
    if (k == keyframes_.end()) continue;
    const size_t i = static_cast<size_t>(k - keyframes_.begin());
    for (size_t j = i > 0 ? i - 1 : 0; j <= i + 2 && j < clouds_.size(); ++j) near.insert(j);
  }
  // Thinned clouds (out of the window) would give another gap: the width measured before.
  const bool full = near.empty() || *near.begin() >= thinned_clouds_;
  if (!full) {
    auto cached = doorway_widths_.find(doorway.id);
    if (cached != doorway_widths_.end()) return cached->second;
  }
  std::vector<double> coords;
  for (size_t i : near) {
    const Eigen::Isometry3d& pose = keyframes_[i].pose;
    for (const auto& q : clouds_[i]) {
      const Eigen::Vector3d p = pose * q.cast<double>();
      const double height = p.z() - doorway.position.z();
      if (height < c.band_low || height > c.band_high) continue;
      const double u = along.dot((p - doorway.position).head<2>());
      if (std::abs(u) > reach) continue;
      if (std::any_of(faces.begin(), faces.end(), [&](const Plane* f) {
            return std::abs(f->plane.SignedDistance(p)) < c.wall_band;
          }))
        coords.push_back(u);
    }
  }
  const double width = GapWidth(coords, c.max_width);
  if (full) doorway_widths_[doorway.id] = width;
  return width;
}

void SGraphBuilder::ThinOldCloudsLocked() {
  const size_t window = static_cast<size_t>(std::max(0, backend_.window_keyframes));
  if (window == 0 || backend_.window_cloud_voxel_size <= 0.0) return;
  for (; thinned_clouds_ + window < clouds_.size(); ++thinned_clouds_) {
    PointList& cloud = clouds_[thinned_clouds_];
    cloud = VoxelFilter(cloud, backend_.window_cloud_voxel_size);
    cloud.shrink_to_fit();
  }
}

Eigen::Isometry3d SGraphBuilder::MapToOdom() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return map_T_odom_ * guard_.correction();
}

int SGraphBuilder::odometry_rejected() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return guard_.rejected();
}

int SGraphBuilder::odometry_bridged() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return guard_.bridged();
}

PointList SGraphBuilder::MapCloud(double voxel_size) const {
  PointList all;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < clouds_.size(); ++i) {
      const Eigen::Isometry3f pose = keyframes_[i].pose.cast<float>();
      for (const auto& p : clouds_[i]) all.push_back(pose * p);
    }
  }
  return VoxelFilter(all, voxel_size);
}

int SGraphBuilder::num_keyframes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(keyframes_.size());
}

size_t SGraphBuilder::num_cloud_points() const {
  std::lock_guard<std::mutex> lock(mutex_);
  size_t n = 0;
  for (const auto& c : clouds_) n += c.size();
  return n;
}

double SGraphBuilder::last_odometry_stamp() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_odom_stamp_;
}

int SGraphBuilder::pending_keyframes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(keyframes_.size()) - optimized_keyframes_;
}

}  // namespace sgraph
}  // namespace is_graphs
