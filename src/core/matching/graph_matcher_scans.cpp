// The scan search's part in GraphMatcher::Propose: the poses the newest keyframes' slices
// cannot tell apart (ScanSearch, certified by its bound) on every storey a proposal may be on.
#include <algorithm>
#include <chrono>
#include <sstream>

#include "is_graphs/matching/graph_matcher.h"

namespace is_graphs {
namespace matching {

const GraphMatcher::ScanView& GraphMatcher::SearchScans(const sgraph::SGraph& graph) {
  if (!config_.scan_proposals) {
    scan_view_ = ScanView();
    return scan_view_;
  }
  // The slices of the keyframes on the newest keyframe's level, in M.
  // What the set is made of: the slices (by keyframe id, stamp, size and first point: keyframe
  // ids start again with a new S-Graph), the storeys searched. Their keyframes' poses move by
  // the optimization's centimetres meanwhile: the set is not made again for that.
  std::vector<double> key;
  const int level = graph.keyframes.empty() ? 0 : graph.keyframes.back().level;
  for (const sgraph::Keyframe& k : graph.keyframes)
    if (!k.slice.empty() && k.level == level)
      key.insert(key.end(),
                 {static_cast<double>(k.id), k.stamp, static_cast<double>(k.slice.size()),
                  k.slice.front().x(), k.slice.front().y()});
  key.push_back(only_storey_);
  for (int s : storeys_walked_) key.push_back(s);
  if (key == scan_view_.key && !scan_view_.summary.empty()) return scan_view_;
  const auto t0 = std::chrono::steady_clock::now();
  ScanView view;
  view.key = key;
  view.margin = config_.scan_search.margin;
  std::vector<Eigen::Vector2d> points;
  for (const sgraph::Keyframe& k : graph.keyframes) {
    if (k.slice.empty() || k.level != level) continue;
    for (const Eigen::Vector3f& p : k.slice)
      points.push_back((k.pose * p.cast<double>()).head<2>());
  }
  std::ostringstream why;
  why.precision(3);
  bool too_many = false, searched = false;
  std::vector<ScanPoseOn> all;
  for (const auto& [storey, elevation] : storey_elevations_) {
    (void)elevation;
    if (!StoreyWalkable(storey) || (only_storey_ >= 0 && storey != only_storey_)) continue;
    if (!scan_.HasWalls(storey)) continue;
    const ScanSearchResult r = scan_.Search(points, storey);
    if (r.status == ScanSearchResult::Status::kTooFewPoints) {
      why << r.reason;
      break;
    }
    if (r.status == ScanSearchResult::Status::kNoWalls) continue;
    searched = true;
    if (r.status == ScanSearchResult::Status::kTooMany) {
      too_many = true;
      why << "storey " << storey << ": " << r.reason;
      break;
    }
    for (const ScanPose& p : r.set) all.push_back({p.bim_T_map, storey, p.score});
  }
  if (!too_many && searched && why.str().empty()) {
    std::stable_sort(all.begin(), all.end(),
                     [](const ScanPoseOn& a, const ScanPoseOn& b) { return a.score > b.score; });
    view.best = all.empty() ? 0.0 : all.front().score;
    for (const ScanPoseOn& p : all)
      if (p.score >= view.best - view.margin) view.set.push_back(p);
    // Every pose of a walkable storey was searched; the set holds those the bound could not
    // rule out, so a pose outside it scores less than best - margin.
    view.certified =
        !view.set.empty() && static_cast<int>(view.set.size()) <= config_.scan_search.max_set;
    why << view.set.size() << (view.set.size() == 1 ? " pose" : " poses") << " within "
        << view.margin << " of the best " << view.best << " (" << points.size() << " points)";
    if (view.set.size() > 1) {
      why << ": scores";
      for (size_t i = 0; i < view.set.size() && i < 4; ++i) why << " " << view.set[i].score;
    }
    if (!view.certified) why << ": too many to decide on";
  } else if (!searched && why.str().empty()) {
    why << "no storey with walls at the slice's height";
  }
  view.summary = why.str();
  view.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  scan_view_ = std::move(view);
  return scan_view_;
}

bool GraphMatcher::InScanSet(const Hypothesis& h,
                             const std::vector<Eigen::Vector2d>& points) const {
  if (!scan_view_.certified) return true;
  return std::any_of(scan_view_.set.begin(), scan_view_.set.end(), [&](const ScanPoseOn& p) {
    return p.storey == h.storey && SameMotion(p.pose, h.pose, points, config_);
  });
}

}  // namespace matching
}  // namespace is_graphs
