#include "is_graphs/matching/pose_hint.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/graph_matcher.h"

namespace is_graphs {
namespace matching {
namespace {

std::string Format(const char* fmt, double a, double b, double c) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

std::string XYYaw(const Pose2& p) {
  return Format("(%.2f, %.2f, %.1f deg)", p.t.x(), p.t.y(), p.yaw * 180.0 / M_PI);
}

}  // namespace

std::string CheckPoseHint(const PoseHint& hint) {
  const auto finite = [](const Pose2& p) { return std::isfinite(p.yaw) && p.t.allFinite(); };
  if (!finite(hint.bim_T_base)) return "the hint's pose is not finite (NaN or inf)";
  if (!finite(hint.map_T_base))
    return "the robot's pose in the map at the hint's stamp is not finite";
  if (!hint.covariance.allFinite()) return "the hint's covariance is not finite (NaN or inf)";
  const Eigen::Matrix3d& c = hint.covariance;
  if ((c - c.transpose()).cwiseAbs().maxCoeff() > 1e-9 * std::max(1.0, c.cwiseAbs().maxCoeff()))
    return "the hint's x, y, yaw covariance is not symmetric";
  const Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c).eigenvalues();
  if (eig.minCoeff() <= 0.0)
    return Format(
        "the hint's x, y, yaw covariance is not positive definite (eigenvalues %.3g, %.3g, %.3g)",
        eig(0), eig(1), eig(2));
  return "";
}

HintGate::HintGate(const PoseHint& hint) : hint_(hint), information_(hint.covariance.inverse()) {}

Pose2 PlanarPose(const Eigen::Isometry3d& pose) {
  return {geometry::Yaw(pose), pose.translation().head<2>()};
}

Pose2 ImpliedRobotPose(const Pose2& bim_T_map, const Pose2& map_T_base) {
  return {geometry::NormalizeAngle(bim_T_map.yaw + map_T_base.yaw), bim_T_map.Apply(map_T_base.t)};
}

double HintGate::Distance2(const Pose2& bim_T_map) const {
  const Pose2 robot = ImpliedRobotPose(bim_T_map, hint_.map_T_base);
  Eigen::Vector3d e;
  e.head<2>() = robot.t - hint_.bim_T_base.t;
  e.z() = geometry::NormalizeAngle(robot.yaw - hint_.bim_T_base.yaw);
  return e.dot(information_ * e);
}

bool HintGate::Inside(const Pose2& bim_T_map, int storey) const {
  if (hint_.storey >= 0 && storey >= 0 && storey != hint_.storey) return false;
  return Distance2(bim_T_map) <= kHintGateChi2;
}

std::string HintedMatching::Set(const PoseHint& hint) {
  if (std::string why = CheckPoseHint(hint); !why.empty()) return why;
  gate_.emplace(hint);
  return "";
}

std::string HintedMatching::Describe() const {
  if (!gate_) return "";
  const PoseHint& h = gate_->hint();
  std::string out =
      "pose hint " + XYYaw(h.bim_T_base) +
      Format(" +- %.2f m, %.1f deg", std::sqrt(std::max(h.covariance(0, 0), h.covariance(1, 1))),
             std::sqrt(h.covariance(2, 2)) * 180.0 / M_PI, 0.0);
  if (h.storey >= 0) out += ", storey " + std::to_string(h.storey);
  if (!h.description.empty()) out += " (" + h.description + ")";
  return out;
}

GraphMatch HintedMatching::Match(GraphMatcher& matcher, const sgraph::SGraph& graph) {
  GraphMatch free = matcher.Match(graph);
  if (!gate_) return free;
  if (free.status == MatchStatus::kUnique) {
    const Pose2 motion = PlanarPose(free.bim_T_map);
    if (gate_->Inside(motion, free.storey)) {
      free.hint = "in force, agrees: " + Describe();
      return free;
    }
    const double d = std::sqrt(gate_->Distance2(motion));
    const bool other_storey = gate_->hint().storey >= 0 && free.storey != gate_->hint().storey;
    std::string why = "the walls seen fit only the robot at " +
                      XYYaw(ImpliedRobotPose(motion, gate_->hint().map_T_base));
    why += other_storey
               ? " on storey " + std::to_string(free.storey)
               : Format(", %.1f sigma from the hint (gate %.1f)", d, std::sqrt(kHintGateChi2), 0.0);
    why += "; localizing as without it (" + Describe() + ")";
    free.warnings.push_back("pose hint rejected: " + why);
    free.hint = "rejected: " + why;
    gate_.reset();
    return free;
  }
  matcher.SetGate(&*gate_);
  GraphMatch gated = matcher.Match(graph);
  matcher.SetGate(nullptr);
  gated.hint = "in force: " + Describe();
  if (gated.status == MatchStatus::kNone && free.status != MatchStatus::kNone) {
    const Pose2 motion = PlanarPose(free.bim_T_map);
    gated.warnings.push_back(
        "no hypothesis inside the pose hint's gate; the evidence's best puts the robot at " +
        XYYaw(ImpliedRobotPose(motion, gate_->hint().map_T_base)) +
        Format(", %.1f sigma from the hint (gate %.1f)", std::sqrt(gate_->Distance2(motion)),
               std::sqrt(kHintGateChi2), 0.0));
  }
  return gated;
}

}  // namespace matching
}  // namespace is_graphs
