#pragma once

#include <string>

#include "is_graphs/matching/scan_search.h"

namespace is_graphs {
namespace matching {

/// Every tolerance and weight of the A-Graph <-> S-Graph matcher (config/matcher.yaml documents
/// the ROS parameters of the same names). Lengths in metres, angles in degrees.
struct MatcherConfig {
  // --- local (room pair) candidates ---
  double angle_tolerance_deg{8.0};  // an S-plane and an A-surface normal, after the yaw
  double offset_tolerance{0.3};     // plane offset residual (BIM deviations, noise)
  double centre_tolerance{0.6};     // room centre residual (centres of polygons are vague)
  double min_plane_fraction{0.6};   // share of a room's S-planes that must find an A-surface
  // A room whose S-centre a plane standing in it moved (a stair's side, a cabinet run taken for
  // its bound) is paired through its other walls (PairEvaluation::centre_off).
  bool pair_through_walls{true};
  // --- global candidates (combining room pairs) ---
  double yaw_tolerance_deg{6.0};  // room pairs of one hypothesis agree on the yaw this well
  double lever_arm_slack{0.035};  // extra tolerance per metre from the seed room (yaw error)
  double quality_sigma{0.12};     // plane residual of a room pair -> quality exp(-r²/2σ²)
  double corridor_weight{0.75};   // weight of a corridor pair in the score (a room counts 1)
  // --- evidence beyond the pairs (the score of a hypothesis) ---
  double wall_crossing_penalty{0.25};  // per BIM wall the walked path crosses under it
  double door_margin{0.4};             // a crossing this far beyond a doorway's half-width
  double max_path_step{1.5};           // longer keyframe steps (scan gaps) are not checked
  // Loose wall planes (in no S-room: seen through a doorway, a corridor's end) that lie on the
  // BIM's wall-surfaces under a hypothesis (SurfaceEvidence): each adds up to
  // surface_evidence_weight to its score; 0: not used.
  double surface_evidence_weight{0.1};
  double surface_full_length{2.0};  // a plane this long counts fully, a shorter one in proportion
  double surface_min_length{1.0};   // shorter planes (or lower ones) are not taken for walls
  double surface_min_height{1.9};
  // Loose wall planes that lie, under a hypothesis, beyond the storey's outline (the convex
  // hull of its wall-surfaces) by more than outside_margin: walls the robot could only have
  // seen outside the building. Each costs up to outside_penalty (x min(1, length /
  // surface_full_length) x its share outside); 0: not used.
  double outside_penalty{0.1};
  double outside_margin{1.0};
  // Doorways the robot walked through (S-Graph doorways) lying at the BIM's doorways under a
  // hypothesis (DoorwayEvidence): each adds up to doorway_evidence_weight; 0: not used.
  double doorway_evidence_weight{0.2};
  double doorway_tolerance{0.5};         // m between an S-doorway and its A-doorway
  double doorway_width_tolerance{0.35};  // m between their widths, when both are known
  // Loose wall planes that could not have been seen under a hypothesis (HiddenWalls: every
  // sight line from the keyframes that observed them through an interior BIM wall): each costs
  // up to sight_penalty (x min(1, length / surface_full_length)); 0: not used.
  double sight_penalty{0.1};
  int sight_viewpoints{12};  // keyframes per plane whose sight lines are checked
  // A UNIQUE answer must fit the walls seen: at least unique_min_wall_share of their length
  // (SurfaceEvidence, on its storey) once they add up to unique_min_walls full-length walls;
  // else AMBIGUOUS. Right UNIQUE answers on the scenario bags fit 0.75-1.0 of them (H3's walls
  // turned 15 deg: 0.75); a roof storey's hall taken for AC11's entrance hall, 0.42-0.47.
  // 0: not used.
  double unique_min_wall_share{0.6};
  double unique_min_walls{4.0};
  // The robot on a stair: its newest keyframe this far above or below the first keyframe of its
  // S-Graph level (sgraph_node's level_tolerance), still rising or falling (sgraph::OnStair), is
  // between storeys, and the level it is counted on is the one it left: not matched (NONE)
  // until it settles. Matching there named the storey below with the robot on the floor above
  // (M4, 4 times).
  double stair_height_tolerance{0.5};
  // A storey from the stairs alone: with levels walked, the current level's storey must have
  // storeys as far above or below as the other levels, within this (m) plus
  // storey_level_tolerance_per_m of the height between them (StoreysFittingLevels); candidates
  // and proposals on other storeys are not made. A large value: any storey.
  double storey_level_tolerance{0.15};
  double storey_level_tolerance_per_m{0.03};
  double sight_door_margin{0.15};  // a sight line this far beyond a doorway's half-width is
                                   // through the wall (door_margin is for the walked path)
  // --- proposals from the first scans (CornerProposals; before a room is closed) ---
  // Motions mapping corners of the wall planes seen so far onto the BIM's corners, each scored
  // on every wall-grade plane (SurfaceEvidence, in walls: a plane surface_full_length long
  // counts 1), less proposal_crossing_penalty per BIM wall the walked path crosses and the
  // planes it could not have seen (HiddenWalls, x1). Together with the room hypotheses'
  // motions; UNIQUE when the best explains proposal_min_share of at least proposal_min_walls
  // walls seen, crosses no wall, and every other motion scores at least
  // max(proposal_margin, proposal_margin_share x walls seen) less.
  bool proposals{true};
  double proposal_corner_reach{0.5};  // m between a plane's end and the line it meets
  double proposal_min_walls{6.0};
  double proposal_min_share{0.75};
  double proposal_margin{2.0};
  double proposal_margin_share{0.15};
  double proposal_crossing_penalty{2.0};
  int proposal_max_candidates{3000};  // more distinct motions: too little seen, not decided
  // A UNIQUE answer from the room pairs is weighed by the proposals too: if its motion is not
  // in their best cluster (the walls seen clearly prefer another), AMBIGUOUS. Found by the
  // harsh campaign: a row of twin offices with one wall moved, another turned (seed 17 trial
  // 778), and a twin wing entered through an opening the plan lacks (seed 21 trial 769).
  bool proposal_cross_check{true};
  // ... only for an answer pairing at most this many S-rooms: the proposals cost 10-100 ms on
  // many walls (bench_matching: 20 S-rooms of 200 A-rooms, 17 -> 123 ms cold with every answer
  // checked), and every wrong UNIQUE the campaigns found paired 2-4 rooms.
  int proposal_cross_check_max_rooms{5};
  // --- the scan search (scan_search.h) on the newest keyframes' slices ---
  // The poses (B_x_M, storey) the slices cannot tell apart, certified by the search's bound, join
  // the proposals; a proposal (or a competitor of the best) outside that set is out: the scans
  // put it more than scan_search.margin below the best. The proposals' best must be in the set,
  // else the two disagree and nothing is UNIQUE from them. Too many poses, too few points or no
  // walls at the slice's height: no set, the proposals as without it (graph_match says why).
  // Off by default: on one keyframe its set is still too large to decide on (a room's view fits
  // 2-25 poses within the margin) and searching five storeys takes up to 1.6 s (docs/matching.md).
  bool scan_proposals{false};
  ScanSearchConfig scan_search;
  // --- decision ---
  double ambiguity_margin{0.4};      // hypotheses scoring within this of the best compete
  double cluster_yaw_deg{3.0};       // hypotheses closer than this (and cluster_translation)
  double cluster_translation{0.5};   //   imply the same motion and are one hypothesis
  int min_matched_rooms{1};          // a UNIQUE match pairs at least this many S-rooms
  double min_matched_fraction{0.5};  // ... and at least this share of the S-Graph's rooms
  int max_seeds{4000};               // bound on the global candidates grown per match
  // A UNIQUE answer is doubted with this room-centre tolerance (a centre moved by clutter taken
  // for a wall): a hypothesis found only so, of another motion and within ambiguity_margin,
  // makes it AMBIGUOUS. <= centre_tolerance: no doubt.
  double doubt_centre_tolerance{1.2};
  // --- walls off the plan (GraphMatch::deviations) ---
  // A paired room's wall-surface whose S-plane stands more than deviation_offset or turned more
  // than deviation_angle_deg from it is marked deviating (its pair keeps only its share of the
  // room's quality); so is an S-plane of a paired room that found no A-surface within the pair
  // tolerances but one of that room facing the same way within deviation_max_offset and
  // deviation_max_angle_deg (a wall built 35 cm or 15 deg off).
  double deviation_offset{0.1};
  double deviation_angle_deg{3.0};
  double deviation_max_offset{0.6};
  double deviation_max_angle_deg{20.0};

  /// "" when valid, else what is wrong, naming the field.
  std::string Validate() const;
};

}  // namespace matching
}  // namespace is_graphs
