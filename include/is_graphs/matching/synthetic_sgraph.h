#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace matching {

/// How to make an S-Graph from an A-Graph (for tests and the benchmark, before the S-Graph node
/// exists): the chosen rooms' surfaces as planes in a map frame M related to B by a planar rigid
/// motion, with noise, BIM deviations, clutter and rooms the BIM does not have. Clutter planes
/// are 1-2.5 m long and 1.2-2.2 m high (a cupboard, a screen: taken for a wall by their size),
/// extra rooms' planes as long as their sides; their extents come from the harsh stream.
struct SyntheticSGraphConfig {
  std::vector<int> rooms;                                      // A-room ids to take; empty: all
  Eigen::Isometry3d bim_T_map{Eigen::Isometry3d::Identity()};  // the truth (yaw + translation)
  bool mirror{false};             // reflect M (x -> -x): the mirror image of the building
  double normal_noise_deg{0.0};   // σ of each plane's normal direction (its ends move <= 10 cm)
  double offset_noise{0.0};       // σ of each plane's offset [m]
  double centre_noise{0.0};       // σ of each room centre, per axis [m]
  double bim_deviation{0.0};      // each wall-surface built up to this far from the BIM [m]
  double corridor_aspect{3.0};    // rooms this elongated become two-plane corridors (<= 0: never)
  double corridor_shift{0.3};     // a corridor's centre moves along its axis by up to this share
  int extra_planes{0};            // clutter planes added to random rooms
  int extra_rooms{0};             // rectangular rooms that are not in the BIM
  double split_probability{0.0};  // a surface bounding several rooms becomes one plane per room
  // --- harsh (drawn from their own stream: the fields above give the same graph with or without)
  int moved_walls{0};                 // surfaces of the taken rooms built off the plan by ...
  double moved_wall_min{0.25};        // ... at least this and at most moved_wall_max [m],
  double moved_wall_max{0.35};        //     either way along the normal
  int turned_walls{0};                // surfaces built turned about their middle by ...
  double turned_wall_deg{15.0};       // ... up to this, either way
  int missing_walls{0};               // surfaces of the taken rooms not built (no plane)
  bool walk{false};                   // keyframes along a walk through the rooms' doorways
  double walk_spacing{0.8};           // m between keyframes
  double walk_noise{0.0};             // σ of each keyframe's position, per axis [m]
  int through_walls{0};               // walks through walls the plan has (openings it lacks)
  std::vector<int> seen_rooms;        // A-rooms whose surfaces are mapped as planes of no S-room
                                      // (seen through a doorway), each 40-100 % of it
  bool doorways{false};               // S-Graph doorways found on the walk (sgraph::DetectDoorways)
  double missing_doorway_share{0.0};  // each one dropped with this probability
  int extra_doorways{0};              // doorways on random S-room planes, where the BIM has none
  // Observations of the planes of no S-room from the walk's keyframes within 10 m that had a
  // clear sight line to them in the building as built (not with `mirror`): ...
  bool observations{false};
  int unbuilt_walls{0};  // ... where this many interior walls of the taken rooms were not built
  std::uint64_t seed{1};
};

struct SyntheticSGraph {
  sgraph::SGraph graph;
  Eigen::Isometry3d bim_T_map{Eigen::Isometry3d::Identity()};
  std::map<int, int> room_truth;   // S-room id -> A-room id (extra rooms absent)
  std::map<int, int> plane_truth;  // S-plane id -> A-wall-surface id (clutter absent)
  std::map<int, double> moved;     // A-surface id -> metres built off the plan (harsh)
  std::map<int, double> turned;    // A-surface id -> radians built turned (harsh)
  std::vector<int> missing;        // A-surface ids not built (harsh)
  std::vector<int> unbuilt;        // A-wall ids not built, seen through (observations)
};

SyntheticSGraph MakeSyntheticSGraph(const agraph::AGraph& building,
                                    const SyntheticSGraphConfig& config);

/// Adds to s.graph the observations of its planes of no S-room from its keyframes within 10 m
/// that had a clear sight line to them (WallCrossings::Blocks, under the truth) in the building
/// as built: the plan less config.unbuilt_walls interior walls of config.rooms (drawn from
/// config.seed; recorded in s.unbuilt); each such plane's extent is cut to the part of it seen
/// (as the S-Graph maps it). MakeSyntheticSGraph calls it with `observations`.
void AddSyntheticObservations(const agraph::AGraph& building, const SyntheticSGraphConfig& config,
                              SyntheticSGraph& s);

/// A motion about z by a uniform yaw with a translation uniform in [-max, max]².
Eigen::Isometry3d RandomPlanarMotion(std::mt19937_64& rng, double max_translation);

/// `count` rooms a robot could have walked through: a random start room, then random rooms
/// adjacent through doorways (falling back to the nearest rooms when doorways run out).
std::vector<int> RandomConnectedRooms(const agraph::AGraph& building, int count,
                                      std::mt19937_64& rng);

/// Whether a room is elongated enough to be seen as a corridor (the generator's rule).
bool IsCorridorLike(const agraph::AGraph& building, int room, double min_aspect);

}  // namespace matching
}  // namespace is_graphs
