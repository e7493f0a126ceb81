#!/usr/bin/env python3
"""Evaluates one localization run: the BIM-frame pose (`pose_bim`) against ground truth
(`ground_truth/pose`), both recorded in RUN.bag by launch/localize.launch record:=RUN.bag.

Prints the time and distance walked until the first pose in the BIM (the first unique match),
the APE after localization computed by evo WITHOUT alignment (global localization: alignment
would hide the error), in x/y and 3-D (RMSE and max), the yaw error, and writes a plot of the
trajectories over the BIM plan coloured by error. Exit 1 when the run never localized.

  evaluate_run.py RUN.bag --agraph BUILDING.agraph.json [--storey S] [--plot OUT.png] [--json OUT.json]
"""
import argparse
import json
import math
import sys

import numpy as np

from evaluation_common import ape, draw_plan


def fail(message):
    print(f"evaluate_run: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_trajectories(run_bag):
    from evo.tools import file_interface
    from rosbags.rosbag1 import Reader

    with Reader(run_bag) as reader:
        topics = {c.topic for c in reader.connections}

        def present(name):  # rosbag record keeps relative names as given: with or without "/"
            for topic in ("/" + name, name):
                if topic in topics:
                    return topic
            return None

        gt_topic, est_topic = present("ground_truth/pose"), present("pose_bim")
        if gt_topic is None:
            fail(f"{run_bag}: no ground_truth/pose (the bag played had no ground truth)")
        gt = file_interface.read_bag_trajectory(reader, gt_topic)
        est = file_interface.read_bag_trajectory(reader, est_topic) if est_topic else None
    return gt, est


def evaluate(gt, est):
    result = {"localized": est is not None and est.num_poses > 0}
    t0 = gt.timestamps[0]
    steps = np.linalg.norm(np.diff(gt.positions_xyz[:, :2], axis=0), axis=1)
    walked = np.concatenate([[0.0], np.cumsum(steps)])
    result["duration_s"] = float(gt.timestamps[-1] - t0)
    result["distance_m"] = float(walked[-1])
    if not result["localized"]:
        return result
    t_loc = est.timestamps[0]
    result["time_to_localize_s"] = float(t_loc - t0)
    result["distance_to_localize_m"] = float(np.interp(t_loc, gt.timestamps, walked))
    numbers = ape(gt, est)
    _, err_xy, _, ref, est_sync = numbers.pop("_series")
    result.update(numbers)
    result["_plot"] = (ref, est_sync, err_xy)
    return result


def plot(result, gt, agraph_path, storey, out_png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(10, 8), dpi=110)
    graph = draw_plan(ax, agraph_path, storey)
    ax.plot(gt.positions_xyz[:, 0], gt.positions_xyz[:, 1], color="black", lw=1.0,
            label="ground truth")
    if result["localized"]:
        _, est, err = result["_plot"]
        sc = ax.scatter(est.positions_xyz[:, 0], est.positions_xyz[:, 1], c=err, s=4,
                        cmap="viridis", vmin=0.0, vmax=max(0.1, float(err.max())),
                        label="pose_bim")
        fig.colorbar(sc, ax=ax, label="x-y error [m]")
        ax.plot(*est.positions_xyz[0, :2], marker="*", ms=14, color="red", ls="none",
                label="first unique match")
        title = (f"localized after {result['time_to_localize_s']:.1f} s / "
                 f"{result['distance_to_localize_m']:.1f} m; APE x-y RMSE "
                 f"{result['ape_xy_rmse_m'] * 100:.1f} cm, max {result['ape_xy_max_m'] * 100:.1f} cm")
    else:
        title = "not localized"
    ax.set_title(f"{graph.get('building', '')}: {title}", fontsize=10)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    fig.savefig(out_png)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_bag")
    parser.add_argument("--agraph", help="the A-Graph file, for the plot")
    parser.add_argument("--storey", default="", help="storey to draw (name or id)")
    parser.add_argument("--plot", help="PNG to write")
    parser.add_argument("--json", help="write the numbers as JSON")
    args = parser.parse_args()
    gt, est = read_trajectories(args.run_bag)
    result = evaluate(gt, est)
    if args.plot and args.agraph:
        plot(result, gt, args.agraph, args.storey, args.plot)
    numbers = {k: v for k, v in result.items() if not k.startswith("_")}
    if args.json:
        with open(args.json, "w") as f:
            json.dump(numbers, f, indent=2, sort_keys=True)
    print(f"run: {numbers['duration_s']:.1f} s, {numbers['distance_m']:.1f} m walked")
    if not numbers["localized"]:
        print("NOT LOCALIZED: no pose in the BIM frame was published")
        return 1
    print(f"localized after {numbers['time_to_localize_s']:.1f} s and "
          f"{numbers['distance_to_localize_m']:.1f} m walked")
    print(f"APE (evo, no alignment, {numbers['poses_evaluated']} poses after localization): "
          f"x-y RMSE {numbers['ape_xy_rmse_m']:.3f} m, max {numbers['ape_xy_max_m']:.3f} m; "
          f"z RMSE {numbers['ape_z_rmse_m']:.3f} m, max {numbers['ape_z_max_m']:.3f} m; "
          f"3-D RMSE {numbers['ape_rmse_m']:.3f} m, max {numbers['ape_max_m']:.3f} m")
    print(f"yaw error: RMSE {numbers['yaw_rmse_deg']:.2f} deg, max {numbers['yaw_max_deg']:.2f} deg")
    if args.plot:
        print(f"plot: {args.plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
