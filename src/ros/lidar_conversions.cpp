#include "lidar_conversions.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace is_graphs {
namespace ros_conversions {
namespace {

using sensor_msgs::PointField;

template <typename T>
T ReadAt(const uint8_t* base, uint32_t offset) {
  T v;
  std::memcpy(&v, base + offset, sizeof(T));
  return v;
}

// A numeric field as double (the slot's type was checked when the layout was made).
double ReadNumber(const uint8_t* p, const FieldSlot& f) {
  switch (f.datatype) {
    case PointField::UINT8:
      return ReadAt<uint8_t>(p, f.offset);
    case PointField::UINT16:
      return ReadAt<uint16_t>(p, f.offset);
    case PointField::UINT32:
      return ReadAt<uint32_t>(p, f.offset);
    case PointField::FLOAT32:
      return ReadAt<float>(p, f.offset);
    case PointField::FLOAT64:
      return ReadAt<double>(p, f.offset);
    default:
      return 0.0;
  }
}

std::string Seconds(double s) {
  std::ostringstream out;
  out.precision(4);
  out << s;
  return out.str();
}

}  // namespace

std::string LidarCloudConfig::Validate() const {
  if (!(max_sweep_period > 0.0 && max_sweep_period <= 1.0))
    return "cloud_max_sweep_period must be in (0, 1] s, got " + std::to_string(max_sweep_period);
  return "";
}

std::string Describe(const CloudLayout& layout) {
  std::string time = "no per-point time (no deskew)";
  if (layout.time_encoding == TimeEncoding::kSecondsF32Relative)
    time = "per-point time '" + layout.time.name + "' float32 s after the stamp";
  else if (layout.time_encoding == TimeEncoding::kNanosU32Relative)
    time = "per-point time '" + layout.time.name + "' uint32 ns after the stamp";
  else if (layout.time_encoding == TimeEncoding::kSecondsF64Absolute)
    time = "per-point time '" + layout.time.name + "' float64 absolute s";
  return std::string(ToString(layout.kind)) + " (" + time + "; fields: " + layout.fields + ")";
}

Result<sgraph::Scan> FromLidarMsg(const sensor_msgs::PointCloud2& msg, const CloudLayout& layout,
                                  double max_sweep_period,
                                  std::vector<std::pair<std::string, std::string>>* problems) {
  using R = Result<sgraph::Scan>;
  if (msg.is_bigendian) return R::Error("big-endian clouds are not supported");
  if (!layout.error.empty()) return R::Error(layout.error);
  const uint64_t count = static_cast<uint64_t>(msg.width) * msg.height;
  if (msg.point_step == 0 && count > 0) return R::Error("point_step is 0");
  if (msg.row_step < static_cast<uint64_t>(msg.width) * msg.point_step ||
      msg.data.size() < static_cast<uint64_t>(msg.row_step) * msg.height)
    return R::Error("data is shorter than width x height x point_step");
  sgraph::Scan scan;
  scan.stamp = msg.header.stamp.toSec();
  scan.frame_id = msg.header.frame_id;
  scan.has_time = layout.time_encoding != TimeEncoding::kNone;
  // A cloud that declares invalid points (is_dense false: an organized cloud's pixels without a
  // return) has them dropped here; in a dense cloud they are a defect the core counts and warns
  // about.
  const bool drop_invalid = !msg.is_dense;
  scan.points.reserve(count);
  const bool absolute = layout.time_encoding == TimeEncoding::kSecondsF64Absolute;
  const double time_scale = layout.time_encoding == TimeEncoding::kNanosU32Relative ? 1e-9 : 1.0;
  double t_min = std::numeric_limits<double>::infinity(), t_max = -t_min;
  uint32_t ring_max = 0;
  for (uint32_t row = 0; row < msg.height; ++row) {
    const uint8_t* row_data = msg.data.data() + static_cast<size_t>(row) * msg.row_step;
    for (uint32_t col = 0; col < msg.width; ++col) {
      const uint8_t* p = row_data + static_cast<size_t>(col) * msg.point_step;
      sgraph::ScanPoint q;
      q.x = ReadAt<float>(p, layout.x.offset);
      q.y = ReadAt<float>(p, layout.y.offset);
      q.z = ReadAt<float>(p, layout.z.offset);
      if (drop_invalid && !(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z)))
        continue;
      if (layout.intensity.present)
        q.intensity = static_cast<float>(ReadNumber(p, layout.intensity));
      if (layout.ring.present) {
        const auto ring = static_cast<uint32_t>(ReadNumber(p, layout.ring));
        ring_max = std::max(ring_max, ring);
        q.ring = static_cast<uint16_t>(ring);
      }
      if (scan.has_time) {
        double t = ReadNumber(p, layout.time) * time_scale;
        if (absolute) t -= scan.stamp;
        q.time = static_cast<float>(t);
        if (std::isfinite(t)) t_min = std::min(t_min, t), t_max = std::max(t_max, t);
      }
      scan.points.push_back(q);
    }
  }
  const uint32_t ring_limit = msg.height > 1 ? msg.height : 256;
  if (layout.ring.present && ring_max >= ring_limit) {
    for (auto& q : scan.points) q.ring = 0;
    problems->push_back({"ring", "ring '" + layout.ring.name + "' reaches " +
                                     std::to_string(ring_max) + ", out of range (< " +
                                     std::to_string(ring_limit) +
                                     (msg.height > 1 ? ", the rows of the organized cloud" : "") +
                                     "): ring left out (fields: " + layout.fields + ")"});
  }
  const double bound = 1.5 * max_sweep_period;
  if (scan.has_time && t_min <= t_max && (t_min < -bound || t_max > bound)) {
    scan.has_time = false;
    for (auto& q : scan.points) q.time = 0.0f;
    problems->push_back(
        {"time", "per-point time '" + layout.time.name + "' spans " + Seconds(t_min) + " .. " +
                     Seconds(t_max) + " s from the stamp, beyond 1.5 sweep periods (" +
                     Seconds(bound) + " s, cloud_max_sweep_period " + Seconds(max_sweep_period) +
                     " s): an unknown unit? Used without deskew (layout " + ToString(layout.kind) +
                     ", fields: " + layout.fields + ")"});
  }
  return R::Ok(std::move(scan));
}

Result<sgraph::Scan> LidarCloudReader::Read(const sensor_msgs::PointCloud2& msg, std::string* info,
                                            std::vector<std::string>* warnings) {
  const std::string signature = FieldsSignature(msg.fields, msg.point_step);
  if (!have_layout_ || signature != signature_) {
    layout_ = DetectCloudLayout(msg.fields, msg.point_step, config_.layout);
    signature_ = signature;
    have_layout_ = true;
    if (layout_.error.empty() && reported_.insert(signature + "#layout").second) {
      *info = "layout " + Describe(layout_);
      if (!layout_.warning.empty()) warnings->push_back(layout_.warning);
    }
  }
  std::vector<std::pair<std::string, std::string>> problems;
  auto scan = FromLidarMsg(msg, layout_, config_.max_sweep_period, &problems);
  for (const auto& [key, message] : problems)
    if (reported_.insert(signature + "#" + key).second) warnings->push_back(message);
  return scan;
}

}  // namespace ros_conversions
}  // namespace is_graphs
