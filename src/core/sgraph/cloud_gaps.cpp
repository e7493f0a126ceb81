#include "is_graphs/sgraph/cloud_gaps.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace is_graphs {
namespace sgraph {

double CloudGapCounter::period() const {
  if (static_cast<int>(steps_.size()) < kMinSteps) return 0.0;
  std::vector<double> sorted(steps_.begin(), steps_.end());
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  return sorted[sorted.size() / 2];
}

int CloudGapCounter::Add(double stamp) {
  if (!std::isfinite(stamp)) return 0;
  if (last_ >= 0.0 && stamp <= last_) {  // time went back: learn the period anew
    steps_.clear();
    last_ = stamp;
    return 0;
  }
  int missing = 0;
  if (last_ >= 0.0) {
    const double step = stamp - last_;
    const double p = period();
    if (p > 0.0) missing = std::max(0, static_cast<int>(std::lround(step / p)) - 1);
    // Steps over gaps would raise the median: only steps of about one period are learnt.
    if (missing == 0) {
      steps_.push_back(step);
      if (static_cast<int>(steps_.size()) > kWindow) steps_.pop_front();
    }
  }
  last_ = stamp;
  missing_ += missing;
  return missing;
}

}  // namespace sgraph
}  // namespace is_graphs
