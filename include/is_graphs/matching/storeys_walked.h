#pragma once

#include <map>
#include <optional>
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

/// Issue 22: the storeys the current level can be on, from levels whose storey a UNIQUE match
/// named (`known`: level -> storey id): storey s fits when, for every known level l other than
/// `current`, elevation(s) lies within `tolerance` + `per_metre` |h_c − h_l| of
/// elevation(known[l]) + (h_c − h_l): after a climb from a storey identified, the next one
/// follows from the height walked, twin floors or not. nullopt (no constraint) when no other
/// level is known; empty when no storey is at that height (a landing, a walk off the
/// building's storeys: nothing to match there).
std::optional<std::vector<int>> StoreysFromKnownLevels(const std::map<int, double>& elevations,
                                                       const std::map<int, double>& levels,
                                                       const std::map<int, int>& known, int current,
                                                       double tolerance, double per_metre);

}  // namespace matching
}  // namespace is_graphs
