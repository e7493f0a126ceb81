#include "is_graphs/pipeline/localization_pipeline.h"

#include <chrono>

namespace is_graphs {
namespace pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace

std::string PipelineConfig::Validate() const {
  if (auto e = frontend.Validate(); !e.empty()) return "frontend: " + e;
  if (auto e = backend.Validate(); !e.empty()) return "backend: " + e;
  if (auto e = matcher.Validate(); !e.empty()) return "matcher: " + e;
  if (auto e = merger.Validate(); !e.empty()) return "merger: " + e;
  return "";
}

LocalizationPipeline::LocalizationPipeline(const PipelineConfig& config)
    : config_(config),
      builder_(config.frontend, config.backend),
      matcher_(config.matcher),
      merger_(config.merger) {}

std::string LocalizationPipeline::SetAGraph(const agraph::AGraph& graph) {
  const std::string error = merger_.SetAGraph(graph);
  if (!error.empty()) return error;
  matcher_.SetAGraph(graph);
  bim_T_odom_ = bim_T_map_ = Eigen::Isometry3d::Identity();
  anchor_ = {};
  return "";
}

std::string LocalizationPipeline::SetPoseHint(double stamp, const matching::PoseHint& hint) {
  const std::string error = hinted_.Set(hint);
  PipelineEvent e;
  e.stamp = stamp;
  e.kind = "hint";
  e.message = error.empty() ? hinted_.Describe() : "pose hint not used: " + error;
  events_.push_back(e);
  // In force at once, as matcher_node matches its last S-Graph again on a hint.
  if (error.empty() && matcher_.HasAGraph() && builder_.num_keyframes() > 0)
    MatchAndMerge(stamp, builder_.Snapshot());
  return error;
}

std::optional<Eigen::Isometry3d> LocalizationPipeline::AddOdometry(
    double stamp, const Eigen::Isometry3d& odom_T_base) {
  const auto r = builder_.AddOdometry(stamp, odom_T_base);
  if (r.reset) {
    merger_.Reset();
    matcher_.ForgetHistory();
    hinted_.Clear();  // its robot pose in M is of the map gone
  }
  if (!r.accepted || !merger_.merged()) return std::nullopt;
  return anchor_.Pose(r.odom_T_base);  // the reading as the S-Graph uses it (guard's bridge)
}

sgraph::SGraphBuilder::ScanResult LocalizationPipeline::AddScan(
    const sgraph::Scan& scan, const Eigen::Isometry3d& base_T_sensor) {
  auto t0 = Clock::now();
  const auto result = builder_.AddScan(scan, base_T_sensor);
  times_.scan.push_back(MsSince(t0));
  if (result.status != sgraph::SGraphBuilder::ScanStatus::kKeyframe) return result;
  if (result.restarted) {  // track lost: the map the merge was built on is gone
    merger_.Reset();
    matcher_.ForgetHistory();
    hinted_.Clear();
    bim_T_odom_ = bim_T_map_ = Eigen::Isometry3d::Identity();
    anchor_ = {};
    PipelineEvent e;
    e.stamp = scan.stamp;
    e.kind = "sgraph_restarted";
    e.message = result.warning;
    events_.push_back(e);
  }
  times_.preprocess.push_back(result.preprocess_ms);
  times_.extraction.push_back(result.extraction_ms);
  times_.association.push_back(result.association_ms);
  times_.rooms.push_back(result.rooms_ms);

  t0 = Clock::now();
  const auto summary = builder_.Optimize();
  times_.optimization.push_back(MsSince(t0));
  times_.optimization_keyframes.push_back(summary.num_keyframes);
  const sgraph::SGraph graph = builder_.Snapshot();
  if (matcher_.HasAGraph()) MatchAndMerge(scan.stamp, graph);
  return result;
}

void LocalizationPipeline::MatchAndMerge(double stamp, const sgraph::SGraph& graph) {
  auto t0 = Clock::now();
  const matching::GraphMatch match = hinted_.Match(matcher_, graph);
  times_.matching.push_back(MsSince(t0));
  PipelineEvent e;
  e.stamp = stamp;
  e.revision = graph.revision;
  e.kind = "match";
  e.status = match.status;
  e.bim_T_map = match.bim_T_map;
  e.storey = match.storey;
  e.hypotheses = match.hypotheses;
  e.competing_storeys = match.competing_storeys;
  e.message = std::to_string(match.room_pairs.size()) + " room pairs, " +
              std::to_string(match.hypotheses) + " hypotheses, score " +
              std::to_string(match.score);
  if (!match.scan_search.empty()) e.message += "; scan search: " + match.scan_search;
  if (!match.competing_storeys.empty()) {
    e.message += ", also fits storey";
    for (int s : match.competing_storeys) e.message += " " + std::to_string(s);
  }
  if (match.hint.rfind("rejected", 0) == 0) {
    PipelineEvent rejected = e;
    rejected.kind = "hint_rejected";
    rejected.message = match.hint;
    events_.push_back(rejected);
  }
  if (events_.empty() || events_.back().kind != "match" || events_.back().status != match.status)
    events_.push_back(e);
  if (match.status == matching::MatchStatus::kUnique) unique_matches_.push_back(e);
  matches_.push_back(e);

  if (match.status != matching::MatchStatus::kUnique && !merger_.merged()) return;
  t0 = Clock::now();
  const merging::MergeOutput out = match.status == matching::MatchStatus::kUnique
                                       ? merger_.OnMatch(match, graph)
                                       : merger_.OnSGraph(graph);
  times_.merging.push_back(MsSince(t0));
  Record(stamp, graph.revision, out);
}

void LocalizationPipeline::Record(double stamp, unsigned revision,
                                  const merging::MergeOutput& out) {
  if (out.merged) bim_T_odom_ = out.bim_T_odom, bim_T_map_ = out.bim_T_map, anchor_ = out.anchor;
  if (out.event == merging::MergeEvent::kNone || out.event == merging::MergeEvent::kUpdated) return;
  PipelineEvent e;
  e.stamp = stamp;
  e.revision = revision;
  e.kind = merging::ToString(out.event);
  e.bim_T_map = out.bim_T_map;
  e.message = out.message;
  events_.push_back(e);
}

}  // namespace pipeline
}  // namespace is_graphs
