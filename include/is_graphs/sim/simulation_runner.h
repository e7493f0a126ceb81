#pragma once

#include <Eigen/Geometry>
#include <cstddef>

#include "is_graphs/sim/odometry_drift.h"
#include "is_graphs/sim/scan_simulator.h"
#include "is_graphs/sim/simulation.h"

namespace is_graphs {
namespace sim {

/// Receives the simulation's outputs in time order (times in s after the start).
class SimulationSink {
 public:
  virtual ~SimulationSink() = default;
  /// One odometry-rate sample: the true base_link pose in bim and the drifting odometry.
  virtual void OnOdometry(double t, const Eigen::Isometry3d& bim_T_base,
                          const OdometrySample& odometry) = 0;
  /// One complete scan, at `publish_time` = scan.stamp + scan period (when a driver has it).
  virtual void OnScan(const LidarScan& scan, double publish_time) = 0;
};

struct RunStats {
  int scans{0};          // published
  int dropped_scans{0};  // in `sensor.dropouts`
  long odometry_samples{0};
  std::size_t points{0};
};

/// Runs the scenario from t = 0 to sim.duration: odometry/ground truth at the odometry rate and
/// scans at the rotation rate, delivered to `sink` in time order (samples up to a scan's end
/// before the scan). With `pipelined`, the next scan is ray-cast on a second thread while the
/// sink handles the current one; the output is identical either way (each scan draws from its
/// own random stream). Scans in a dropout window are neither simulated nor delivered; the
/// odometry runs on. At a kidnap's carry the odometry is told (OdometryDrift::Carried).
RunStats RunSimulation(const Simulation& sim, SimulationSink& sink, bool pipelined = true);

}  // namespace sim
}  // namespace is_graphs
