// SGraphBuilder: merging mapped planes that turn out to be one surface. Two pieces of a wall
// seen apart (a doorway or an occluder between them, farther than association_max_gap) become
// two planes; when later views extend them until they overlap, they are one wall mapped twice,
// and every room built on either would count it twice.
#include <algorithm>
#include <cmath>

#include "is_graphs/sgraph/plane_association.h"
#include "is_graphs/sgraph/sgraph_builder.h"

namespace is_graphs {
namespace sgraph {
namespace {

constexpr double kMinOverlap = 0.2;   // m along the wall
constexpr double kMaxAngleDeg = 3.0;  // between the normals
// m: each one's middle from the other plane; below a window's set-back (~0.1 m) in its wall.
constexpr double kMaxOffset = 0.08;

}  // namespace

PlaneSegment SGraphBuilder::AsSegment(const MapPlane& p) {
  PlaneSegment s;
  s.plane = p.plane.plane;
  s.covariance = p.plane.covariance;
  s.horizontal = p.horizontal;
  s.start = p.start;
  s.end = p.end;
  s.low = p.plane.z_min;
  s.high = p.plane.z_max;
  s.num_points = p.plane.num_points;
  return s;
}

void SGraphBuilder::MergeDuplicatePlanes(const std::vector<int>& touched) {
  for (int id : touched) {
    if (planes_[id].merged_into >= 0 || planes_[id].horizontal) continue;
    for (size_t other = 0; other < planes_.size(); ++other) {
      const int o = static_cast<int>(other);
      if (o == id || planes_[o].merged_into >= 0 || planes_[o].horizontal) continue;
      const MapPlane &a = planes_[id], &b = planes_[o];
      if (a.plane.plane.normal.dot(b.plane.plane.normal) < std::cos(kMaxAngleDeg * M_PI / 180.0))
        continue;
      const PlaneSegment sa = AsSegment(a), sb = AsSegment(b);
      if (!CoplanarInScan(sa, sb, kMaxOffset)) continue;
      MapPlaneView view;
      view.plane = b.plane.plane;
      view.start = b.start;
      view.end = b.end;
      if (SegmentGap(sa, view) > -kMinOverlap) continue;
      const int into = std::min(id, o), from = std::max(id, o);
      MergePlane(from, into);
      if (from == id) break;  // this one is gone; the survivor is checked when touched again
    }
  }
}

void SGraphBuilder::MergePlane(int from, int into) {
  MapPlane& gone = planes_[from];
  const PlaneSegment piece = AsSegment(gone);
  ExtendPlane(planes_[into], piece);
  gone.merged_into = into;
  planes_[into].last_keyframe = std::max(planes_[into].last_keyframe, gone.last_keyframe);
  planes_[into].num_keyframes += gone.num_keyframes;
  for (auto& o : observations_)
    if (o.plane == from) o.plane = into;
  for (auto& room : rooms_) {
    std::vector<int> planes;
    std::vector<double> distances;
    for (size_t i = 0; i < room.planes.size(); ++i) {
      const int p = room.planes[i] == from ? into : room.planes[i];
      if (std::count(planes.begin(), planes.end(), p)) continue;
      planes.push_back(p);
      if (i < room.distances.size()) distances.push_back(room.distances[i]);
    }
    room.planes = std::move(planes);
    room.distances = std::move(distances);
  }
}

}  // namespace sgraph
}  // namespace is_graphs
