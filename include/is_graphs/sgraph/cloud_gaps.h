#pragma once

#include <deque>

namespace is_graphs {
namespace sgraph {

/// Clouds that never reached the node, from gaps in the stamps of those that did: the sensor's
/// period is the median of the recent steps between stamps (a 10 Hz LiDAR: 0.1 s), and a step
/// of about n periods means n - 1 clouds missing (dropped by a full subscriber queue when the
/// node is slower than the clouds come, by the transport, or by the driver).
class CloudGapCounter {
 public:
  /// The clouds missing before this one (0 for the first ones, while the period is learnt).
  /// Stamps not after the last one start over (a restarted bag).
  int Add(double stamp);
  int missing() const { return missing_; }  // since the start
  double period() const;                    // s; 0 while unknown

 private:
  static constexpr int kWindow = 21;  // steps the period is the median of
  static constexpr int kMinSteps = 5;
  std::deque<double> steps_;
  double last_{-1.0};
  int missing_{0};
};

}  // namespace sgraph
}  // namespace is_graphs
