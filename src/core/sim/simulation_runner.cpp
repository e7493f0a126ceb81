#include "is_graphs/sim/simulation_runner.h"

#include <future>

namespace is_graphs {
namespace sim {

RunStats RunSimulation(const Simulation& sim, SimulationSink& sink, bool pipelined) {
  RunStats stats;
  OdometryDrift odometry = sim.MakeOdometry();
  const double odom_dt = 1.0 / sim.config.odometry.rate_hz;
  const double scan_dt = sim.sensor->ScanPeriod();
  const int n_scans = sim.NumScans();
  auto simulate = [&sim, scan_dt](int k) {
    return sim.scans->Simulate(static_cast<std::uint64_t>(k), k * scan_dt);
  };
  auto next_published = [&sim, n_scans](int k) {
    while (k < n_scans && sim.ScanDropped(k)) ++k;
    return k;
  };
  std::future<LidarScan> next;
  int pending = next_published(0);
  if (pipelined && pending < n_scans) next = std::async(std::launch::async, simulate, pending);
  int leg = 0;
  for (int k = 0; k <= n_scans; ++k) {
    const double until = k < n_scans ? (k + 1) * scan_dt : sim.duration;
    for (; stats.odometry_samples * odom_dt <= until + 1e-9; ++stats.odometry_samples) {
      const double t = stats.odometry_samples * odom_dt;
      const Eigen::Isometry3d truth = sim.motion->BasePose(t);
      const int now = sim.motion->LegAt(t);
      if (now != leg) odometry.Carried();  // kidnapped since the last sample
      leg = now;
      sink.OnOdometry(t, truth, odometry.Step(t, truth));
    }
    if (k == n_scans) break;
    if (k != pending) {  // in a dropout
      ++stats.dropped_scans;
      continue;
    }
    LidarScan scan = pipelined ? next.get() : simulate(k);
    pending = next_published(k + 1);
    if (pipelined && pending < n_scans) next = std::async(std::launch::async, simulate, pending);
    stats.points += scan.points.size();
    ++stats.scans;
    sink.OnScan(scan, (k + 1) * scan_dt);
  }
  return stats;
}

}  // namespace sim
}  // namespace is_graphs
