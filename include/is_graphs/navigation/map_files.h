#pragma once

#include <string>

#include "is_graphs/navigation/occupancy_grid.h"

namespace is_graphs {
namespace navigation {

/// Writes the grid in map_server's format (ROS 1 map_server, nav2's map_server): `yaml_path`
/// (image, resolution, origin [x, y, 0], negate 0, occupied_thresh 0.65, free_thresh 0.196) and
/// the image beside it, same stem, .pgm (binary, trinary: occupied 0, free 254, unknown 205; the
/// image's top row is the grid's last). "" on success, else what failed.
std::string WriteMapFiles(const OccupancyGrid& grid, const std::string& yaml_path);

/// Reads a PGM written by WriteMapFiles back into cells (0 -> occupied, 254 -> free, else
/// unknown) of `grid`, whose size it must have. "" on success.
std::string ReadMapImage(const std::string& pgm_path, OccupancyGrid& grid);

}  // namespace navigation
}  // namespace is_graphs
