#!/usr/bin/env python3
"""`make evaluate`: the localization on every full-length scenario bag against ground truth.

For each scenario (bags/D*, R*, H*, S*, M*, G*, E*, P*, A* and L*.yaml, not *_short; an R
scenario whose full bag is absent falls back to its _short bag, and says so; a missing D bag is listed as missing), runs
replay_pipeline (the core the nodes run, synchronously, without ROS transport: deterministic)
and compares with the ground truth, WITHOUT alignment (evo):
  - iS-Graphs: the pose in the BIM frame, from the first pose after localization on;
  - odometry: raw leg odometry put in the BIM frame with the true start pose;
  - S-Graph alone: its final optimized keyframe trajectory put in the BIM frame the same way,
    and online: map <- odom of the S-Graph at that moment times the odometry (sgraph_node's tf).
Also: time and distance to the first UNIQUE match, wrong UNIQUE matches (> 0.5 m or 5 deg from
the true B_x_M), the map cloud against the BIM wall-surfaces, speed and memory.
Writes OUT/results.md, OUT/results.json and OUT/<scenario>/{run.*, replay.log, trajectory.png,
error.png}. Exit 1 when no bag was evaluated, 2 on a bad scenario or a failed replay.

  evaluate.py [--out .ws/evaluate] [--replay PATH] [SCENARIO.yaml ...]
"""
import argparse
import glob
import json
import os
import subprocess
import sys

import numpy as np

from evaluation_common import ape, place_with_start_pose

REPO = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))


class EvaluationError(Exception):
    pass


def read_scenario(path):
    import yaml

    try:
        with open(path) as f:
            s = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as e:
        raise EvaluationError(f"{path}: cannot read the scenario: {e}") from e
    if not isinstance(s, dict) or not s.get("building"):
        raise EvaluationError(f"{path}: no 'building:' in the scenario")
    building = s["building"] if os.path.isabs(s["building"]) else os.path.join(REPO, s["building"])
    storey = str(s.get("storey", "") or "")
    told = s.get("localizer_storey", storey)  # "" = the whole building (issue 22)
    return building, storey, str(told or "")


def find_bags(yamls):
    """[(name, yaml, bag, note)] for the scenarios with a bag, and the names without one."""
    found, missing = [], []
    for y in yamls:
        name = os.path.basename(y)[:-len(".yaml")]
        bag = os.path.join(os.path.dirname(y), name + ".bag")
        short = os.path.join(os.path.dirname(y), name + "_short.bag")
        if os.path.isfile(bag):
            found.append((name, y, bag, ""))
        elif name.startswith("R") and os.path.isfile(short):
            found.append((name, y[:-5] + "_short.yaml", short,
                          f"full bag absent: its _short bag ({name}_short) used"))
        else:
            missing.append(name)
    return found, missing


def agraph_json(building):
    if building.endswith(".json"):
        return building
    cache = os.path.join(os.environ.get("ROS_HOME", os.path.join(REPO, ".ws", "ros_home")),
                         "is_graphs", "cache")
    proc = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "ifc_to_agraph.py"),
                           building, "--cache-dir", cache, "--quiet"], capture_output=True,
                          text=True)
    if proc.returncode != 0:
        raise EvaluationError(f"{building}: conversion failed: {proc.stderr.strip()}")
    return proc.stdout.strip().splitlines()[-1]


def run_replay(replay, bag, building, storey, prefix):
    args = [replay, bag, "--building", building, "--out-prefix", prefix]
    if storey:
        args += ["--storey", storey]
    with open(prefix + ".replay.log", "w") as log:
        proc = subprocess.run(args, stdout=log, stderr=subprocess.STDOUT)
    if proc.returncode != 0:
        with open(prefix + ".replay.log") as log:
            tail = "".join(log.readlines()[-15:])
        raise EvaluationError(f"replay_pipeline failed on {bag} (exit {proc.returncode}):\n{tail}")


def read_tum(path):
    from evo.tools import file_interface

    if not os.path.isfile(path) or os.path.getsize(path) == 0:
        return None
    return file_interface.read_tum_trajectory_file(path)


def after(traj, t):
    """The poses of `traj` from stamp t on (a copy; None when there are none)."""
    import copy

    ids = np.flatnonzero(traj.timestamps >= t)
    if len(ids) == 0:
        return None
    out = copy.deepcopy(traj)
    out.reduce_to_ids(ids)
    return out


def walked_at(odom, t):
    steps = np.linalg.norm(np.diff(odom.positions_xyz[:, :2], axis=0), axis=1)
    return float(np.interp(t, odom.timestamps, np.concatenate([[0.0], np.cumsum(steps)])))


def storey_at(storeys, z):
    """Index into `storeys` (dicts with "elevation") of the one a base at height z stands on: the
    highest elevation at or below z + 5 cm (agraph::StoreyAtHeight); -1 below them all."""
    best = -1
    for i, s in enumerate(storeys):
        if s["elevation"] <= z + 0.05 and (best < 0 or s["elevation"] > storeys[best]["elevation"]):
            best = i
    return best


def per_storey(storeys, truth_t, truth_xyz, est_t, est_xyz, odom_t, odom_xy, tol_xy=0.5,
               tol_z=1.0):
    """Issue 22's per-storey time to localize. For each storey the truth walks on, in the order
    reached: when the robot arrived on it (s, from truth_t[0]) and the seconds and metres walked
    from then to the first pose in B on it within tol_xy (x-y) and tol_z of the truth (None:
    never). Arrays: stamps (N) and positions (N x 3, or N x 2 for odometry)."""
    truth_t, truth_xyz = np.asarray(truth_t), np.asarray(truth_xyz)
    est_t, est_xyz = np.asarray(est_t), np.asarray(est_xyz).reshape(-1, 3)
    steps = np.linalg.norm(np.diff(np.asarray(odom_xy)[:, :2], axis=0), axis=1)
    walked = np.concatenate([[0.0], np.cumsum(steps)])
    at = [storey_at(storeys, z) for z in truth_xyz[:, 2]]
    out, seen = [], set()
    for k, s in enumerate(at):
        if s < 0 or s in seen:
            continue
        seen.add(s)
        arrived = truth_t[k]
        entry = {"storey": storeys[s].get("name", str(s)), "arrived_s": float(arrived - truth_t[0]),
                 "localized_after_s": None, "localized_after_m": None}
        for t, p in zip(est_t, est_xyz):
            if t < arrived:
                continue
            want = np.array([np.interp(t, truth_t, truth_xyz[:, i]) for i in range(3)])
            if storey_at(storeys, want[2]) != s:
                continue
            if np.linalg.norm(p[:2] - want[:2]) <= tol_xy and abs(p[2] - want[2]) <= tol_z:
                entry["localized_after_s"] = float(t - arrived)
                entry["localized_after_m"] = float(np.interp(t, odom_t, walked)
                                                   - np.interp(arrived, odom_t, walked))
                break
        out.append(entry)
    return out


def public(numbers):
    return {k: v for k, v in numbers.items() if not k.startswith("_")}


def evaluate_outputs(prefix):
    """The numbers of one replay from its files PREFIX.{json,truth,pose_bim,odom,sgraph}.tum, and
    the error series for the plots (under "_series")."""
    with open(prefix + ".json") as f:
        run = json.load(f)
    truth, est = read_tum(prefix + ".truth.tum"), read_tum(prefix + ".pose_bim.tum")
    odom, sgraph = read_tum(prefix + ".odom.tum"), read_tum(prefix + ".sgraph.tum")
    if truth is None or odom is None:
        raise EvaluationError(f"{prefix}: no ground truth or no odometry in the replay's output")
    t0 = run.get("first_stamp", truth.timestamps[0])  # the bag's start: event times count from it
    uniques = run.get("unique_matches", [])
    r = {"bag_seconds": run["bag_seconds"], "walked_m": run["walked_m"],
         "localized": est is not None, "localized_at_end": run.get("localized_at_end", False),
         "unique_matches": len(uniques), "wrong_matches": run.get("wrong_matches", 0),
         "wrong_storey_matches": run.get("wrong_storey_matches", 0),
         "map_cloud_error": run.get("map_cloud_error"), "keyframes": run["keyframes"],
         "real_time_factor": run["real_time_factor"], "replay_seconds": run["wall_seconds"],
         "peak_rss_mib": run["peak_rss_mib"], "_t0": t0}
    if uniques:
        r["first_unique_s"] = uniques[0]["t"]
        r["first_unique_m"] = walked_at(odom, t0 + uniques[0]["t"])
    series, placed = {}, {}
    for method, frame_traj in (("odometry", odom), ("sgraph", sgraph),
                               ("sgraph_online", read_tum(prefix + ".sgraph_online.tum"))):
        if frame_traj is None or frame_traj.num_poses < 2:
            continue
        placed[method], _ = place_with_start_pose(frame_traj, truth)
        numbers = ape(truth, placed[method])
        r[method], series[method] = public(numbers), numbers["_series"]
    if est is not None:
        t_loc = est.timestamps[0]
        r["seconds_to_localize"] = run["seconds_to_localize"]
        r["distance_to_localize"] = run["distance_to_localize"]
        numbers = ape(truth, est)
        r["isgraphs"], series["isgraphs"] = public(numbers), numbers["_series"]
        # The baselines over the same window (after localization), for a like-for-like view.
        for method, traj in placed.items():
            late = after(traj, t_loc)
            if late is not None and late.num_poses > 1:
                r[method + "_after_localization"] = public(ape(truth, late))
    r["_series"], r["_truth"], r["_est"], r["_odom"] = series, truth, est, odom
    return r


def evaluate_scenario(name, yaml_path, bag, note, replay, out_dir):
    from evaluation_plots import error_plot, trajectory_plot

    building, storey, told = read_scenario(yaml_path)
    os.makedirs(os.path.join(out_dir, name), exist_ok=True)
    prefix = os.path.join(out_dir, name, "run")
    run_replay(replay, bag, building, told, prefix)
    r = evaluate_outputs(prefix)
    r.update({"bag": os.path.relpath(bag, REPO), "building": os.path.relpath(building, REPO),
              "storey": storey, "localizer_storey": told, "note": note})
    graph = agraph_json(building)
    with open(graph) as f:
        storeys = json.load(f).get("storeys", [])
    est, odom = r["_est"], r["_odom"]
    if storeys:  # a run never localized still walked its storeys: "never" on each
        truth = r["_truth"]
        est_t, est_xyz = (est.timestamps, est.positions_xyz) if est is not None else ([], [])
        r["storeys"] = per_storey(storeys, truth.timestamps, truth.positions_xyz, est_t, est_xyz,
                                  odom.timestamps, odom.positions_xyz)
    trajectory_plot(name, r["_truth"], r["_series"], graph, storey,
                    os.path.join(out_dir, name, "trajectory.png"))
    error_plot(name, r["_t0"], r["_series"], os.path.join(out_dir, name, "error.png"))
    return public(r)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenarios", nargs="*",
                        help="scenario YAMLs (default: bags/D*, R*, H*, S*, M*, G*, E*, P*, A*)")
    parser.add_argument("--out", default=os.path.join(REPO, ".ws", "evaluate"))
    parser.add_argument("--replay",
                        default=os.path.join(REPO, ".ws", "devel", "lib", "is_graphs",
                                             "replay_pipeline"))
    args = parser.parse_args()
    from evaluation_report import write_reports

    yamls = args.scenarios or sorted(
        y for pattern in ("D*.yaml", "R*.yaml", "H*.yaml", "S*.yaml", "M*.yaml", "G*.yaml", "E*.yaml",
                        "P*.yaml", "A*.yaml", "L*.yaml")
        for y in glob.glob(os.path.join(REPO, "bags", pattern)) if not y.endswith("_short.yaml"))
    if not os.access(args.replay, os.X_OK):
        print(f"evaluate: error: {args.replay} not built (make build)", file=sys.stderr)
        return 2
    found, missing = find_bags(yamls)
    if missing:
        print(f"evaluate: bags missing (make bags makes them): {', '.join(missing)}")
    results = {}
    for name, yaml_path, bag, note in found:
        print(f"evaluate: {name}: replaying {os.path.relpath(bag, REPO)}"
              + (f" ({note})" if note else ""), flush=True)
        try:
            results[name] = evaluate_scenario(name, yaml_path, bag, note, args.replay, args.out)
        except EvaluationError as e:
            print(f"evaluate: error: {name}: {e}", file=sys.stderr)
            return 2
    if not results:
        print("evaluate: error: no scenario bag to evaluate (make bags)", file=sys.stderr)
        return 1
    md = write_reports(results, missing, args.out)
    print(open(md).read())
    return 0


if __name__ == "__main__":
    sys.exit(main())
