#include "velodyne_conversions.h"

#include <cstring>
#include <string>

namespace is_graphs {
namespace ros_conversions {
namespace {

const sensor_msgs::PointField* FindField(const sensor_msgs::PointCloud2& msg,
                                         const std::string& name) {
  for (const auto& f : msg.fields)
    if (f.name == name) return &f;
  return nullptr;
}

template <typename T>
T ReadAt(const uint8_t* base, uint32_t offset) {
  T v;
  std::memcpy(&v, base + offset, sizeof(T));
  return v;
}

}  // namespace

Result<sgraph::Scan> FromVelodyneMsg(const sensor_msgs::PointCloud2& msg) {
  using R = Result<sgraph::Scan>;
  if (msg.is_bigendian) return R::Error("big-endian clouds are not supported");
  const auto* x = FindField(msg, "x");
  const auto* y = FindField(msg, "y");
  const auto* z = FindField(msg, "z");
  if (!x || !y || !z) return R::Error("the cloud has no x, y, z fields");
  for (const auto* f : {x, y, z})
    if (f->datatype != sensor_msgs::PointField::FLOAT32)
      return R::Error("field '" + f->name + "' is not float32");
  const auto* intensity = FindField(msg, "intensity");
  const auto* ring = FindField(msg, "ring");
  const auto* time = FindField(msg, "time");
  if (intensity && intensity->datatype != sensor_msgs::PointField::FLOAT32) intensity = nullptr;
  if (ring && ring->datatype != sensor_msgs::PointField::UINT16) ring = nullptr;
  if (time && time->datatype != sensor_msgs::PointField::FLOAT32) time = nullptr;
  const uint64_t count = static_cast<uint64_t>(msg.width) * msg.height;
  if (msg.point_step == 0 && count > 0) return R::Error("point_step is 0");
  if (msg.row_step < static_cast<uint64_t>(msg.width) * msg.point_step ||
      msg.data.size() < static_cast<uint64_t>(msg.row_step) * msg.height)
    return R::Error("data is shorter than width x height x point_step");
  for (const auto* f : {x, y, z, intensity, ring, time})
    if (f && f->offset + 4 > msg.point_step && !(f == ring && f->offset + 2 <= msg.point_step))
      return R::Error("field '" + f->name + "' lies outside point_step");
  sgraph::Scan scan;
  scan.stamp = msg.header.stamp.toSec();
  scan.frame_id = msg.header.frame_id;
  scan.has_time = time != nullptr;
  scan.points.resize(count);
  size_t k = 0;
  for (uint32_t row = 0; row < msg.height; ++row) {
    const uint8_t* row_data = msg.data.data() + static_cast<size_t>(row) * msg.row_step;
    for (uint32_t col = 0; col < msg.width; ++col, ++k) {
      const uint8_t* p = row_data + static_cast<size_t>(col) * msg.point_step;
      sgraph::ScanPoint& q = scan.points[k];
      q.x = ReadAt<float>(p, x->offset);
      q.y = ReadAt<float>(p, y->offset);
      q.z = ReadAt<float>(p, z->offset);
      if (intensity) q.intensity = ReadAt<float>(p, intensity->offset);
      if (ring) q.ring = ReadAt<uint16_t>(p, ring->offset);
      if (time) q.time = ReadAt<float>(p, time->offset);
    }
  }
  return R::Ok(std::move(scan));
}

}  // namespace ros_conversions
}  // namespace is_graphs
