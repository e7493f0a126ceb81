// LiDAR clouds of every driver layout into the core's scan (issue 23): clouds written by
// make_bag's writer for the simulated VLP-16, OS1-64 and XT32 (the drivers' layouts) read back
// with the layout detected; RoboSense and XYZI clouds; forced layouts; and bad input (no time
// field, a time in an unknown unit, duplicate fields, rings out of range, short data): one
// warning naming the fields, the cloud used without deskew or skipped, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <tuple>

#include "../../src/ros/lidar_conversions.h"
#include "../../src/ros/tools/lidar_cloud_writer.h"

namespace is_graphs {
namespace {

using ros_conversions::CloudLayoutKind;
using sensor_msgs::PointField;

constexpr double kStart = 1000.25;  // the scan's first firing, bag time

// A scan of `model` as the simulator makes it: one return per column for a few lasers, on a
// cylinder 5 m around the sensor.
sim::LidarScan MakeScan(const sim::LidarModel& model) {
  sim::LidarScan scan;
  for (int k = 0; k < model.FiringsPerScan(); k += 7) {
    for (int laser = 0; laser < model.Lasers(); laser += 3) {
      const Eigen::Vector3f d = model.Direction(k, laser);
      const Eigen::Vector3f p = 5.0f / std::hypot(d.x(), d.y()) * d;
      scan.points.push_back({p.x(), p.y(), p.z(), 40.0f, model.Ring(laser),
                             static_cast<float>(model.PulseTime(k, laser)),
                             static_cast<uint32_t>(k)});
    }
  }
  return scan;
}

struct Read {
  Result<sgraph::Scan> scan = Result<sgraph::Scan>::Error("not read");
  std::string info;
  std::vector<std::string> warnings;
};

Read ReadWith(ros_conversions::LidarCloudReader& reader, const sensor_msgs::PointCloud2& msg) {
  Read r;
  r.scan = reader.Read(msg, &r.info, &r.warnings);
  return r;
}

Read ReadOnce(const sensor_msgs::PointCloud2& msg,
              CloudLayoutKind layout = CloudLayoutKind::kAuto) {
  ros_conversions::LidarCloudConfig config;
  config.layout = layout;
  ros_conversions::LidarCloudReader reader(config);
  return ReadWith(reader, msg);
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Each point of `scan` read back: the same x, y, z, ring and time (relative to the stamp, which
// is `time_offset` after the scan start).
void ExpectSameReturns(const sim::LidarScan& scan, const sgraph::Scan& read, double time_offset,
                       const sim::LidarModel& model) {
  std::vector<const sgraph::ScanPoint*> finite;
  for (const auto& q : read.points) {
    ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
    finite.push_back(&q);
  }
  ASSERT_EQ(finite.size(), scan.points.size());
  ASSERT_TRUE(read.has_time);
  // Organized clouds hold the points by row (ring) then column: compare as sets keyed so.
  // (ring, column), the column from the time (a column's lasers fire within its interval).
  const double interval = model.FiringTime(1);
  auto key = [interval](uint16_t ring, double time) {
    return std::make_pair(ring, static_cast<long>(std::floor(time / interval + 1e-3)));
  };
  std::map<std::pair<uint16_t, long>, const sim::LidarPoint*> by_key;
  for (const auto& p : scan.points) {
    by_key[key(p.ring, p.time)] = &p;
    ASSERT_EQ(key(p.ring, p.time).second, static_cast<long>(p.column));
  }
  for (const auto* q : finite) {
    const auto it = by_key.find(key(q->ring, q->time + time_offset));
    ASSERT_NE(it, by_key.end()) << "ring " << q->ring << " time " << q->time;
    EXPECT_EQ(q->x, it->second->x);
    EXPECT_EQ(q->y, it->second->y);
    EXPECT_EQ(q->z, it->second->z);
    EXPECT_NEAR(q->time + time_offset, it->second->time, 2e-7);
  }
}

TEST(LidarConversions, Vlp16CloudIsVelodyneLayout) {
  const sim::LidarModel model(sim::LidarConfig::For(sim::LidarModelKind::kVlp16));
  const sim::LidarScan scan = MakeScan(model);
  const Read r = ReadOnce(sim_ros::ToCloud(scan, model, ros::Time(kStart)));
  ASSERT_TRUE(r.scan.ok()) << r.scan.error();
  EXPECT_TRUE(Contains(r.info, "velodyne")) << r.info;
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_DOUBLE_EQ(r.scan.value().stamp, ros::Time(kStart).toSec());
  ExpectSameReturns(scan, r.scan.value(), 0.0, model);
}

TEST(LidarConversions, OusterCloudIsOrganizedWithNansAndNanosecondTimes) {
  const sim::LidarModel model(sim::LidarConfig::For(sim::LidarModelKind::kOs1_64));
  const sim::LidarScan scan = MakeScan(model);
  const sensor_msgs::PointCloud2 msg = sim_ros::ToCloud(scan, model, ros::Time(kStart));
  EXPECT_EQ(msg.height, 64u);
  EXPECT_EQ(msg.width, 1024u);
  EXPECT_EQ(msg.point_step, 48u);
  EXPECT_FALSE(msg.is_dense);
  EXPECT_EQ(msg.header.frame_id, "os_lidar");
  const Read r = ReadOnce(msg);
  ASSERT_TRUE(r.scan.ok()) << r.scan.error();
  EXPECT_TRUE(Contains(r.info, "ouster (per-point time 't' uint32 ns")) << r.info;
  EXPECT_TRUE(r.warnings.empty());
  // The pixels without a return (NaN, is_dense false) are dropped here, not warned about.
  EXPECT_EQ(r.scan.value().points.size(), scan.points.size());
  ExpectSameReturns(scan, r.scan.value(), 0.0, model);
}

TEST(LidarConversions, HesaiCloudHasAbsoluteTimesMadeRelativeToTheStamp) {
  const sim::LidarModel model(sim::LidarConfig::For(sim::LidarModelKind::kHesaiXt32));
  const sim::LidarScan scan = MakeScan(model);
  const sensor_msgs::PointCloud2 msg = sim_ros::ToCloud(scan, model, ros::Time(kStart));
  EXPECT_EQ(msg.point_step, 48u);
  double first = 0.0;
  std::memcpy(&first, msg.data.data() + 24, 8);
  EXPECT_NEAR(first, kStart, 1e-9);  // absolute
  const Read r = ReadOnce(msg);
  ASSERT_TRUE(r.scan.ok()) << r.scan.error();
  EXPECT_TRUE(Contains(r.info, "hesai (per-point time 'timestamp' float64 absolute")) << r.info;
  EXPECT_TRUE(r.warnings.empty());
  // The driver stamps the cloud with its first point's time (here the scan start).
  ExpectSameReturns(scan, r.scan.value(), msg.header.stamp.toSec() - kStart, model);
}

// A cloud of `n` points with the given fields (float32 x y z at 0 4 8 and the rest as given),
// every point's bytes from `fill`.
sensor_msgs::PointCloud2 Cloud(
    const std::vector<std::tuple<std::string, uint8_t, uint32_t>>& fields, uint32_t point_step,
    uint32_t n, const std::function<void(uint8_t*, uint32_t)>& fill) {
  sensor_msgs::PointCloud2 msg;
  msg.header.stamp = ros::Time(kStart);
  msg.header.frame_id = "lidar";
  for (const auto& [name, type, offset] : fields) {
    PointField f;
    f.name = name;
    f.datatype = type;
    f.offset = offset;
    f.count = 1;
    msg.fields.push_back(f);
  }
  msg.height = 1;
  msg.width = n;
  msg.point_step = point_step;
  msg.row_step = point_step * n;
  msg.data.resize(msg.row_step);
  for (uint32_t i = 0; i < n; ++i) {
    uint8_t* p = msg.data.data() + i * point_step;
    const float xyz[3] = {2.0f + i * 0.01f, 1.0f, 0.5f};
    std::memcpy(p, xyz, 12);
    fill(p, i);
  }
  return msg;
}

// RoboSense (rslidar_sdk XYZIRT): x y z intensity float32, ring uint16, timestamp float64.
sensor_msgs::PointCloud2 Robosense(double time_scale = 1.0) {
  return Cloud({{"x", PointField::FLOAT32, 0},
                {"y", PointField::FLOAT32, 4},
                {"z", PointField::FLOAT32, 8},
                {"intensity", PointField::FLOAT32, 12},
                {"ring", PointField::UINT16, 16},
                {"timestamp", PointField::FLOAT64, 24}},
               32, 100, [time_scale](uint8_t* p, uint32_t i) {
                 const uint16_t ring = i % 32;
                 // rslidar_sdk stamps the cloud with its last point: times up to the stamp.
                 const double t = (kStart - 0.1 + 0.001 * i) * time_scale;
                 std::memcpy(p + 16, &ring, 2);
                 std::memcpy(p + 24, &t, 8);
               });
}

TEST(LidarConversions, RobosenseTimestampsBeforeTheStampAreKept) {
  const Read r = ReadOnce(Robosense());
  ASSERT_TRUE(r.scan.ok()) << r.scan.error();
  EXPECT_TRUE(Contains(r.info, "robosense")) << r.info;
  EXPECT_TRUE(r.warnings.empty());
  ASSERT_TRUE(r.scan.value().has_time);
  EXPECT_NEAR(r.scan.value().points[0].time, -0.1, 1e-6);
  EXPECT_NEAR(r.scan.value().points[99].time, -0.001, 1e-6);
  EXPECT_EQ(r.scan.value().points[33].ring, 1);
}

TEST(LidarConversions, XyziCloudIsUsedWithoutDeskewAndOneWarning) {
  const auto msg = Cloud({{"x", PointField::FLOAT32, 0},
                          {"y", PointField::FLOAT32, 4},
                          {"z", PointField::FLOAT32, 8},
                          {"intensity", PointField::FLOAT32, 12}},
                         16, 10, [](uint8_t*, uint32_t) {});
  ros_conversions::LidarCloudReader reader({});
  Read r = ReadWith(reader, msg);
  ASSERT_TRUE(r.scan.ok()) << r.scan.error();
  EXPECT_FALSE(r.scan.value().has_time);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(Contains(r.warnings[0], "no per-point time")) << r.warnings[0];
  EXPECT_TRUE(
      Contains(r.warnings[0], "fields: x(float32) y(float32) z(float32) intensity(float32)"))
      << r.warnings[0];
  r = ReadWith(reader, msg);  // the same signature again: no second warning
  EXPECT_TRUE(r.scan.ok());
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_TRUE(r.info.empty());
}

TEST(LidarConversions, ForcedLayoutWithoutItsTimeFieldWarnsAndDoesNotDeskew) {
  const sim::LidarModel model(sim::LidarConfig::For(sim::LidarModelKind::kVlp16));
  const auto msg = sim_ros::ToCloud(MakeScan(model), model, ros::Time(kStart));
  const Read r = ReadOnce(msg, CloudLayoutKind::kOuster);
  ASSERT_TRUE(r.scan.ok()) << r.scan.error();
  EXPECT_FALSE(r.scan.value().has_time);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(Contains(r.warnings[0], "cloud_layout ouster expects 't' (uint32")) << r.warnings[0];
  EXPECT_TRUE(Contains(r.warnings[0], "time(float32)")) << r.warnings[0];  // the fields found
  // Forcing the right one, or xyzi, is quiet.
  EXPECT_TRUE(ReadOnce(msg, CloudLayoutKind::kVelodyne).warnings.empty());
  const Read xyzi = ReadOnce(msg, CloudLayoutKind::kXyzi);
  EXPECT_TRUE(xyzi.warnings.empty());
  EXPECT_FALSE(xyzi.scan.value().has_time);
}

TEST(LidarConversions, TimeInAnUnknownUnitWarnsOnceAndDoesNotDeskew) {
  // A Velodyne-like `time` in ms (0 .. 100) rather than s.
  const auto ms = Cloud({{"x", PointField::FLOAT32, 0},
                         {"y", PointField::FLOAT32, 4},
                         {"z", PointField::FLOAT32, 8},
                         {"time", PointField::FLOAT32, 12}},
                        16, 100, [](uint8_t* p, uint32_t i) {
                          const float t = 1.0f * i;
                          std::memcpy(p + 12, &t, 4);
                        });
  ros_conversions::LidarCloudReader reader({});
  Read r = ReadWith(reader, ms);
  ASSERT_TRUE(r.scan.ok()) << r.scan.error();
  EXPECT_FALSE(r.scan.value().has_time);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(Contains(r.warnings[0], "'time' spans 0 .. 99 s from the stamp")) << r.warnings[0];
  EXPECT_TRUE(Contains(r.warnings[0], "unknown unit")) << r.warnings[0];
  EXPECT_TRUE(Contains(r.warnings[0], "fields: x(float32) y(float32) z(float32) time(float32)"));
  for (const auto& q : r.scan.value().points) EXPECT_EQ(q.time, 0.0f);
  r = ReadWith(reader, ms);
  EXPECT_FALSE(r.scan.value().has_time);
  EXPECT_TRUE(r.warnings.empty());
  // Absolute timestamps in ns rather than s.
  r = ReadOnce(Robosense(1e9));
  ASSERT_TRUE(r.scan.ok());
  EXPECT_FALSE(r.scan.value().has_time);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(Contains(r.warnings[0], "'timestamp' spans")) << r.warnings[0];
  // A longer sweep bound accepts what the default refuses.
  ros_conversions::LidarCloudConfig slow;
  slow.max_sweep_period = 1.0;
  EXPECT_EQ(slow.Validate(), "");
  slow.max_sweep_period = 0.0;
  EXPECT_TRUE(Contains(slow.Validate(), "cloud_max_sweep_period"));
}

TEST(LidarConversions, DuplicateFieldsAreLeftOutOrSkipTheCloud) {
  const auto fill = [](uint8_t* p, uint32_t i) {
    const float t = 0.001f * i;
    std::memcpy(p + 12, &t, 4);
    std::memcpy(p + 16, &t, 4);
  };
  // Two `time` fields: which one is meant is unknown: no deskew, one warning.
  Read r = ReadOnce(Cloud({{"x", PointField::FLOAT32, 0},
                           {"y", PointField::FLOAT32, 4},
                           {"z", PointField::FLOAT32, 8},
                           {"time", PointField::FLOAT32, 12},
                           {"time", PointField::FLOAT32, 16}},
                          20, 10, fill));
  ASSERT_TRUE(r.scan.ok()) << r.scan.error();
  EXPECT_FALSE(r.scan.value().has_time);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(Contains(r.warnings[0], "field 'time' appears more than once")) << r.warnings[0];
  // Two `x` fields: the cloud is skipped, the error naming the fields.
  r = ReadOnce(Cloud({{"x", PointField::FLOAT32, 0},
                      {"y", PointField::FLOAT32, 4},
                      {"z", PointField::FLOAT32, 8},
                      {"x", PointField::FLOAT32, 12}},
                     20, 10, fill));
  ASSERT_FALSE(r.scan.ok());
  EXPECT_TRUE(Contains(r.scan.error(), "field 'x' appears more than once")) << r.scan.error();
  EXPECT_TRUE(Contains(r.scan.error(), "fields: x(float32) y(float32) z(float32) x(float32)"));
}

TEST(LidarConversions, RingsOutOfRangeAreLeftOut) {
  const auto msg = Cloud({{"x", PointField::FLOAT32, 0},
                          {"y", PointField::FLOAT32, 4},
                          {"z", PointField::FLOAT32, 8},
                          {"ring", PointField::UINT16, 12},
                          {"time", PointField::FLOAT32, 16}},
                         20, 10, [](uint8_t* p, uint32_t i) {
                           const uint16_t ring = i == 5 ? 40000 : i;  // read from a wrong offset
                           const float t = 0.001f * i;
                           std::memcpy(p + 12, &ring, 2);
                           std::memcpy(p + 16, &t, 4);
                         });
  const Read r = ReadOnce(msg);
  ASSERT_TRUE(r.scan.ok()) << r.scan.error();
  EXPECT_TRUE(r.scan.value().has_time);  // the cloud is used, with its times
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(Contains(r.warnings[0], "ring 'ring' reaches 40000, out of range (< 256)"))
      << r.warnings[0];
  for (const auto& q : r.scan.value().points) EXPECT_EQ(q.ring, 0);
}

TEST(LidarConversions, MalformedCloudsAreErrorsNotCrashes) {
  const auto fill = [](uint8_t*, uint32_t) {};
  auto msg = Cloud({{"x", PointField::FLOAT32, 0},
                    {"y", PointField::FLOAT32, 4},
                    {"z", PointField::FLOAT32, 8},
                    {"time", PointField::FLOAT32, 12}},
                   16, 10, fill);
  auto short_data = msg;
  short_data.data.resize(100);
  EXPECT_FALSE(ReadOnce(short_data).scan.ok());
  auto outside = msg;
  outside.fields[2].offset = 14;  // z reaches past the 16-byte point
  const Read r = ReadOnce(outside);
  ASSERT_FALSE(r.scan.ok());
  EXPECT_TRUE(Contains(r.scan.error(), "field 'z' lies outside point_step")) << r.scan.error();
  auto no_xyz = msg;
  no_xyz.fields.erase(no_xyz.fields.begin());
  EXPECT_TRUE(Contains(ReadOnce(no_xyz).scan.error(), "no field 'x'"));
  auto typed = msg;
  typed.fields[1].datatype = PointField::FLOAT64;
  EXPECT_TRUE(Contains(ReadOnce(typed).scan.error(), "field 'y' is float64"));
  auto zero_step = msg;
  zero_step.point_step = 0;
  EXPECT_FALSE(ReadOnce(zero_step).scan.ok());
  auto mistyped_time = msg;
  mistyped_time.fields[3].datatype = PointField::FLOAT64;  // 'time' float64 reaches past 16 too
  const Read t = ReadOnce(mistyped_time);
  ASSERT_TRUE(t.scan.ok()) << t.scan.error();
  EXPECT_FALSE(t.scan.value().has_time);
  EXPECT_EQ(t.warnings.size(), 1u);
}

TEST(LidarConversions, NansOfADenseCloudAreLeftToTheCore) {
  // A cloud that says it is dense but holds NaN: a defect the core counts and warns about.
  auto msg = Cloud(
      {{"x", PointField::FLOAT32, 0}, {"y", PointField::FLOAT32, 4}, {"z", PointField::FLOAT32, 8}},
      12, 10, [](uint8_t* p, uint32_t i) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        if (i % 2) std::memcpy(p, &nan, 4);
      });
  msg.is_dense = true;
  EXPECT_EQ(ReadOnce(msg).scan.value().points.size(), 10u);
  msg.is_dense = false;
  EXPECT_EQ(ReadOnce(msg).scan.value().points.size(), 5u);
}

TEST(LidarConversions, LayoutNamesRoundTrip) {
  for (const char* name : {"auto", "velodyne", "ouster", "hesai", "robosense", "xyzi"}) {
    const auto kind = ros_conversions::ParseCloudLayoutKind(name);
    ASSERT_TRUE(kind.has_value()) << name;
    EXPECT_STREQ(ros_conversions::ToString(*kind), name);
  }
  EXPECT_FALSE(ros_conversions::ParseCloudLayoutKind("livox").has_value());
}

}  // namespace
}  // namespace is_graphs
