#pragma once

#include <sensor_msgs/PointField.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace is_graphs {
namespace ros_conversions {

/// The per-point field layouts of the LiDAR drivers sgraph_node reads (parameter
/// `cloud_layout`).
enum class CloudLayoutKind {
  kAuto,       // detected from the fields (the default)
  kVelodyne,   // velodyne_pointcloud XYZIRT: `time` float32, s after the header stamp
  kOuster,     // ouster-ros: `t` uint32, ns after the header stamp
  kHesai,      // Hesai ROS drivers: `timestamp` float64, absolute s (before `ring`)
  kRobosense,  // rslidar_sdk XYZIRT: `timestamp` float64, absolute s (after `ring`)
  kXyzi,       // no per-point time: no deskew
};
const char* ToString(CloudLayoutKind kind);
std::optional<CloudLayoutKind> ParseCloudLayoutKind(const std::string& name);
/// "auto, velodyne, ouster, hesai, robosense, xyzi" (for messages).
std::string CloudLayoutChoices();

/// How a layout encodes the per-point time.
enum class TimeEncoding {
  kNone,
  kSecondsF32Relative,  // float32 s after the header stamp (may be negative: stamp at the end)
  kNanosU32Relative,    // uint32 ns after the header stamp
  kSecondsF64Absolute,  // float64 s since the epoch
};

/// Where one field lies in a point; `datatype` is a sensor_msgs::PointField constant.
struct FieldSlot {
  bool present{false};
  std::string name;
  std::uint32_t offset{0};
  std::uint8_t datatype{0};
};

/// The layout of one fields signature, decided once per signature by DetectCloudLayout.
struct CloudLayout {
  CloudLayoutKind kind{CloudLayoutKind::kXyzi};  // as detected or forced
  FieldSlot x, y, z, intensity, ring, time;
  TimeEncoding time_encoding{TimeEncoding::kNone};
  std::string fields;   // the fields found, e.g. "x(float32) y(float32) ... t(uint32) ..."
  std::string error;    // not usable (no x, y, z float32 inside the point): the cloud is skipped
  std::string warning;  // usable with less (no usable time: no deskew; ring or intensity left out)
};

/// Inspects a cloud's fields. `forced` kAuto detects the driver from the time field's name and
/// type; another kind expects that driver's time field (missing or mistyped: no deskew, with a
/// warning naming the field expected and the fields found). Duplicate names: x, y or z make
/// the cloud unusable, a duplicate time, ring or intensity field is left out.
CloudLayout DetectCloudLayout(const std::vector<sensor_msgs::PointField>& fields,
                              std::uint32_t point_step, CloudLayoutKind forced);

/// Identifies a cloud's fields (names, offsets, types, counts) and point_step: clouds with the
/// same signature have the same layout.
std::string FieldsSignature(const std::vector<sensor_msgs::PointField>& fields,
                            std::uint32_t point_step);

/// The byte size of a PointField datatype (0 for an unknown one).
std::uint32_t DatatypeSize(std::uint8_t datatype);

}  // namespace ros_conversions
}  // namespace is_graphs
