// ClassifyWalls: as-built against as-planned per IFC wall (issue 21; docs/deviations.md).
#include "is_graphs/merging/wall_deviations.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "is_graphs/geometry/se3.h"
#include "wall_consensus.h"
#include "wall_sight_lines.h"

namespace is_graphs {
namespace merging {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

/// An S-plane of the A-surface's: where it stands off it and how much of it it covers.
struct SurfaceFit {
  int plane{-1};  // index into the planes in B
  double offset{0.0}, angle{0.0}, overlap{0.0};
};

/// How S-plane `p` stands against the A-surface `s`; nullopt-like plane -1 when it is not it.
SurfaceFit Fit(const agraph::WallSurface& s, const detail::PlaneInB& p,
               const WallDeviationConfig& config) {
  SurfaceFit fit;
  const Eigen::Vector2d an = s.plane.normal.head<2>().normalized();
  const double angle = geometry::SignedTurn(an, p.normal);
  if (std::abs(angle) > config.max_angle_deg * kDegToRad) return fit;
  const Eigen::Vector2d mid = 0.5 * (s.start + s.end);
  const double offset = (p.d - p.normal.dot(mid)) / p.normal.dot(an);
  if (std::abs(offset) > config.max_offset) return fit;
  const double length = s.Length();
  if (length <= 0.0) return fit;
  const Eigen::Vector2d t = (s.end - s.start) / length;
  const double u1 = (p.start - s.start).dot(t), u2 = (p.end - s.start).dot(t);
  const double overlap = std::min(length, std::max(u1, u2)) - std::max(0.0, std::min(u1, u2));
  if (overlap < std::min(config.min_overlap, 0.5 * length)) return fit;
  fit.offset = offset, fit.angle = angle, fit.overlap = overlap, fit.plane = 0;
  return fit;
}

/// EXTRA entries from the unexplained wall-height planes; a wall's two faces make one entry.
std::vector<WallDeviation> Extras(const std::vector<detail::PlaneInB>& planes,
                                  const std::vector<bool>& explained,
                                  const WallDeviationConfig& config) {
  std::vector<int> candidates;
  for (size_t i = 0; i < planes.size(); ++i)
    if (!explained[i] && planes[i].Length() >= config.extra_min_length &&
        planes[i].height >= config.extra_min_height && planes[i].views >= config.extra_min_views)
      candidates.push_back(static_cast<int>(i));
  std::vector<bool> used(planes.size(), false);
  std::vector<WallDeviation> out;
  for (int i : candidates) {
    if (used[i]) continue;
    used[i] = true;
    const detail::PlaneInB& p = planes[i];
    WallDeviation e;
    e.status = WallStatus::kExtra;
    e.s_planes = {p.id};
    e.height = p.height;
    e.normal = p.normal;
    const Eigen::Vector2d t = (p.end - p.start).normalized();
    double lo = 0.0, hi = p.Length();
    for (int j : candidates) {  // the wall's other face: opposed, within a wall's thickness
      const detail::PlaneInB& q = planes[j];
      if (used[j] || p.normal.dot(q.normal) > -std::cos(10.0 * kDegToRad)) continue;
      const Eigen::Vector2d qm = 0.5 * (q.start + q.end);
      if (std::abs(p.normal.dot(qm) - p.d) > 0.4) continue;
      const double v1 = (q.start - p.start).dot(t), v2 = (q.end - p.start).dot(t);
      if (std::min(hi, std::max(v1, v2)) - std::max(lo, std::min(v1, v2)) <= 0.0) continue;
      used[j] = true;
      e.s_planes.push_back(q.id);
      e.height = std::max(e.height, q.height);
      lo = std::min(lo, std::min(v1, v2)), hi = std::max(hi, std::max(v1, v2));
    }
    e.start = p.start + lo * t, e.end = p.start + hi * t;
    out.push_back(e);
  }
  return out;
}

/// Each A-surface's best S-plane (most overlap, then least offset); `explained`: the planes
/// near any A-surface.
std::map<int, SurfaceFit> BestFits(const std::map<int, const agraph::WallSurface*>& surfaces,
                                   const std::vector<detail::PlaneInB>& planes,
                                   const WallDeviationConfig& config,
                                   std::vector<bool>* explained) {
  explained->assign(planes.size(), false);
  std::map<int, SurfaceFit> best;
  for (const auto& [id, s] : surfaces)
    for (size_t i = 0; i < planes.size(); ++i) {
      SurfaceFit f = Fit(*s, planes[i], config);
      if (f.plane < 0) continue;
      f.plane = static_cast<int>(i);
      (*explained)[i] = true;
      auto it = best.find(id);
      if (it == best.end() || f.overlap > it->second.overlap + 1e-9 ||
          (std::abs(f.overlap - it->second.overlap) <= 1e-9 &&
           std::abs(f.offset) < std::abs(it->second.offset)))
        best[id] = f;
    }
  return best;
}

}  // namespace

const char* ToString(WallStatus status) {
  switch (status) {
    case WallStatus::kAsPlanned:
      return "AS_PLANNED";
    case WallStatus::kMoved:
      return "MOVED";
    case WallStatus::kNotBuilt:
      return "NOT_BUILT";
    case WallStatus::kExtra:
      return "EXTRA";
    case WallStatus::kNotSeen:
      return "NOT_SEEN";
  }
  return "?";
}

std::string WallDeviationConfig::Validate() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(planned_offset)) return "planned_offset: must be > 0 m";
  if (!positive(planned_angle_deg)) return "planned_angle_deg: must be > 0";
  if (!positive(max_offset) || max_offset <= planned_offset)
    return "max_offset: must be > planned_offset";
  if (!positive(max_angle_deg) || max_angle_deg <= planned_angle_deg || max_angle_deg >= 80.0)
    return "max_angle_deg: must be in (planned_angle_deg, 80)";
  if (!positive(min_overlap)) return "min_overlap: must be > 0 m";
  if (!positive(extra_min_length)) return "extra_min_length: must be > 0 m";
  if (!std::isfinite(extra_min_height) || extra_min_height < 0.0)
    return "extra_min_height: must be >= 0 m";
  if (extra_min_views < 1) return "extra_min_views: must be >= 1";
  if (!std::isfinite(door_margin) || door_margin < 0.0) return "door_margin: must be >= 0 m";
  if (not_built_min_rays < 1) return "not_built_min_rays: must be >= 1";
  return "";
}

Eigen::Isometry3d ConsensusBimTMap(const agraph::AGraph& building, const sgraph::SGraph& graph,
                                   const Eigen::Isometry3d& bim_T_map,
                                   const WallDeviationConfig& config) {
  std::map<int, const agraph::WallSurface*> surfaces;
  for (const auto& s : building.surfaces) surfaces[s.id] = &s;
  std::vector<bool> explained;
  const std::map<int, SurfaceFit> best =
      BestFits(surfaces, detail::PlanesInB(graph, bim_T_map), config, &explained);
  // A wall's faces are one piece of evidence: each weighs its overlap / the faces seen.
  std::map<int, int> faces_seen;
  for (const auto& [id, f] : best) ++faces_seen[surfaces[id]->wall];
  std::vector<detail::SeenSurface> seen;
  for (const auto& [id, f] : best) {
    const agraph::WallSurface& s = *surfaces[id];
    seen.push_back({s.plane.normal.head<2>().normalized(), 0.5 * (s.start + s.end), f.offset,
                    f.angle, f.overlap / faces_seen[s.wall]});
  }
  // Robust scales half the AS_PLANNED tolerances: a wall off by more hardly pulls.
  return detail::ConsensusCorrection(seen, 0.5 * config.planned_offset,
                                     0.5 * config.planned_angle_deg * kDegToRad) *
         bim_T_map;
}

std::vector<WallDeviation> ClassifyWalls(const agraph::AGraph& building,
                                         const sgraph::SGraph& graph,
                                         const Eigen::Isometry3d& bim_T_map,
                                         const WallDeviationConfig& config) {
  std::map<int, const agraph::WallSurface*> surfaces;
  for (const auto& s : building.surfaces) surfaces[s.id] = &s;
  // Against the merge's B_x_M corrected by the consensus of the walls seen (the merge can be
  // pulled a little by walls built off the plan).
  const Eigen::Isometry3d corrected = ConsensusBimTMap(building, graph, bim_T_map, config);
  const std::vector<detail::PlaneInB> planes = detail::PlanesInB(graph, corrected);
  std::vector<bool> explained;
  std::map<int, SurfaceFit> best = BestFits(surfaces, planes, config, &explained);
  const std::vector<detail::PathStep> path = detail::WalkedPathInB(graph, corrected);
  const double z_robot = detail::RobotHeight(graph, corrected);  // the storey walked on
  std::vector<WallDeviation> out;
  for (const auto& w : building.walls) {
    WallDeviation r;
    r.wall_id = w.id, r.guid = w.guid, r.name = w.name;
    const agraph::WallSurface* a = surfaces.count(w.surface_a) ? surfaces[w.surface_a] : nullptr;
    const agraph::WallSurface* b = surfaces.count(w.surface_b) ? surfaces[w.surface_b] : nullptr;
    const agraph::WallSurface* first = a ? a : b;
    if (!first || z_robot < first->z_min - 0.5 || z_robot > first->z_max) continue;  // storey
    const Eigen::Vector2d n_first = first->plane.normal.head<2>().normalized();
    const double along = a ? 1.0 : -1.0;  // offsets along surface_a's normal
    r.normal = along * n_first;
    // The mid-line is half the thickness behind the face, whichever face it is.
    r.start = first->start - 0.5 * w.thickness * n_first;
    r.end = first->end - 0.5 * w.thickness * n_first;
    double weight = 0.0, offset = 0.0, angle = 0.0;
    std::vector<double> offsets;
    for (const agraph::WallSurface* s : {a, b}) {
      if (!s || !best.count(s->id)) continue;
      const SurfaceFit& f = best[s->id];
      const detail::PlaneInB& p = planes[f.plane];
      const double sign = along * s->plane.normal.head<2>().normalized().dot(n_first) >= 0 ? 1 : -1;
      const double var = std::max(p.offset_variance, 0.005 * 0.005);
      weight += 1.0 / var, offset += sign * f.offset / var, angle += f.angle / var;
      offsets.push_back(sign * f.offset);
      r.s_planes.push_back(p.id);
    }
    if (weight > 0.0) {
      r.offset = offset / weight, r.angle = angle / weight, r.sigma = std::sqrt(1.0 / weight);
      if (offsets.size() == 2) r.sigma = std::max(r.sigma, 0.5 * std::abs(offsets[0] - offsets[1]));
      const bool planned = std::abs(r.offset) <= config.planned_offset &&
                           std::abs(r.angle) <= config.planned_angle_deg * kDegToRad;
      r.status = planned ? WallStatus::kAsPlanned : WallStatus::kMoved;
    } else {
      std::vector<detail::Gap> doors;
      for (const auto& d : building.doorways)
        if (d.wall == w.id && d.InWall())
          doors.push_back({d.position.head<2>(), 0.5 * d.width + config.door_margin});
      r.rays_through = detail::RaysThrough(r.start, r.end, doors, planes, path);
      r.status = r.rays_through >= config.not_built_min_rays ? WallStatus::kNotBuilt
                                                             : WallStatus::kNotSeen;
    }
    out.push_back(r);
  }
  for (auto& e : Extras(planes, explained, config)) out.push_back(std::move(e));
  return out;
}

}  // namespace merging
}  // namespace is_graphs
