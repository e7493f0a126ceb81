// bench_long: the whole localization (LocalizationPipeline, as replay_pipeline runs it) fed scan
// by scan straight from the simulator, without a bag: an hour-long run costs no disk (a 540 s
// bag is 2.9 GB). Per time window of the run (default 10 min): the p50 / p99 of the S-Graph
// optimization, the matching and the merging, the pipeline's real-time factor (the time spent in
// the pipeline's calls only, the ray casting excluded), the peak RSS so far (getrusage), the x-y
// and z errors of the published BIM-frame pose against the truth, the share of published poses
// on the truth's storey (agraph::StoreyAtHeight of each; a multi-storey run), and the most
// keyframes one S-Graph optimization had (moved or held: BackendConfig::window_keyframes).
// Prints a Markdown table, a row as each window ends. The localizer gets the scenario's
// `localizer_storey` ("": the whole building), else its `storey`, as make_bags / evaluate do.
//
// The ray casting (about 80 ms a scan here, more than the pipeline) runs on a second thread
// while the pipeline handles the previous scan (--serial: not; slower, for a busy machine).
//
//   bench_long SCENARIO.yaml [--root DIR] [--duration S] [--window S] [--serial]
//   (--root: the repository, for the YAML's relative `building` (default .); --duration: stop
//    after S s of the scenario; --window: the table's row length in s)
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/pipeline/localization_pipeline.h"
#include "is_graphs/sim/scenario_yaml.h"
#include "is_graphs/sim/simulation.h"
#include "is_graphs/sim/simulation_runner.h"

namespace is_graphs {
namespace {

using Clock = std::chrono::steady_clock;

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t i = static_cast<size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
  return v[std::min(v.size() - 1, q <= 0.0 ? 0 : i)];
}

double PeakRssMib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

/// One row of the table: what the pipeline did in [start, end) s of the run.
struct Window {
  Window(double from, double to) : start(from), end(to) {}
  double start{0.0}, end{0.0};
  std::vector<double> optimization, matching, merging, errors, z_errors;
  std::vector<double> right_storey;       // 1 where the pose's storey is the truth's, else 0
  std::vector<double> problem_keyframes;  // in each S-Graph optimization (moved or held)
  double pipeline_seconds{0.0};
  int keyframes{0};
  double peak_rss_mib{0.0};
};

std::string Cell(const std::vector<double>& v) {
  char s[64];
  std::snprintf(s, sizeof s, "%.1f / %.1f", Percentile(v, 0.5), Percentile(v, 0.99));
  return s;
}

void PrintRow(const std::string& label, const Window& w) {
  const double seconds = w.end - w.start;
  double rms = 0.0;
  for (double e : w.errors) rms += e * e;
  rms = w.errors.empty() ? NAN : std::sqrt(rms / static_cast<double>(w.errors.size()));
  double rms_z = 0.0, right = 0.0;
  for (double e : w.z_errors) rms_z += e * e;
  rms_z = w.z_errors.empty() ? NAN : std::sqrt(rms_z / static_cast<double>(w.z_errors.size()));
  for (double r : w.right_storey) right += r;
  right = w.right_storey.empty() ? NAN : 100.0 * right / static_cast<double>(w.right_storey.size());
  std::printf("| %s | %d | %.0f | %s | %s | %s | %.1f× | %.0f | %.3f | %.3f | %.1f |\n",
              label.c_str(), w.keyframes, Percentile(w.problem_keyframes, 1.0),
              Cell(w.optimization).c_str(), Cell(w.matching).c_str(), Cell(w.merging).c_str(),
              seconds / std::max(1e-9, w.pipeline_seconds), w.peak_rss_mib, rms, rms_z, right);
  std::fflush(stdout);
}

std::string Minutes(const Window& w) {
  char label[32];
  std::snprintf(label, sizeof label, "%.0f–%.0f", w.start / 60.0, w.end / 60.0);
  return label;
}

/// Feeds the simulation to the pipeline, timing the pipeline's calls only.
class PipelineSink : public sim::SimulationSink {
 public:
  PipelineSink(pipeline::LocalizationPipeline& p, const sim::Simulation& sim, double window,
               double duration)
      : pipeline_(p), sim_(sim), window_(window), duration_(duration) {
    windows_.emplace_back(0.0, window_);
  }

  void OnOdometry(double t, const Eigen::Isometry3d& truth,
                  const sim::OdometrySample& odometry) override {
    if (t > duration_) return;
    Roll(t);
    const auto t0 = Clock::now();
    const auto pose = pipeline_.AddOdometry(sim_.config.start_time + t, odometry.odom_T_base);
    windows_.back().pipeline_seconds += Seconds(t0);
    if (pose) {
      Window& w = windows_.back();
      w.errors.push_back((pose->translation() - truth.translation()).head<2>().norm());
      w.z_errors.push_back(std::abs(pose->translation().z() - truth.translation().z()));
      const bool right = agraph::StoreyAtHeight(sim_.graph, pose->translation().z()) ==
                         agraph::StoreyAtHeight(sim_.graph, truth.translation().z());
      w.right_storey.push_back(right ? 1.0 : 0.0);
      if (!right) {  // how far the truth was from a storey's boundary height (StoreyAtHeight's)
        double nearest = INFINITY;
        for (const auto& storey : sim_.graph.storeys)
          nearest = std::min(nearest, std::abs(truth.translation().z() + 0.05 - storey.elevation));
        wrong_storey_margin_ = std::max(wrong_storey_margin_, nearest);
      }
    }
  }

  void OnScan(const sim::LidarScan& scan, double publish_time) override {
    if (publish_time > duration_) return;
    Roll(publish_time);
    sgraph::Scan s;
    s.stamp = sim_.config.start_time + scan.stamp;
    s.frame_id = "sensor";
    s.points.reserve(scan.points.size());
    for (const auto& p : scan.points)
      s.points.push_back({p.x, p.y, p.z, p.intensity, p.ring, p.time});
    const pipeline::StageTimes& times = pipeline_.times();
    const size_t o = times.optimization.size(), m = times.matching.size(), g = times.merging.size();
    const auto t0 = Clock::now();
    pipeline_.AddScan(s, sim_.base_T_sensor);
    Window& w = windows_.back();
    w.pipeline_seconds += Seconds(t0);
    w.optimization.insert(w.optimization.end(), times.optimization.begin() + o,
                          times.optimization.end());
    w.problem_keyframes.insert(w.problem_keyframes.end(), times.optimization_keyframes.begin() + o,
                               times.optimization_keyframes.end());
    w.matching.insert(w.matching.end(), times.matching.begin() + m, times.matching.end());
    w.merging.insert(w.merging.end(), times.merging.begin() + g, times.merging.end());
  }

  /// The most a pose on another storey than the truth's had the truth from a storey's boundary.
  double wrong_storey_margin() const { return wrong_storey_margin_; }

  /// Closes (and prints) the last window.
  std::vector<Window>& Finish(double end) {
    windows_.back().end = std::min(windows_.back().end, end);
    Close(windows_.back());
    if (windows_.back().end > windows_.back().start)
      PrintRow(Minutes(windows_.back()), windows_.back());
    return windows_;
  }

 private:
  static double Seconds(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  }
  void Close(Window& w) {
    w.keyframes = pipeline_.builder().num_keyframes();
    w.peak_rss_mib = PeakRssMib();
  }
  void Roll(double t) {
    while (t >= windows_.back().end) {
      Close(windows_.back());
      PrintRow(Minutes(windows_.back()), windows_.back());
      const double start = windows_.back().end;
      windows_.emplace_back(start, start + window_);
    }
  }

  pipeline::LocalizationPipeline& pipeline_;
  const sim::Simulation& sim_;
  double window_, duration_;
  std::vector<Window> windows_;
  double wrong_storey_margin_{0.0};
};

int Usage() {
  std::cerr << "usage: bench_long SCENARIO.yaml [--root DIR] [--duration S] [--window S] "
               "[--serial]\n";
  return 2;
}

int Run(int argc, char** argv) {
  if (argc < 2) return Usage();
  std::string yaml = argv[1], root = ".";
  double duration = -1.0, window = 600.0;
  bool pipelined = true;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--serial") {
      pipelined = false;
      continue;
    }
    if (i + 1 >= argc) return Usage();
    if (a == "--root")
      root = argv[++i];
    else if (a == "--duration")
      duration = std::stod(argv[++i]);
    else if (a == "--window")
      window = std::stod(argv[++i]);
    else
      return Usage();
  }
  if (!(window > 0.0)) return Usage();
  const auto config = sim::LoadScenarioYaml(yaml, root);
  if (!config.ok()) return std::cerr << "bench_long: " << config.error() << "\n", 2;
  const double full = config.value().duration;  // 0: until the route ends
  const double scale = full > 0.0 && duration > 0.0 && duration < full ? duration / full : 1.0;
  const auto prepared =
      sim::PrepareSimulation(config.value(), sim::DefaultBimCacheDir(root), scale);
  if (!prepared.ok()) return std::cerr << "bench_long: " << prepared.error() << "\n", 2;
  const sim::Simulation& sim = *prepared.value();
  duration = sim.duration;

  pipeline::PipelineConfig pipeline_config;
  if (const auto e = pipeline_config.Validate(); !e.empty())
    return std::cerr << "bench_long: " << e << "\n", 2;
  pipeline::LocalizationPipeline localization(pipeline_config);
  // The storey the localizer is told, as replay_pipeline's --storey gives it: `localizer_storey`
  // where the scenario has one ("": the whole building), else the storey the robot starts on.
  const std::optional<std::string>& told = sim.config.localizer_storey;
  const auto building = !told           ? agraph::SelectStorey(sim.graph, sim.storey)
                        : told->empty() ? Result<agraph::AGraph>::Ok(sim.graph)
                                        : agraph::SelectStorey(sim.graph, *told);
  if (!building.ok()) return std::cerr << "bench_long: " << building.error() << "\n", 2;
  if (const auto e = localization.SetAGraph(building.value()); !e.empty())
    return std::cerr << "bench_long: unusable A-Graph: " << e << "\n", 2;

  std::cerr << "bench_long: " << yaml << ", " << duration << " s of simulated run, the localizer "
            << (told && told->empty() ? "given the whole building (" : "given one storey (of ")
            << sim.graph.storeys.size() << " storeys)\n";
  std::printf(
      "| run [min] | keyframes | optimized keyframes (max) | optimization p50 / p99 [ms] | "
      "matching p50 / p99 [ms] | merging p50 / p99 [ms] | pipeline RTF | peak RSS [MiB] | "
      "x-y error RMS [m] | z error RMS [m] | on the right storey [%%] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  PipelineSink sink(localization, sim, window, duration);
  const auto start = Clock::now();
  sim::RunSimulation(sim, sink, pipelined);
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  std::vector<Window>& windows = sink.Finish(duration);
  Window all(0.0, duration);
  for (const Window& w : windows) {
    using Series = std::vector<double> Window::*;
    for (Series v : {&Window::optimization, &Window::matching, &Window::merging, &Window::errors,
                     &Window::z_errors, &Window::right_storey, &Window::problem_keyframes})
      (all.*v).insert((all.*v).end(), (w.*v).begin(), (w.*v).end());
    all.pipeline_seconds += w.pipeline_seconds;
  }
  all.keyframes = windows.back().keyframes;
  all.peak_rss_mib = PeakRssMib();
  PrintRow("whole run", all);
  const auto& events = localization.events();
  const auto first = std::find_if(events.begin(), events.end(),
                                  [](const auto& e) { return e.kind == "localized"; });
  std::printf("\nlocalized %s; %zu events; pipeline %.0f s, whole (with ray casting) %.0f s\n",
              first == events.end()
                  ? "never"
                  : ("at " + std::to_string(first->stamp - sim.config.start_time) + " s").c_str(),
              events.size(), all.pipeline_seconds, wall);
  // The events by kind (a "lost" or "rejected" shows here) and the poses off the truth's storey.
  std::map<std::string, int> kinds;
  for (const auto& e : events) ++kinds[e.kind];
  std::string by_kind;
  for (const auto& [kind, n] : kinds)
    by_kind += (by_kind.empty() ? "" : ", ") + kind + " " + std::to_string(n);
  const auto wrong = std::count(all.right_storey.begin(), all.right_storey.end(), 0.0);
  std::printf(
      "events: %s; %zu poses published, %td on another storey than the truth's (the truth at most "
      "%.3f m from a storey's boundary height then)\n\n",
      by_kind.c_str(), all.right_storey.size(), wrong, sink.wrong_storey_margin());
  return 0;
}

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) { return is_graphs::Run(argc, argv); }
