#pragma once

#include <cstdlib>
// Helpers of the matcher tests: the project's buildings through the real converter (cached),
// and what "a correct match" means.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "converter_check.h"
#include "is_graphs/agraph/ifc_conversion.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/graph_match.h"
#include "is_graphs/matching/synthetic_sgraph.h"

namespace is_graphs {
namespace testing {

/// The A-Graph of `path` (an IFC converted with the real converter, cached per process), or
/// nullptr when the file or the converter is missing (the caller skips).
inline const agraph::AGraph* LoadBuildingOnce(const std::string& path, std::string* why) {
  static std::map<std::string, std::unique_ptr<agraph::AGraph>> cache;
  auto it = cache.find(path);
  if (it != cache.end()) return it->second.get();
  std::unique_ptr<agraph::AGraph> graph;
  const agraph::IfcConversionConfig config;
  if (!std::filesystem::exists(path)) {
    *why = path + " is not there";
  } else if (!std::filesystem::exists(config.converter) ||
             !std::filesystem::exists(config.python)) {
    *why = "no IFC converter (" + config.python + " " + config.converter + "): run make setup";
  } else if (!IfcConverterMissing().empty()) {
    *why = IfcConverterMissing();
  } else {
    auto loaded = agraph::LoadBim(path, config);
    if (loaded.ok())
      graph = std::make_unique<agraph::AGraph>(std::move(loaded).value());
    else
      *why = loaded.error();
  }
  return (cache[path] = std::move(graph)).get();
}

/// A vertical wall-surface of a hand-made A-Graph: from a to b, its normal out of the material.
inline agraph::WallSurface MakeSurface(int id, int wall, int storey, const Eigen::Vector2d& a,
                                       const Eigen::Vector2d& b, const Eigen::Vector2d& normal) {
  agraph::WallSurface s;
  s.plane = geometry::Plane(Eigen::Vector3d(normal.x(), normal.y(), 0.0), normal.dot(a));
  s.id = id;
  s.wall = wall;
  s.storey = storey;
  s.start = a;
  s.end = b;
  return s;
}

/// A synthetic S-Graph's config with the matcher tests' usual noise (1 deg normals, 3 cm
/// offsets, 10 cm centres, BIM off by 5 cm), at B_x_M (x, y, yaw).
inline matching::SyntheticSGraphConfig Noisy(std::uint64_t seed, double yaw, double x, double y) {
  matching::SyntheticSGraphConfig c;
  c.bim_T_map = geometry::IsometryFromXYYaw(x, y, yaw);
  c.normal_noise_deg = 1.0;
  c.offset_noise = 0.03;
  c.centre_noise = 0.1;
  c.bim_deviation = 0.05;
  c.seed = seed;
  return c;
}

inline std::string ProjectBim(const std::string& name) {
  return std::string(IS_GRAPHS_SOURCE_DIR) + "/bim/" + name;
}

inline int RoomByName(const agraph::AGraph& g, const std::string& name) {
  for (const auto& r : g.rooms)
    if (r.name == name) return r.id;
  ADD_FAILURE() << "no room named " << name;
  return -1;
}

/// The campaigns' buildings: the project's own and every IFC in ../shared/bim that converts.
inline std::vector<std::pair<std::string, const agraph::AGraph*>> CampaignBuildings() {
  std::vector<std::pair<std::string, const agraph::AGraph*>> buildings;
  for (const char* name : {"office.ifc", "rotated.ifc", "large.ifc", "symmetric.ifc"}) {
    std::string why;
    if (const auto* g = LoadBuildingOnce(ProjectBim(name), &why)) buildings.emplace_back(name, g);
  }
  const std::string shared = IS_GRAPHS_SHARED_BIM_DIR;
  if (std::filesystem::exists(shared)) {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(shared))
      if (e.path().extension() == ".ifc") files.push_back(e.path());
    std::sort(files.begin(), files.end());  // directory order is not deterministic
    for (const auto& f : files) {
      std::string why;
      if (const auto* g = LoadBuildingOnce(f.string(), &why))
        buildings.emplace_back(f.filename().string(), g);
    }
  }
  return buildings;
}

/// Whether S-room `s_id` of `s`, one the BIM lacks (a room the campaign placed at random),
/// stands where A-room `a_id` of `building` is under the true motion, as the campaign builds a
/// BIM room off the plan: its centre within 0.6 m of the A-room's (the bound every room is placed
/// within) and at least three of its planes within 10° and 0.4 m of the A-room's surfaces (the
/// harsh campaign moves walls by up to 35 cm, with 5 cm of offset noise). Placed on a BIM room
/// by chance (seed 17 trial 348, seed 28 trial 319 of 40 000 harsh trials), it is that room
/// built off the plan to any sensor: its pair is right.
inline bool StandsOnTheARoom(const matching::SyntheticSGraph& s, int s_id,
                             const agraph::AGraph& building, int a_id) {
  const sgraph::Room* room = nullptr;
  for (const auto& r : s.graph.rooms)
    if (r.id == s_id) room = &r;
  const agraph::Room* a = nullptr;
  for (const auto& r : building.rooms)
    if (r.id == a_id) a = &r;
  if (!room || !a) return false;
  const Eigen::Vector3d centre = s.bim_T_map * room->center;
  if ((centre - a->center).head<2>().norm() > 0.6) return false;
  int on_surfaces = 0;
  for (int plane_id : room->planes)
    for (const auto& p : s.graph.planes) {
      if (p.id != plane_id) continue;
      const geometry::Plane moved = p.plane.Transformed(s.bim_T_map);
      const Eigen::Vector3d foot = moved.Project(centre);
      bool on = false;
      for (int surface : a->surfaces)
        for (const auto& w : building.surfaces)
          if (w.id == surface && std::abs(w.plane.normal.dot(moved.normal)) >= std::cos(0.1745) &&
              std::abs(w.plane.SignedDistance(foot)) <= 0.4)
            on = true;
      on_surfaces += on;
    }
  return on_surfaces >= 3;
}

/// The motion is the true one (at every S-room) and every room pair is a true pair: the S-room's
/// own A-room, or, for an S-room the BIM lacks and with `building` given, an A-room it stands on
/// under the true motion (StandsOnTheARoom).
inline bool MatchIsCorrect(const matching::GraphMatch& m, const matching::SyntheticSGraph& s,
                           std::string* why = nullptr, const agraph::AGraph* building = nullptr) {
  const Eigen::Isometry3d& truth = s.bim_T_map;
  const double yaw_error =
      std::abs(geometry::NormalizeAngle(geometry::Yaw(m.bim_T_map) - geometry::Yaw(truth)));
  std::ostringstream out;
  bool ok = yaw_error < 3.0 * M_PI / 180.0;
  if (!ok) out << "yaw off by " << yaw_error * 180.0 / M_PI << " deg; ";
  for (const auto& r : s.graph.rooms) {
    const Eigen::Vector3d c(r.center.x(), r.center.y(), 0.0);
    const double e = ((m.bim_T_map * c) - (truth * c)).head<2>().norm();
    if (e > 0.6) ok = false, out << "room " << r.id << " placed " << e << " m off; ";
  }
  // The mapped walls and the walk placed where they are (a match from wall planes alone has no
  // room to check). A plane far from the walk (seen through a doorway, 15 m away) may be off by
  // what the yaw tolerance allows there too: 0.6 m + its distance to the nearest keyframe x
  // sin 3°. (A right match, its rooms and walk within 0.3 m, put planes seen 20 m away 0.8 m
  // off under the harsh campaign's 3° normal noise; at a fixed 0.6 m that counted as wrong.)
  for (const auto& p : s.graph.planes) {
    if (!p.start.allFinite() || !p.end.allFinite()) continue;
    const Eigen::Vector2d mid = 0.5 * (p.start + p.end);
    const Eigen::Vector3d c(mid.x(), mid.y(), 0.0);
    const double e = ((m.bim_T_map * c) - (truth * c)).head<2>().norm();
    double lever = s.graph.keyframes.empty() ? 0.0 : std::numeric_limits<double>::infinity();
    for (const auto& k : s.graph.keyframes)
      lever = std::min(lever, (k.pose.translation().head<2>() - mid).norm());
    if (e > 0.6 + lever * std::sin(3.0 * M_PI / 180.0)) {
      ok = false, out << "plane " << p.id << " placed " << e << " m off; ";
      break;
    }
  }
  for (const auto& k : s.graph.keyframes) {
    const Eigen::Vector3d c(k.pose.translation().x(), k.pose.translation().y(), 0.0);
    const double e = ((m.bim_T_map * c) - (truth * c)).head<2>().norm();
    if (e > 0.6) {
      ok = false, out << "keyframe " << k.id << " placed " << e << " m off; ";
      break;
    }
  }
  for (const auto& p : m.room_pairs) {
    const auto it = s.room_truth.find(p.s_id);
    if (it != s.room_truth.end() ? it->second != p.a_id
                                 : !building || !StandsOnTheARoom(s, p.s_id, *building, p.a_id))
      ok = false, out << "pair S" << p.s_id << "-A" << p.a_id << " is wrong; ";
  }
  if (why) *why = out.str();
  return ok;
}

/// A randomized campaign's seed: IS_GRAPHS_SEED when set, else `fallback`.
inline std::uint64_t CampaignSeed(std::uint64_t fallback) {
  const char* env = std::getenv("IS_GRAPHS_SEED");
  return env && *env ? std::strtoull(env, nullptr, 10) : fallback;
}

/// The tally of a randomized matching campaign, overall and per building.
struct CampaignTally {
  int trials{0}, unique{0}, ambiguous{0}, none{0}, wrong{0};
  std::map<std::string, std::array<int, 4>> per_building;  // trials, unique, ambiguous, wrong

  /// Counts one answer; a wrong UNIQUE fails the test, naming the trial (`what`) and why.
  void Add(const std::string& building, const matching::GraphMatch& m,
           const matching::SyntheticSGraph& s, const std::string& what,
           const agraph::AGraph* graph = nullptr) {
    auto& b = per_building[building];
    ++trials, ++b[0];
    if (m.status == matching::MatchStatus::kUnique) {
      ++unique, ++b[1];
      std::string why;
      if (!MatchIsCorrect(m, s, &why, graph)) {
        ++wrong, ++b[3];
        ADD_FAILURE() << what << ": wrong UNIQUE: " << why;
      }
    } else if (m.status == matching::MatchStatus::kAmbiguous) {
      ++ambiguous, ++b[2];
    } else {
      ++none;
    }
  }

  void Print(const std::string& tag, double seconds, const std::string& extra = "") const {
    std::cout << "[ " << tag << " ] " << trials << " trials in " << seconds << " s" << extra
              << ": UNIQUE " << unique << " (" << 100.0 * unique / std::max(trials, 1)
              << " %), AMBIGUOUS " << ambiguous << ", NONE " << none << ", wrong UNIQUE " << wrong
              << std::endl;
    for (const auto& [name, st] : per_building)
      std::cout << "[ " << tag << " ]   " << name << ": " << st[0] << " trials, UNIQUE " << st[1]
                << ", AMBIGUOUS " << st[2] << ", wrong " << st[3] << std::endl;
  }
};

}  // namespace testing
}  // namespace is_graphs

#define IS_GRAPHS_BUILDING_OR_SKIP(var, path)                              \
  std::string var##_why;                                                   \
  const agraph::AGraph* var = testing::LoadBuildingOnce(path, &var##_why); \
  if (!var) GTEST_SKIP() << var##_why
