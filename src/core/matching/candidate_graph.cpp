#include "is_graphs/matching/candidate_graph.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "room_pair_geometry.h"

namespace is_graphs {
namespace matching {
namespace {

using room_pair::Foot;
using room_pair::kDegToRad;
using room_pair::kSpanCos;
using room_pair::NeededPlanes;
using room_pair::OnePlaneInside;
using room_pair::SpansLessThanTheRoom;

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

/// One motion fitted to a room pair's surface pairs (all, or all but one left out): the
/// candidate and whether it holds, before the check against the yaw the pairs were found
/// under. `fitted` false: a set left out whose planes do not fix the motion, or whose left-out
/// plane could not stand in the room (nothing fitted).
struct Fitted {
  bool fitted{false};
  bool ok{false};
  RoomCandidate candidate;
};

/// The pairs of one A-room found under some yaw, their fit, and each variant's once tried.
struct PairSet {
  std::vector<std::pair<int, int>> found;  // under some yaw, before pruning
  std::vector<std::pair<int, int>> pairs;  // pruned
  bool enough{false};                      // pairs enough to fit
  Fitted all;
  std::vector<std::optional<Fitted>> left_out;  // by the pair left out
};

/// Fits the motion of an S-room onto an A-room from surface pairs (buffers reused).
class PairFitter {
 public:
  PairFitter(int s_index, const MatcherConfig& config, const EvaluationTolerances& tol)
      : s_index_(s_index), config_(config), tol_(tol), centre_(1) {}

  /// The motion fitted to `pairs` but `skip` (-1: all of them), and the pair evaluated.
  Fitted Fit(const RoomDescriptor& s, const RoomDescriptor& a, int a_index,
             const std::vector<std::pair<int, int>>& pairs, int skip) {
    Fitted out;
    planes_.clear();
    matched_s_.clear();
    for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
      if (k == skip) continue;
      const auto [i, j] = pairs[k];
      planes_.push_back(
          {s.planes[i].normal, s.planes[i].d, a.planes[j].normal, a.planes[j].d, a.centre});
      matched_s_.push_back(s.planes[i]);
    }
    const bool full_rank =
        s.kind == RoomKind::kRoom && PlanesSpanTwoDirectionsCos(matched_s_, kSpanCos);
    if (skip >= 0 && !full_rank) return out;
    // The centre as a prior: firm for a room, only nominal along a corridor's axis and where a
    // pair is left out (the plane that moved the S-centre).
    centre_[0] = {s.centre, a.centre, full_rank && skip < 0 ? config_.centre_tolerance : 100.0};
    const RigidFit fit = FitYawTranslation(planes_, centre_);
    out.fitted = true;
    RoomCandidate& c = out.candidate;
    c.s_room = s_index_;
    c.a_room = a_index;
    c.pose = fit.pose;
    const Eigen::Matrix2d rot = c.pose.R();  // once, for the centre, the axis and the pair
    c.at = rot * s.centre + c.pose.t;
    c.full_rank = full_rank;
    const Eigen::Vector2d n0 = rot * matched_s_.front().normal;
    c.axis = Eigen::Vector2d(-n0.y(), n0.x());
    const PairEvaluation eval = EvaluatePair(s, a, c.pose, rot, full_rank, tol_);
    c.quality = eval.quality;
    c.centre_off = eval.centre_off;
    // A pair left out must be a plane standing in the room (a wall across it, 1 m off the
    // A-room's, bounds another room: the tower's entrance hall under the larger office above
    // it), unless every plane pairs under the motion without it.
    out.ok = eval.ok && (skip < 0 || eval.surfaces.size() == s.planes.size() ||
                         OnePlaneInside(s, a, c.pose, eval.surfaces, tol_.min_cos, tol_.offset));
    return out;
  }

 private:
  int s_index_;
  const MatcherConfig& config_;
  const EvaluationTolerances& tol_;
  std::vector<PlaneCorrespondence> planes_;
  std::vector<PlaneFeature> matched_s_;
  std::vector<PointCorrespondence> centre_;
};

}  // namespace

std::vector<RoomCandidate> GenerateRoomCandidates(const RoomDescriptor& s, int s_index,
                                                  const std::vector<RoomDescriptor>& a_rooms,
                                                  const MatcherConfig& config) {
  std::vector<RoomCandidate> out;
  if (s.planes.empty()) return out;
  const EvaluationTolerances tol = EvaluationTolerances::From(config);
  const double r_tol = config.offset_tolerance + config.centre_tolerance;
  const double min_cos = tol.min_cos;
  const int needed = NeededPlanes(static_cast<int>(s.planes.size()), config.min_plane_fraction);

  // Anchors: the first plane and the first one not parallel to it (an extra plane in the
  // S-room must not hide the room: two anchors).
  std::vector<int> anchors{0};
  for (size_t i = 1; i < s.planes.size(); ++i)
    if (std::abs(s.planes[i].normal.dot(s.planes[0].normal)) < kSpanCos) {
      anchors.push_back(static_cast<int>(i));
      break;
    }

  struct Turn {
    double yaw;
    Eigen::Matrix2d rot;
  };
  std::vector<Turn> yaws;  // reused for every A-room, as are the vectors below
  std::vector<std::pair<int, int>> pairs;
  PairFitter fitter(s_index, config, tol);
  std::vector<PairSet> memo;         // the pair sets fitted for one A-room: the first memo_used
  size_t memo_used = 0;              // (the rest keep their buffers for the next A-room)
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
    memo_used = 0;
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
      // The pruning and the fits depend on the pairs alone, not on the yaw they were found
      // under (only the check that a fit stays near that yaw does): the two anchors' yaws of
      // one motion, a degree or two apart, mostly pair alike (a third of the fits were repeats).
      auto it = std::find_if(memo.begin(), memo.begin() + memo_used,
                             [&](const PairSet& m) { return m.found == pairs; });
      if (it == memo.begin() + memo_used) {  // new: into a used entry's buffers, if any
        if (memo_used == memo.size()) memo.emplace_back();
        PairSet& set = memo[memo_used++];
        set.found = pairs;
        PruneInconsistent(s, a, 2.0 * tol.angle_rad, 2.0 * r_tol, pairs);
        set.enough = static_cast<int>(pairs.size()) >= needed;
        set.pairs = pairs;
        set.left_out.assign(set.enough ? pairs.size() : 0, std::nullopt);
        if (set.enough) set.all = fitter.Fit(s, a, static_cast<int>(ai), pairs, -1);
        it = memo.begin() + (memo_used - 1);
      }
      if (!it->enough) continue;
      const std::vector<std::pair<int, int>>& kept = it->pairs;
      // Whether a fit holds under this yaw (its candidate into *c if the check passes).
      auto holds = [&](const Fitted& f, RoomCandidate* c) {
        if (!f.fitted || AngleDistance(f.candidate.pose.yaw, yaw) > 2.0 * tol.angle_rad)
          return false;
        *c = f.candidate;
        return f.ok;
      };
      found.assign(1, RoomCandidate{});
      if (!holds(it->all, &found[0])) {
        // One plane that is not the room's bound (paired with a wall it is not) pulls the fit:
        // each pair left out in turn, where every S-plane found a surface and the one left out
        // could stand in the room (checked before any fit: variants are what the cold match
        // costs). Every variant that holds is kept: which plane stands in the room (a stair's
        // side by the north wall, or one by the south wall under a motion 1.5 m along) the
        // room alone may not tell; the rest of the evidence does, or the answer stays AMBIGUOUS.
        const bool try_variants = config.pair_through_walls && found[0].full_rank &&
                                  kept.size() >= 4 && kept.size() == s.planes.size();
        found.clear();
        RoomCandidate variant;
        for (int skip = 0; try_variants && skip < static_cast<int>(kept.size()); ++skip) {
          std::optional<Fitted>& f = it->left_out[skip];
          if (!f) {
            others.clear();
            for (int k = 0; k < static_cast<int>(kept.size()); ++k)
              if (k != skip) others.push_back(kept[k].first);
            f = SpansLessThanTheRoom(s, others, kept[skip].first, min_cos)
                    ? fitter.Fit(s, a, static_cast<int>(ai), kept, skip)
                    : Fitted{};
          }
          if (holds(*f, &variant)) found.push_back(variant);
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
