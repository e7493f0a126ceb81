// EvaluatePair (declared in candidate_graph.h): a room pair under a given motion, the
// tolerances it is judged by, and the room-pair geometry the candidates' fits share.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "is_graphs/matching/candidate_graph.h"
#include "room_pair_geometry.h"

namespace is_graphs {
namespace matching {
namespace room_pair {

int NeededPlanes(int n, double fraction) {
  return std::max(std::min(n, 2), static_cast<int>(std::ceil(fraction * n - 1e-9)));
}

PointNormal Foot(const RoomDescriptor& room, int plane) {
  const PlaneFeature& f = room.planes[plane];
  return {room.centre - f.r * f.normal, f.normal};
}

bool SpansLessThanTheRoom(const RoomDescriptor& s, const std::vector<int>& others, int left,
                          double min_cos) {
  const PlaneFeature& plane = s.planes[left];
  double width = 0.0;
  for (size_t x = 0; x < others.size(); ++x)
    for (size_t y = x + 1; y < others.size(); ++y) {
      const PlaneFeature &p = s.planes[others[x]], &q = s.planes[others[y]];
      if (p.normal.dot(q.normal) <= -min_cos && std::abs(p.normal.dot(plane.normal)) < kSpanCos)
        width = std::max(width, std::abs(p.d + q.d));
    }
  return width > 0.0 && plane.length <= kMaxSpan * width;
}

bool OnePlaneInside(const RoomDescriptor& s, const RoomDescriptor& a, const Pose2& pose,
                    const std::vector<std::pair<int, int>>& surfaces, double min_cos,
                    double offset) {
  const int n = static_cast<int>(s.planes.size());
  if (static_cast<int>(surfaces.size()) != n - 1 || n - 1 < 3) return false;
  std::vector<char> paired(n, 0);
  std::vector<int> others;
  for (const auto& [i, j] : surfaces) paired[i] = 1, others.push_back(i);
  const int left = static_cast<int>(std::find(paired.begin(), paired.end(), 0) - paired.begin());
  return SpansLessThanTheRoom(s, others, left, min_cos) &&
         SignedDistanceToPolygon(a.polygon, pose.Apply(Foot(s, left).point)) < -offset;
}

}  // namespace room_pair

using room_pair::kDegToRad;
using room_pair::NeededPlanes;
using room_pair::OnePlaneInside;

EvaluationTolerances EvaluationTolerances::From(const MatcherConfig& config, double slack) {
  EvaluationTolerances t;
  t.offset = config.offset_tolerance + slack;
  t.centre = config.centre_tolerance + slack;
  t.angle_rad = config.angle_tolerance_deg * kDegToRad;
  t.min_cos = std::cos(t.angle_rad);
  t.min_plane_fraction = config.min_plane_fraction;
  t.quality_sigma = config.quality_sigma;
  t.centre_off = config.pair_through_walls;
  return t;
}

PairEvaluation EvaluatePair(const RoomDescriptor& s, const RoomDescriptor& a, const Pose2& pose,
                            bool full_rank, const EvaluationTolerances& tol) {
  return EvaluatePair(s, a, pose, pose.R(), full_rank, tol);
}

PairEvaluation EvaluatePair(const RoomDescriptor& s, const RoomDescriptor& a, const Pose2& pose,
                            const Eigen::Matrix2d& rot, bool full_rank,
                            const EvaluationTolerances& tol) {
  PairEvaluation out;
  const double min_cos = tol.min_cos;
  const Eigen::Vector2d centre_b = rot * s.centre + pose.t;
  // Full rank: the centres agree, or the S-centre at least lies in the A-room (checked for
  // centre_off once the planes are paired).
  bool centre_off = false;
  if (full_rank) {
    if ((centre_b - a.centre).norm() > tol.centre) {
      if (!tol.centre_off || s.planes.size() < 4 || a.polygon.empty() ||
          SignedDistanceToPolygon(a.polygon, centre_b) > 0.0)
        return out;
      centre_off = true;
    }
  } else if (!a.polygon.empty() && SignedDistanceToPolygon(a.polygon, centre_b) > tol.centre) {
    return out;
  }
  // The A-surfaces used: bits for up to 64 (every room seen so far), a vector beyond.
  std::uint64_t used_bits = 0;
  std::vector<char> used_many(a.planes.size() > 64 ? a.planes.size() : 0, 0);
  auto use = [&](size_t j) {
    used_many.empty() ? void(used_bits |= 1ull << j) : void(used_many[j] = 1);
  };
  auto used = [&](size_t j) {
    return used_many.empty() ? ((used_bits >> j) & 1ull) != 0 : used_many[j] != 0;
  };
  out.surfaces.reserve(s.planes.size());
  out.residuals.reserve(s.planes.size());
  double sum_sq = 0.0;
  for (size_t i = 0; i < s.planes.size(); ++i) {
    const Eigen::Vector2d n = rot * s.planes[i].normal;
    const double d = s.planes[i].d + n.dot(pose.t);
    const double r = n.dot(a.centre) - d;  // A-centre in front of the moved S-plane
    int best = -1;
    double best_err = tol.offset;
    for (size_t j = 0; j < a.planes.size(); ++j) {
      if (n.dot(a.planes[j].normal) < min_cos) continue;
      const double err = std::abs(r - a.planes[j].r);
      if (err <= best_err) best = static_cast<int>(j), best_err = err;
    }
    if (best < 0) continue;
    out.surfaces.emplace_back(static_cast<int>(i), best);
    out.residuals.push_back(best_err);
    use(best);
    sum_sq += best_err * best_err;
  }
  const int n = static_cast<int>(s.planes.size());
  const int matched = static_cast<int>(out.surfaces.size());
  if (matched == 0 || matched < NeededPlanes(n, tol.min_plane_fraction)) return out;
  if (centre_off && !OnePlaneInside(s, a, pose, out.surfaces, min_cos, tol.offset)) return out;

  // Coverage of the A-room by what was seen: all its surfaces for a closed room, the ones
  // parallel to the seen planes for a corridor (its ends are not part of it).
  double seen = 0.0, total = 0.0;
  for (size_t j = 0; j < a.planes.size(); ++j) {
    bool relevant = full_rank;
    for (size_t i = 0; i < s.planes.size() && !relevant; ++i)
      relevant = std::abs((rot * s.planes[i].normal).dot(a.planes[j].normal)) >= min_cos;
    if (!relevant) continue;
    const double len = a.planes[j].length > 0.0 ? a.planes[j].length : 1.0;
    total += len;
    if (used(j)) seen += len;
  }
  const double coverage = total > 0.0 ? seen / total : 0.0;
  out.rms = std::sqrt(sum_sq / matched);
  double fit = 0.0;  // mean of the planes' Gaussians: one deviating wall costs its share only
  for (double r : out.residuals)
    fit += std::exp(-0.5 * (r * r) / (tol.quality_sigma * tol.quality_sigma));
  fit /= matched;
  out.quality = (static_cast<double>(matched) / n) * (0.5 + 0.5 * coverage) * fit;
  out.ok = true;
  out.centre_off = centre_off;
  return out;
}

}  // namespace matching
}  // namespace is_graphs
