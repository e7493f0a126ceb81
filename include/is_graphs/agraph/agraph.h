#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/geometry/plane.h"

namespace is_graphs {
namespace agraph {

// The Architectural Graph, in the BIM frame; see docs/agraph_format.md for every field.
// Ids are dense indices into their own vector.

struct Storey {
  int id{0};
  long ifc_id{-1};
  std::string guid;
  std::string name;
  double elevation{0.0};
  double height{0.0};
};

struct WallSurface {
  int id{0};
  long ifc_id{-1};
  std::string guid;
  int wall{-1};
  int storey{0};
  geometry::Plane plane;  // normal points out of the wall material
  geometry::Orientation orientation{geometry::Orientation::kOther};
  Eigen::Vector2d start{Eigen::Vector2d::Zero()};
  Eigen::Vector2d end{Eigen::Vector2d::Zero()};
  double z_min{0.0};
  double z_max{0.0};
  std::vector<int> rooms;

  /// Horizontal unit tangent t = ẑ × normal; (end - start) · t > 0.
  Eigen::Vector3d Tangent() const;
  double Length() const { return (end - start).norm(); }
};

struct Wall {
  int id{0};
  long ifc_id{-1};
  std::string guid;
  std::string name;
  int storey{0};
  int surface_a{-1};
  int surface_b{-1};
  double thickness{0.0};
  Eigen::Vector3d start{Eigen::Vector3d::Zero()};   // wall point w_s
  Eigen::Vector3d center{Eigen::Vector3d::Zero()};  // wall centre
  double length{0.0};
  double height{0.0};
  bool external{false};
};

struct Room {
  int id{0};
  long ifc_id{-1};
  std::string guid;
  std::string name;
  std::string long_name;
  int storey{0};
  std::vector<Eigen::Vector2d> polygon;  // counter-clockwise, not closed
  double z_min{0.0};
  double z_max{0.0};
  /// The floor walked on in the room (file field `floor_z`, since converter 7): from the slab or
  /// floor covering under it, else the space's bottom, the mesh, the storey's elevation. A file
  /// without it (older converters) gives the storey's elevation, and floor_source "".
  double floor_z{0.0};
  /// "slab", "covering", "space", "mesh", "storey"; "" when the file has no floor_z.
  std::string floor_source;
  Eigen::Vector3d center{Eigen::Vector3d::Zero()};
  double area{0.0};
  std::vector<int> surfaces;
  std::vector<int> walls;
  std::vector<int> doorways;
};

/// What joins a doorway's rooms (A-Graph file field `kind`): a door (IfcDoor), an opening in a
/// wall that nothing fills, or a virtual separation (no wall: a space boundary marked VIRTUAL,
/// an IfcVirtualElement). Files of converter version 1 hold doors only.
enum class DoorwayKind { kDoor = 0, kOpening = 1, kVirtual = 2 };

/// "door", "opening", "virtual".
const char* ToString(DoorwayKind kind);

struct Doorway {
  int id{0};
  DoorwayKind kind{DoorwayKind::kDoor};
  long ifc_id{-1};
  std::string guid;
  std::string name;
  int storey{0};
  int wall{-1};
  Eigen::Vector3d position{Eigen::Vector3d::Zero()};
  double width{0.0};
  double height{0.0};
  std::vector<int> rooms;  // two, or one for a door to outdoors
  /// Whether it goes through a wall (a door or an opening; a virtual separation has none).
  bool InWall() const { return kind != DoorwayKind::kVirtual; }
};

struct SourceInfo {
  std::string file;
  std::string sha256;
  std::string schema;
  std::string application;
  double length_unit_m{1.0};
  std::string converter_version;
};

/// What the conversion left out of one storey, by IFC class and reason (the file's `report`;
/// each loss is also named in `warnings`).
struct ConversionDrop {
  int storey{0};
  std::string ifc_class;
  std::string reason;
  int count{0};
};

struct AGraph {
  int format_version{1};
  SourceInfo source;
  std::string building;
  std::string mesh;  // path of the OBJ mesh, resolved against the A-Graph file's folder; "" if none
  std::vector<Storey> storeys;
  std::vector<WallSurface> surfaces;
  std::vector<Wall> walls;
  std::vector<Room> rooms;
  std::vector<Doorway> doorways;
  std::vector<std::string> warnings;
  std::vector<ConversionDrop> dropped;  // empty for files of converter version 1
};

}  // namespace agraph
}  // namespace is_graphs
