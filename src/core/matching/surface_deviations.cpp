// GraphMatcher::Deviations: the wall-surfaces of the paired rooms that their S-planes show off
// the plan (issue 25: a room with one wall built off keeps its pair through the others, and that
// wall is marked instead of sinking the room).
#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/graph_matcher.h"

namespace is_graphs {
namespace matching {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

}  // namespace

std::vector<SurfaceDeviation> GraphMatcher::Deviations(
    const Hypothesis& h, const std::vector<RoomDescriptor>& s_rooms) const {
  const double max_turn = config_.deviation_max_angle_deg * kDegToRad;
  const double turn_limit = config_.deviation_angle_deg * kDegToRad;
  // How far S-plane i of `s` stands from A-plane q of `a` under `pose` (+: into the room) and
  // how much it is turned.
  auto measure = [](const Pose2& pose, const RoomDescriptor& s, size_t i, const RoomDescriptor& a,
                    const PlaneFeature& q) {
    const Eigen::Vector2d n = pose.Rotate(s.planes[i].normal);
    const double r = n.dot(a.centre) - (s.planes[i].d + n.dot(pose.t));
    return std::make_pair(q.r - r, geometry::SignedTurn(q.normal, n));
  };
  auto off_plan = [&](const std::pair<double, double>& m) {
    return std::abs(m.first) > config_.deviation_offset || std::abs(m.second) > turn_limit;
  };
  // The motion refitted to the pairs that stand on the plan. The hypothesis was fitted to every
  // pair, and a wall built off pulls it by part of its own offset, which then shows on walls
  // that are on the plan. So the pairs standing off are left out one at a time, each time the
  // one whose removal leaves the most pairs on the plan (then the smallest residuals): the
  // consensus of the room's other walls, not the largest residual, decides.
  std::vector<std::pair<int, int>> all;  // (member, index into its surface pairs)
  for (size_t k = 0; k < h.members.size(); ++k)
    for (size_t e = 0; e < h.members[k].evaluation.surfaces.size(); ++e)
      all.emplace_back(static_cast<int>(k), static_cast<int>(e));
  auto measure_pair = [&](const Pose2& at, const std::pair<int, int>& p) {
    const MemberPair& m = h.members[p.first];
    const auto [i, j] = m.evaluation.surfaces[p.second];
    return measure(at, s_rooms[m.s_room], i, a_rooms_[m.a_room], a_rooms_[m.a_room].planes[j]);
  };
  std::vector<bool> left_out(all.size(), false);
  // To the planes alone: a room centre moves with a wall built off (and with clutter).
  auto refit = [&](const std::vector<bool>& out_of_fit) {
    std::vector<PlaneCorrespondence> planes;
    for (size_t k = 0; k < all.size(); ++k) {
      if (out_of_fit[k]) continue;
      const MemberPair& m = h.members[all[k].first];
      const RoomDescriptor &s = s_rooms[m.s_room], &a = a_rooms_[m.a_room];
      const auto [i, j] = m.evaluation.surfaces[all[k].second];
      planes.push_back(
          {s.planes[i].normal, s.planes[i].d, a.planes[j].normal, a.planes[j].d, a.centre});
    }
    const RigidFit fit = FitYawTranslation(planes, {});
    return fit.translation_determined && fit.planes_determine_translation ? fit.pose : h.pose;
  };
  // How many of the pairs still in the fit stand off the plan under `at`, and the squared
  // offsets of those on it.
  auto tally = [&](const Pose2& at, const std::vector<bool>& out_of_fit, int* off, double* sse) {
    *off = 0, *sse = 0.0;
    for (size_t k = 0; k < all.size(); ++k) {
      if (out_of_fit[k]) continue;
      const auto m = measure_pair(at, all[k]);
      if (off_plan(m))
        ++*off;
      else
        *sse += m.first * m.first;
    }
  };
  // At most half of the pairs are left out: where more stand off, there is no consensus to
  // refit to (and the rounds stay bounded: O(n^2) fits at worst).
  Pose2 pose = h.pose;
  for (size_t round = 0; 2 * round < all.size(); ++round) {
    int off = 0;
    double sse = 0.0;
    tally(pose, left_out, &off, &sse);
    if (off == 0) break;  // the pairs left fit the plan
    int best = -1, best_off = 0;
    double best_sse = 0.0;
    Pose2 best_pose = pose;
    for (size_t k = 0; k < all.size(); ++k) {
      if (left_out[k]) continue;
      left_out[k] = true;
      const Pose2 trial = refit(left_out);
      int trial_off = 0;
      double trial_sse = 0.0;
      tally(trial, left_out, &trial_off, &trial_sse);
      left_out[k] = false;
      if (best < 0 || trial_off < best_off || (trial_off == best_off && trial_sse < best_sse))
        best = static_cast<int>(k), best_off = trial_off, best_sse = trial_sse, best_pose = trial;
    }
    if (best < 0) break;
    left_out[best] = true;
    pose = best_pose;
  }
  std::vector<SurfaceDeviation> out;
  std::set<std::pair<int, int>> seen;  // (S-plane, A-surface) reported
  auto report = [&](const PlaneFeature& a_plane, int s_id, double offset, double angle,
                    bool paired) {
    std::vector<int> pieces = a_plane.pieces;
    if (pieces.empty()) pieces = {a_plane.id};
    for (int a_id : pieces)
      if (seen.insert({s_id, a_id}).second) out.push_back({a_id, s_id, offset, angle, paired});
  };
  for (const auto& m : h.members) {
    const RoomDescriptor& s = s_rooms[m.s_room];
    const RoomDescriptor& a = a_rooms_[m.a_room];
    std::vector<int> pair_of(s.planes.size(), -1);  // S-plane index -> A-plane index
    std::vector<bool> a_used(a.planes.size(), false);
    for (const auto& [i, j] : m.evaluation.surfaces) pair_of[i] = j, a_used[j] = true;
    for (size_t i = 0; i < s.planes.size(); ++i) {
      if (pair_of[i] >= 0) {
        const PlaneFeature& q = a.planes[pair_of[i]];
        const auto m = measure(pose, s, i, a, q);
        if (off_plan(m)) report(q, s.planes[i].id, m.first, m.second, true);
        continue;
      }
      // Unpaired: the nearest A-surface of this room facing the same way that no S-plane took
      // (one that did is on the plan: this plane is something in front of it).
      int best = -1;
      double best_offset = 0.0, best_angle = 0.0;
      for (size_t j = 0; j < a.planes.size(); ++j) {
        if (a_used[j]) continue;
        const auto [offset, angle] = measure(pose, s, i, a, a.planes[j]);
        if (std::abs(angle) > max_turn || std::abs(offset) > config_.deviation_max_offset) continue;
        if (best < 0 || std::abs(offset) < std::abs(best_offset))
          best = static_cast<int>(j), best_offset = offset, best_angle = angle;
      }
      if (best >= 0) {
        a_used[best] = true;
        report(a.planes[best], s.planes[i].id, best_offset, best_angle, false);
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const SurfaceDeviation& x, const SurfaceDeviation& y) {
    return std::tie(x.s_id, x.a_id) < std::tie(y.s_id, y.a_id);
  });
  return out;
}

}  // namespace matching
}  // namespace is_graphs
