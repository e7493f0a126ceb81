#include "is_graphs/navigation/map_files.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace is_graphs {
namespace navigation {

std::string WriteMapFiles(const OccupancyGrid& grid, const std::string& yaml_path) {
  const std::filesystem::path yaml(yaml_path);
  std::filesystem::path pgm = yaml;
  pgm.replace_extension(".pgm");
  std::error_code ec;
  if (yaml.has_parent_path()) std::filesystem::create_directories(yaml.parent_path(), ec);
  std::ofstream image(pgm, std::ios::binary | std::ios::trunc);
  if (!image) return "cannot write " + pgm.string();
  image << "P5\n# is_graphs bim_map, " << grid.resolution << " m/pixel\n"
        << grid.width << " " << grid.height << "\n255\n";
  std::string row(static_cast<size_t>(grid.width), '\0');
  for (int iy = grid.height - 1; iy >= 0; --iy) {
    for (int ix = 0; ix < grid.width; ++ix) {
      const auto c = grid.At(ix, iy);
      row[ix] = static_cast<char>(c == OccupancyGrid::kOccupied ? 0
                                  : c == OccupancyGrid::kFree   ? 254
                                                                : 205);
    }
    image.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  if (!image) return "cannot write " + pgm.string();
  std::ofstream out(yaml, std::ios::trunc);
  out << std::setprecision(10) << "image: " << pgm.filename().string() << "\n"
      << "resolution: " << grid.resolution << "\n"
      << "origin: [" << grid.origin.x() << ", " << grid.origin.y() << ", 0.0]\n"
      << "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n";
  if (!out) return "cannot write " + yaml.string();
  return "";
}

std::string ReadMapImage(const std::string& pgm_path, OccupancyGrid& grid) {
  std::ifstream in(pgm_path, std::ios::binary);
  std::string magic;
  in >> magic;
  if (magic != "P5") return pgm_path + ": not a binary PGM";
  const auto skip_comments = [&] {
    in >> std::ws;
    while (in.peek() == '#') {
      std::string line;
      std::getline(in, line);
      in >> std::ws;
    }
  };
  int width = 0, height = 0, max = 0;
  skip_comments();
  in >> width;
  skip_comments();
  in >> height;
  skip_comments();
  in >> max;
  in.get();
  if (width != grid.width || height != grid.height || max != 255)
    return pgm_path + ": " + std::to_string(width) + " x " + std::to_string(height) +
           ", not the grid's size";
  std::string row(static_cast<size_t>(width), '\0');
  for (int iy = height - 1; iy >= 0; --iy) {
    if (!in.read(row.data(), width)) return pgm_path + ": truncated";
    for (int ix = 0; ix < width; ++ix) {
      const auto v = static_cast<unsigned char>(row[ix]);
      grid.At(ix, iy) = v == 0     ? OccupancyGrid::kOccupied
                        : v == 254 ? OccupancyGrid::kFree
                                   : OccupancyGrid::kUnknown;
    }
  }
  return "";
}

}  // namespace navigation
}  // namespace is_graphs
