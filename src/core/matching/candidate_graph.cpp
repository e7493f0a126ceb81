#include "is_graphs/matching/candidate_graph.h"

#include <algorithm>
#include <cmath>

namespace is_graphs {
namespace matching {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kSpanAngle = 20.0 * kDegToRad;  // planes this far apart fix a translation
// A plane standing in a room (centre_off) spans at most this share of the room's width.
constexpr double kMaxSpan = 0.8;

int NeededPlanes(int n, double fraction) {
  return std::max(std::min(n, 2), static_cast<int>(std::ceil(fraction * n - 1e-9)));
}

PointNormal Foot(const RoomDescriptor& room, int plane) {
  const PlaneFeature& f = room.planes[plane];
  return {room.centre - f.r * f.normal, f.normal};
}

/// Drops surface pairs inconsistent with the others (most conflicts first) until all agree.
/// Whether two pairs conflict does not depend on the others: tested once per two.
void PruneInconsistent(const RoomDescriptor& s, const RoomDescriptor& a, double angle_tol,
                       double distance_tol, std::vector<std::pair<int, int>>& pairs) {
  const size_t n = pairs.size();
  if (n < 2) return;
  const double cos_angle_tol = std::cos(angle_tol);
  thread_local std::vector<char> conflict;  // reused: this runs for every A-room and yaw
  thread_local std::vector<int> alive;
  conflict.assign(n * n, 0);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      conflict[i * n + j] = conflict[j * n + i] = !SurfacePairsAgree(
          Foot(s, pairs[i].first), Foot(s, pairs[j].first), Foot(a, pairs[i].second),
          Foot(a, pairs[j].second), cos_angle_tol, distance_tol);
  alive.resize(n);  // indices into the original pairs, in order
  for (size_t i = 0; i < n; ++i) alive[i] = static_cast<int>(i);
  while (alive.size() >= 2) {
    int worst = -1, worst_count = 0;
    for (size_t x = 0; x < alive.size(); ++x) {
      int count = 0;
      for (int y : alive) count += conflict[alive[x] * n + y];
      if (count > worst_count) worst = static_cast<int>(x), worst_count = count;
    }
    if (worst < 0) break;
    alive.erase(alive.begin() + worst);
  }
  if (alive.size() == n) return;
  std::vector<std::pair<int, int>> kept;
  for (int i : alive) kept.push_back(pairs[i]);
  pairs = std::move(kept);
}

/// Whether S-plane `left` could be a plane standing in the room bounded by the S-planes
/// `others` (indices): two of them face each other across it (normals at right angles to its
/// own) and it spans at most kMaxSpan of the width between them. A wall across the whole room
/// bounds a smaller room: another room, not this one with a plane standing in it.
bool SpansLessThanTheRoom(const RoomDescriptor& s, const std::vector<int>& others, int left,
                          double min_cos) {
  const PlaneFeature& plane = s.planes[left];
  const double cos_span = std::cos(kSpanAngle);
  double width = 0.0;
  for (size_t x = 0; x < others.size(); ++x)
    for (size_t y = x + 1; y < others.size(); ++y) {
      const PlaneFeature &p = s.planes[others[x]], &q = s.planes[others[y]];
      if (p.normal.dot(q.normal) <= -min_cos && std::abs(p.normal.dot(plane.normal)) < cos_span)
        width = std::max(width, std::abs(p.d + q.d));
    }
  return width > 0.0 && plane.length <= kMaxSpan * width;
}

/// For a pair whose centres disagree: the S-planes all paired (`surfaces`) but one, at least
/// three, the one left over spanning less than the room (SpansLessThanTheRoom) and lying inside
/// the A-room by more than `offset` under `pose` (its foot, the point nearest the S-centre): a
/// plane standing in the room, not a wall beyond it or across it.
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

}  // namespace

EvaluationTolerances EvaluationTolerances::From(const MatcherConfig& config, double slack) {
  EvaluationTolerances t;
  t.offset = config.offset_tolerance + slack;
  t.centre = config.centre_tolerance + slack;
  t.angle_rad = config.angle_tolerance_deg * kDegToRad;
  t.min_plane_fraction = config.min_plane_fraction;
  t.quality_sigma = config.quality_sigma;
  t.centre_off = config.pair_through_walls;
  return t;
}

PairEvaluation EvaluatePair(const RoomDescriptor& s, const RoomDescriptor& a, const Pose2& pose,
                            bool full_rank, const EvaluationTolerances& tol) {
  PairEvaluation out;
  const double min_cos = std::cos(tol.angle_rad);
  const Eigen::Matrix2d rot = pose.R();  // once: the loops below turn every plane
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
  thread_local std::vector<char> a_used;             // reused: this runs for every candidate pair
  thread_local std::vector<Eigen::Vector2d> turned;  // the S-normals in B
  a_used.assign(a.planes.size(), 0);
  turned.resize(s.planes.size());
  out.surfaces.reserve(s.planes.size());
  out.residuals.reserve(s.planes.size());
  double sum_sq = 0.0;
  for (size_t i = 0; i < s.planes.size(); ++i) {
    const Eigen::Vector2d n = turned[i] = rot * s.planes[i].normal;
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
    a_used[best] = 1;
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
    for (size_t i = 0; i < turned.size() && !relevant; ++i)
      relevant = std::abs(turned[i].dot(a.planes[j].normal)) >= min_cos;
    if (!relevant) continue;
    const double len = a.planes[j].length > 0.0 ? a.planes[j].length : 1.0;
    total += len;
    if (a_used[j]) seen += len;
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

std::vector<RoomCandidate> GenerateRoomCandidates(const RoomDescriptor& s, int s_index,
                                                  const std::vector<RoomDescriptor>& a_rooms,
                                                  const MatcherConfig& config) {
  std::vector<RoomCandidate> out;
  if (s.planes.empty()) return out;
  const EvaluationTolerances tol = EvaluationTolerances::From(config);
  const double r_tol = config.offset_tolerance + config.centre_tolerance;
  const double min_cos = std::cos(tol.angle_rad);
  const int needed = NeededPlanes(static_cast<int>(s.planes.size()), config.min_plane_fraction);

  // Anchors: the first plane and the first one not parallel to it (an extra plane in the
  // S-room must not hide the room: two anchors).
  std::vector<int> anchors{0};
  for (size_t i = 1; i < s.planes.size(); ++i)
    if (std::abs(s.planes[i].normal.dot(s.planes[0].normal)) < std::cos(kSpanAngle)) {
      anchors.push_back(static_cast<int>(i));
      break;
    }

  struct Turn {
    double yaw;
    Eigen::Matrix2d rot;
  };
  std::vector<Turn> yaws;  // reused for every A-room, as are the vectors below
  std::vector<std::pair<int, int>> pairs;
  std::vector<PlaneCorrespondence> planes;
  std::vector<PlaneFeature> matched_s;
  std::vector<PointCorrespondence> centre(1);
  std::vector<RoomCandidate> found;  // of one A-room and yaw
  std::vector<int> others;           // S-planes of a variant's pairs
  for (size_t ai = 0; ai < a_rooms.size(); ++ai) {
    const RoomDescriptor& a = a_rooms[ai];
    // Structural pre-check (cheap): enough S-planes have an A-surface at their distance.
    int compatible = 0;
    for (const auto& p : s.planes)
      for (const auto& q : a.planes)
        if (std::abs(p.r - q.r) <= r_tol) {
          ++compatible;
          break;
        }
    if (compatible < needed) continue;

    yaws.clear();
    for (int anchor : anchors)
      for (const auto& q : a.planes) {
        if (std::abs(s.planes[anchor].r - q.r) > r_tol) continue;
        // The turn taking the anchor's normal to q's, and its rotation without sin/cos.
        const Eigen::Vector2d& from = s.planes[anchor].normal;
        const double sin_t = from.x() * q.normal.y() - from.y() * q.normal.x();
        const double cos_t = from.dot(q.normal);
        const double yaw = std::atan2(sin_t, cos_t);
        if (std::any_of(yaws.begin(), yaws.end(),
                        [&](const Turn& t) { return AngleDistance(t.yaw, yaw) < 1.0 * kDegToRad; }))
          continue;
        const double norm = std::hypot(sin_t, cos_t);
        Turn turn{yaw, Eigen::Matrix2d::Identity()};
        if (norm > 0.0) turn.rot << cos_t / norm, -sin_t / norm, sin_t / norm, cos_t / norm;
        yaws.push_back(turn);
      }

    const size_t first_of_room = out.size();
    for (const Turn& turn : yaws) {
      const double yaw = turn.yaw;
      const Eigen::Matrix2d& rot = turn.rot;
      pairs.clear();
      for (size_t i = 0; i < s.planes.size(); ++i) {
        const Eigen::Vector2d n = rot * s.planes[i].normal;
        int best = -1;
        double best_err = r_tol;
        for (size_t j = 0; j < a.planes.size(); ++j) {
          if (n.dot(a.planes[j].normal) < min_cos) continue;
          const double err = std::abs(s.planes[i].r - a.planes[j].r);
          if (err <= best_err) best = static_cast<int>(j), best_err = err;
        }
        if (best >= 0) pairs.emplace_back(static_cast<int>(i), best);
      }
      PruneInconsistent(s, a, 2.0 * tol.angle_rad, 2.0 * r_tol, pairs);
      if (static_cast<int>(pairs.size()) < needed) continue;

      // The motion fitted to the pairs but `skip` (-1: all of them) and the pair evaluated.
      auto fit_pairs = [&](int skip, RoomCandidate* c) {
        planes.clear();
        matched_s.clear();
        for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
          if (k == skip) continue;
          const auto [i, j] = pairs[k];
          planes.push_back(
              {s.planes[i].normal, s.planes[i].d, a.planes[j].normal, a.planes[j].d, a.centre});
          matched_s.push_back(s.planes[i]);
        }
        const bool full_rank =
            s.kind == RoomKind::kRoom && PlanesSpanTwoDirections(matched_s, kSpanAngle);
        if (skip >= 0 && !full_rank) return false;
        // The centre as a prior: firm for a room, only nominal along a corridor's axis and
        // where a pair is left out (the plane that moved the S-centre).
        centre[0] = {s.centre, a.centre, full_rank && skip < 0 ? config.centre_tolerance : 100.0};
        const RigidFit fit = FitYawTranslation(planes, centre);
        if (AngleDistance(fit.pose.yaw, yaw) > 2.0 * tol.angle_rad) return false;
        c->s_room = s_index;
        c->a_room = static_cast<int>(ai);
        c->pose = fit.pose;
        c->at = fit.pose.Apply(s.centre);
        c->full_rank = full_rank;
        const Eigen::Vector2d n0 = c->pose.Rotate(matched_s.front().normal);
        c->axis = Eigen::Vector2d(-n0.y(), n0.x());
        const PairEvaluation eval = EvaluatePair(s, a, c->pose, full_rank, tol);
        c->quality = eval.quality;
        c->centre_off = eval.centre_off;
        // A pair left out must be a plane standing in the room (a wall across it, 1 m off the
        // A-room's, bounds another room: the tower's entrance hall under the larger office
        // above it), unless every plane pairs under the motion without it.
        return eval.ok && (skip < 0 || eval.surfaces.size() == s.planes.size() ||
                           OnePlaneInside(s, a, c->pose, eval.surfaces, min_cos, tol.offset));
      };
      found.assign(1, RoomCandidate{});
      if (!fit_pairs(-1, &found[0])) {
        // One plane that is not the room's bound (paired with a wall it is not) pulls the fit:
        // each pair left out in turn, where every S-plane found a surface and the one left out
        // could stand in the room (checked before any fit: variants are what the cold match
        // costs). Every variant that holds is kept: which plane stands in the room (a stair's
        // side by the north wall, or one by the south wall under a motion 1.5 m along) the
        // room alone may not tell; the rest of the evidence does, or the answer stays AMBIGUOUS.
        const bool try_variants = config.pair_through_walls && found[0].full_rank &&
                                  pairs.size() >= 4 && pairs.size() == s.planes.size();
        found.clear();
        RoomCandidate variant;
        for (int skip = 0; try_variants && skip < static_cast<int>(pairs.size()); ++skip) {
          others.clear();
          for (int k = 0; k < static_cast<int>(pairs.size()); ++k)
            if (k != skip) others.push_back(pairs[k].first);
          if (SpansLessThanTheRoom(s, others, pairs[skip].first, min_cos) &&
              fit_pairs(skip, &variant))
            found.push_back(variant);
        }
      }
      // One candidate per A-room and motion (the best): same yaw, and same place but for
      // centre_off variants.
      for (const RoomCandidate& c : found) {
        bool merged = false;
        for (size_t k = first_of_room; k < out.size() && !merged; ++k) {
          if (AngleDistance(out[k].pose.yaw, c.pose.yaw) >= 2.0 * kDegToRad) continue;
          if ((c.centre_off || out[k].centre_off) &&
              (out[k].pose.t - c.pose.t).norm() > config.centre_tolerance)
            continue;
          if (c.quality > out[k].quality) out[k] = c;
          merged = true;
        }
        if (!merged) out.push_back(c);
      }
    }
  }
  return out;
}

RoomCorrespondence ToCorrespondence(const RoomCandidate& c, const RoomDescriptor& s,
                                    const RoomDescriptor& a) {
  RoomCorrespondence out;
  out.s_centre = s.centre;
  out.a_centre = c.centre_off ? c.at : a.centre;
  out.yaw = c.pose.yaw;
  out.axis_free = !c.full_rank;
  out.axis_b = c.axis;
  return out;
}

}  // namespace matching
}  // namespace is_graphs
