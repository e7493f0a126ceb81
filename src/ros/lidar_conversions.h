#pragma once

#include <sensor_msgs/PointCloud2.h>

#include <set>
#include <string>
#include <vector>

#include "cloud_layout.h"
#include "is_graphs/common/result.h"
#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace ros_conversions {

/// How LiDAR clouds are read (sgraph_node parameters `cloud_layout`,
/// `cloud_max_sweep_period`; replay_pipeline --cloud-layout). Validated once.
struct LidarCloudConfig {
  CloudLayoutKind layout{CloudLayoutKind::kAuto};
  // Per-point times further than 1.5 x this from the stamp are in an unknown unit: the cloud
  // is used without deskew. 0.2 s: the slowest common rate (5 Hz).
  double max_sweep_period{0.2};
  /// "" when valid, else "<parameter> <what is wrong>".
  std::string Validate() const;
};

/// A cloud with a known layout as the core's scan: per-point times made relative to the header
/// stamp (has_time false when the layout has none, or when they reach beyond 1.5 x
/// max_sweep_period: an unknown unit); rings out of range (>= the rows of an organized cloud,
/// else >= 256) set to 0. Points with non-finite x, y or z are dropped when the cloud declares
/// them (is_dense false, as ouster-ros' organized clouds), else kept (the core drops, counts and
/// warns about them). Each
/// non-fatal problem of this cloud is appended to `problems` as {key, message}. An error when
/// the layout is unusable or the data is shorter than width x height x point_step.
Result<sgraph::Scan> FromLidarMsg(const sensor_msgs::PointCloud2& msg, const CloudLayout& layout,
                                  double max_sweep_period,
                                  std::vector<std::pair<std::string, std::string>>* problems);

/// Reads clouds as they come: the layout is detected once per fields signature, and each kind
/// of problem is reported once per signature (a stream of bad clouds gives one warning).
class LidarCloudReader {
 public:
  explicit LidarCloudReader(const LidarCloudConfig& config) : config_(config) {}

  /// The scan, or the error (the cloud is skipped; not deduplicated: log it throttled).
  /// `info`: the layout, set the first time a signature is seen; `warnings`: problems to log
  /// now (each the first time only).
  Result<sgraph::Scan> Read(const sensor_msgs::PointCloud2& msg, std::string* info,
                            std::vector<std::string>* warnings);
  const CloudLayout& layout() const { return layout_; }

 private:
  LidarCloudConfig config_;
  std::string signature_;
  bool have_layout_{false};
  CloudLayout layout_;
  std::set<std::string> reported_;  // "<signature>#<problem key>"
};

/// One line describing a layout, e.g. "ouster (per-point time 't' uint32 ns; fields: ...)".
std::string Describe(const CloudLayout& layout);

}  // namespace ros_conversions
}  // namespace is_graphs
