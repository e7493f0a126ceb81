#pragma once

#include <map>
#include <vector>

namespace is_graphs {
namespace matching {

/// Issue 22: the storeys the robot can stand on now, from the heights of the levels it walked
/// alone (no storey known: a storey identified from the stairs). Storey s fits the current
/// level c when, for another level l walked, the building has a storey at
/// elevation(s) + (h_l − h_c) within `tolerance` + `per_metre` |h_l − h_c| (a floor's surface
/// above its storey's elevation, the odometry misjudging a rise). Returned: the storeys that fit
/// the most other levels (a level the walk made of a long landing fits none and so rules out
/// none); empty, for "any storey", when none fits even one (a walk off the building's storeys:
/// no height to go by) or no other level was walked.
/// `elevations`: storey id -> elevation in B; `levels`: level -> height in M of its first
/// keyframe (sgraph levels); `current`: the level of the newest keyframe.
std::vector<int> StoreysFittingLevels(const std::map<int, double>& elevations,
                                      const std::map<int, double>& levels, int current,
                                      double tolerance, double per_metre);

}  // namespace matching
}  // namespace is_graphs
