#include "lidar_cloud_writer.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

namespace is_graphs {
namespace sim_ros {
namespace {

using sensor_msgs::PointField;

struct Field {
  const char* name;
  uint8_t datatype;
  uint32_t offset;
};

sensor_msgs::PointCloud2 Empty(const std::vector<Field>& fields, uint32_t point_step,
                               uint32_t height, uint32_t width, const std::string& frame) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header.frame_id = frame;
  for (const Field& f : fields) {
    PointField field;
    field.name = f.name;
    field.datatype = f.datatype;
    field.offset = f.offset;
    field.count = 1;
    cloud.fields.push_back(field);
  }
  cloud.point_step = point_step;
  cloud.height = height;
  cloud.width = width;
  cloud.row_step = point_step * width;
  cloud.is_bigendian = false;
  cloud.is_dense = true;
  cloud.data.resize(static_cast<size_t>(cloud.row_step) * height);  // zeroed (padding too)
  return cloud;
}

template <typename T>
void Put(uint8_t* out, uint32_t offset, T value) {
  std::memcpy(out + offset, &value, sizeof(T));
}

sensor_msgs::PointCloud2 Velodyne(const sim::LidarScan& scan, const ros::Time& stamp) {
  sensor_msgs::PointCloud2 cloud =
      Empty({{"x", PointField::FLOAT32, 0},
             {"y", PointField::FLOAT32, 4},
             {"z", PointField::FLOAT32, 8},
             {"intensity", PointField::FLOAT32, 12},
             {"ring", PointField::UINT16, 16},
             {"time", PointField::FLOAT32, 18}},
            22, 1, static_cast<uint32_t>(scan.points.size()), "velodyne");
  cloud.header.stamp = stamp;
  uint8_t* out = cloud.data.data();
  for (const sim::LidarPoint& p : scan.points) {
    Put(out, 0, p.x);
    Put(out, 4, p.y);
    Put(out, 8, p.z);
    Put(out, 12, p.intensity);
    Put(out, 16, p.ring);
    Put(out, 18, p.time);
    out += cloud.point_step;
  }
  return cloud;
}

sensor_msgs::PointCloud2 Ouster(const sim::LidarScan& scan, const sim::LidarModel& model,
                                const ros::Time& stamp) {
  const uint32_t rows = static_cast<uint32_t>(model.Lasers());
  const uint32_t columns = static_cast<uint32_t>(model.FiringsPerScan());
  sensor_msgs::PointCloud2 cloud =
      Empty({{"x", PointField::FLOAT32, 0},
             {"y", PointField::FLOAT32, 4},
             {"z", PointField::FLOAT32, 8},
             {"intensity", PointField::FLOAT32, 16},
             {"t", PointField::UINT32, 20},
             {"reflectivity", PointField::UINT16, 24},
             {"ring", PointField::UINT16, 26},
             {"ambient", PointField::UINT16, 28},
             {"range", PointField::UINT32, 32}},
            48, rows, columns, DriverFor(model.config().model).points_frame);
  cloud.header.stamp = stamp;
  cloud.is_dense = false;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (uint32_t row = 0; row < rows; ++row) {
    for (uint32_t col = 0; col < columns; ++col) {  // every pixel: no return until filled
      uint8_t* out = cloud.data.data() + static_cast<size_t>(row) * cloud.row_step +
                     static_cast<size_t>(col) * cloud.point_step;
      Put(out, 0, nan);
      Put(out, 4, nan);
      Put(out, 8, nan);
      Put(out, 20, static_cast<uint32_t>(std::llround(model.FiringTime(col) * 1e9)));
      Put(out, 26, static_cast<uint16_t>(row));
    }
  }
  const double reflectivity_scale = 255.0 / model.spec().intensity_scale;
  for (const sim::LidarPoint& p : scan.points) {
    // ouster-ros' row is the ring (0 = the highest beam), its column the measurement id.
    uint8_t* out = cloud.data.data() + static_cast<size_t>(p.ring) * cloud.row_step +
                   static_cast<size_t>(p.column) * cloud.point_step;
    Put(out, 0, p.x);
    Put(out, 4, p.y);
    Put(out, 8, p.z);
    Put(out, 16, p.intensity);
    Put(out, 24, static_cast<uint16_t>(std::lround(p.intensity * reflectivity_scale)));
    const double range = std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
    Put(out, 32, static_cast<uint32_t>(std::llround(range * 1000.0)));
  }
  return cloud;
}

sensor_msgs::PointCloud2 Hesai(const sim::LidarScan& scan, const sim::LidarModel& model,
                               const ros::Time& scan_start) {
  sensor_msgs::PointCloud2 cloud = Empty({{"x", PointField::FLOAT32, 0},
                                          {"y", PointField::FLOAT32, 4},
                                          {"z", PointField::FLOAT32, 8},
                                          {"intensity", PointField::FLOAT32, 16},
                                          {"timestamp", PointField::FLOAT64, 24},
                                          {"ring", PointField::UINT16, 32}},
                                         48, 1, static_cast<uint32_t>(scan.points.size()),
                                         DriverFor(model.config().model).points_frame);
  // The driver's ring is the laser (channel) id.
  std::vector<int> laser_of_ring(model.Lasers());
  for (int laser = 0; laser < model.Lasers(); ++laser) laser_of_ring[model.Ring(laser)] = laser;
  const double start = scan_start.toSec();
  cloud.header.stamp = scan_start;
  uint8_t* out = cloud.data.data();
  for (size_t i = 0; i < scan.points.size(); ++i, out += cloud.point_step) {
    const sim::LidarPoint& p = scan.points[i];
    const double timestamp = start + model.PulseTime(p.column, laser_of_ring[p.ring]);
    if (i == 0) cloud.header.stamp = ros::Time(timestamp);  // the driver's: the first point's
    Put(out, 0, p.x);
    Put(out, 4, p.y);
    Put(out, 8, p.z);
    Put(out, 16, p.intensity);
    Put(out, 24, timestamp);
    Put(out, 32, p.ring);
  }
  return cloud;
}

}  // namespace

LidarDriver DriverFor(sim::LidarModelKind model) {
  switch (model) {
    case sim::LidarModelKind::kOs1_64:
      return {"ouster/points", "os_sensor", "os_lidar"};
    case sim::LidarModelKind::kHesaiXt32:
      return {"hesai/pandar", "hesai_lidar", "hesai_lidar"};
    case sim::LidarModelKind::kVlp16:
      break;
  }
  return {"velodyne_points", "velodyne", "velodyne"};
}

sensor_msgs::PointCloud2 ToCloud(const sim::LidarScan& scan, const sim::LidarModel& model,
                                 const ros::Time& scan_start) {
  switch (model.config().model) {
    case sim::LidarModelKind::kOs1_64:
      return Ouster(scan, model, scan_start);
    case sim::LidarModelKind::kHesaiXt32:
      return Hesai(scan, model, scan_start);
    case sim::LidarModelKind::kVlp16:
      break;
  }
  return Velodyne(scan, scan_start);
}

}  // namespace sim_ros
}  // namespace is_graphs
