#include "localization_services.h"

namespace is_graphs {
namespace ros_matcher {
namespace {

Request Make(Request::Kind kind) {
  Request r;
  r.kind = kind;
  return r;
}

}  // namespace

LocalizationServices::LocalizationServices(ros::NodeHandle& nh,
                                           const ros_conversions::HintFrames& frames,
                                           std::function<void(const Request&)> submit)
    : frames_(frames), submit_(std::move(submit)), tf_listener_(tf_buffer_), tf_(tf_buffer_) {
  initialpose_sub_ = nh.subscribe("initialpose", 1, &LocalizationServices::OnInitialPose, this);
  hint_srv_ = nh.advertiseService("set_pose_hint", &LocalizationServices::OnSetPoseHint, this);
  relocalize_srv_ = nh.advertiseService("relocalize", &LocalizationServices::OnRelocalize, this);
  storey_srv_ = nh.advertiseService("set_storey", &LocalizationServices::OnSetStorey, this);
}

void LocalizationServices::SetBuilding(const agraph::AGraph& building) {
  std::lock_guard<std::mutex> lock(mutex_);
  storeys_ = agraph::AGraph{};
  storeys_.storeys = building.storeys;
  has_building_ = true;
}

Result<int> LocalizationServices::Storey(const std::string& storey) {
  if (storey.empty()) return Result<int>::Ok(-1);
  std::lock_guard<std::mutex> lock(mutex_);
  if (!has_building_)
    return Result<int>::Error("no A-Graph yet (a_graph): cannot look up storey '" + storey + "'");
  return ros_conversions::HintStorey(storeys_, storey);
}

Result<matching::PoseHint> LocalizationServices::Hint(
    const geometry_msgs::PoseWithCovarianceStamped& msg, const std::string& storey) {
  const Result<int> id = Storey(storey);
  if (!id.ok()) return Result<matching::PoseHint>::Error(id.error());
  return ros_conversions::PoseHintFromMsg(msg, id.value(), tf_, frames_);
}

void LocalizationServices::OnInitialPose(
    const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& msg) {
  const auto hint = Hint(*msg, "");
  if (!hint.ok()) {
    ROS_WARN("matcher_node: pose hint on initialpose not used: %s", hint.error().c_str());
    return;
  }
  Request r = Make(Request::Kind::kHint);
  r.hint = hint.value();
  submit_(r);
}

bool LocalizationServices::OnSetPoseHint(is_graphs::SetPoseHint::Request& req,
                                         is_graphs::SetPoseHint::Response& res) {
  auto hint = Hint(req.pose, req.storey);
  res.success = hint.ok();
  if (!hint.ok()) {
    res.message = "pose hint not used: " + hint.error();
    ROS_WARN("matcher_node: set_pose_hint: %s", res.message.c_str());
    return true;
  }
  hint.value().description = "set_pose_hint, " + hint.value().description;
  Request r = Make(Request::Kind::kHint);
  r.hint = hint.value();
  submit_(r);
  matching::HintedMatching describe;
  describe.Set(hint.value());
  res.message = describe.Describe() + ": in force from the next match";
  return true;
}

bool LocalizationServices::OnRelocalize(std_srvs::Trigger::Request&,
                                        std_srvs::Trigger::Response& res) {
  submit_(Make(Request::Kind::kRelocalize));
  res.success = true;
  res.message = "the match and any pose hint forgotten; localizing again";
  return true;
}

bool LocalizationServices::OnSetStorey(is_graphs::SetStorey::Request& req,
                                       is_graphs::SetStorey::Response& res) {
  const Result<int> id = Storey(req.storey);
  res.success = id.ok();
  if (!id.ok()) {
    res.message = "storey not changed: " + id.error();
    ROS_WARN("matcher_node: set_storey: %s", res.message.c_str());
    return true;
  }
  Request r = Make(Request::Kind::kStorey);
  r.storey = id.value();
  r.storey_name = req.storey;
  submit_(r);
  res.message = req.storey.empty() ? "matching on the whole building; localizing again"
                                   : "matching on storey '" + req.storey + "' (id " +
                                         std::to_string(id.value()) + ") only; localizing again";
  return true;
}

}  // namespace ros_matcher
}  // namespace is_graphs
