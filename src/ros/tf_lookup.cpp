#include "tf_lookup.h"

#include <tf2/exceptions.h>
#include <tf2_eigen/tf2_eigen.h>

namespace is_graphs {
namespace ros_tf {

Result<Eigen::Isometry3d> TfLookup::Lookup(const std::string& target, const std::string& source,
                                           const ros::Time& time,
                                           const ros::Duration& timeout) const {
  using R = Result<Eigen::Isometry3d>;
  if (target.empty() || source.empty())
    return R::Error("no transform from '" + source + "' to '" + target + "': empty frame name");
  try {
    const auto t = buffer_.lookupTransform(target, source, time, timeout);
    const Eigen::Isometry3d out = tf2::transformToEigen(t);
    if (!out.matrix().allFinite())
      return R::Error("the transform from '" + source + "' to '" + target +
                      "' is not finite (NaN or inf in tf)");
    return R::Ok(out);
  } catch (const tf2::TransformException& e) {
    return R::Error("no transform from '" + source + "' to '" + target + "': " + e.what());
  }
}

Result<ros::Time> TfLookup::LatestStamp(const std::string& target,
                                        const std::string& source) const {
  using R = Result<ros::Time>;
  try {
    return R::Ok(buffer_.lookupTransform(target, source, ros::Time(0)).header.stamp);
  } catch (const tf2::TransformException& e) {
    return R::Error("no transform from '" + source + "' to '" + target + "': " + e.what());
  }
}

Result<Eigen::Isometry3d> TfLookup::LookupStatic(const std::string& target,
                                                 const std::string& source,
                                                 const ros::Duration& timeout) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = static_cache_.find({target, source});
    if (it != static_cache_.end()) return Result<Eigen::Isometry3d>::Ok(it->second);
  }
  auto r = Lookup(target, source, ros::Time(0), timeout);
  if (r.ok()) {
    std::lock_guard<std::mutex> lock(mutex_);
    static_cache_[{target, source}] = r.value();
  }
  return r;
}

}  // namespace ros_tf
}  // namespace is_graphs
