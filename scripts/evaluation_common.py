"""Shared by scripts/evaluate_run.py (a live run's bag) and scripts/evaluate.py (`make evaluate`):
the APE without alignment (evo), the start-pose placement of a baseline trajectory in the BIM
frame, and the BIM plan drawn under a plot."""
import json

import numpy as np


def yaw_of(quaternions_wxyz):
    w, x, y, z = np.asarray(quaternions_wxyz).T
    return np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def ape(ref_full, est, max_diff=0.03):
    """APE of `est` against the ground truth `ref_full` (evo PoseTrajectory3D), NOT aligned: each
    estimate is paired with the truth of the same stamp (evo's association, within max_diff s).
    Returns the numbers (3-D RMSE/max by evo, x-y, z and yaw RMSE/max) and, under "_series", the
    stamps and per-pose errors (x-y [m], yaw [deg]) with the associated trajectories."""
    from evo.core import metrics, sync

    ref, est_sync = sync.associate_trajectories(ref_full, est, max_diff=max_diff)
    metric = metrics.APE(metrics.PoseRelation.translation_part)
    metric.process_data((ref, est_sync))
    stats = metric.get_all_statistics()
    err_xy = np.linalg.norm(ref.positions_xyz[:, :2] - est_sync.positions_xyz[:, :2], axis=1)
    err_z = np.abs(ref.positions_xyz[:, 2] - est_sync.positions_xyz[:, 2])
    dyaw = yaw_of(est_sync.orientations_quat_wxyz) - yaw_of(ref.orientations_quat_wxyz)
    dyaw = np.degrees(np.abs(np.arctan2(np.sin(dyaw), np.cos(dyaw))))
    return {
        "poses_evaluated": int(ref.num_poses),
        "ape_rmse_m": float(stats["rmse"]), "ape_max_m": float(stats["max"]),
        "ape_xy_rmse_m": float(np.sqrt(np.mean(err_xy ** 2))), "ape_xy_max_m": float(err_xy.max()),
        "ape_z_rmse_m": float(np.sqrt(np.mean(err_z ** 2))), "ape_z_max_m": float(err_z.max()),
        "yaw_rmse_deg": float(np.sqrt(np.mean(dyaw ** 2))), "yaw_max_deg": float(dyaw.max()),
        "_series": (est_sync.timestamps, err_xy, dyaw, ref, est_sync),
    }


def pose_at(traj, stamp):
    """The 4x4 pose of `traj` at `stamp`: linear interpolation of the position between the two
    samples around it, the orientation of the nearer one (the truth is sampled densely)."""
    t = traj.timestamps
    i = int(np.clip(np.searchsorted(t, stamp), 1, len(t) - 1))
    a = (stamp - t[i - 1]) / (t[i] - t[i - 1]) if t[i] > t[i - 1] else 0.0
    a = float(np.clip(a, 0.0, 1.0))
    pose = np.array(traj.poses_se3[i if a >= 0.5 else i - 1])
    pose[:3, 3] = (1 - a) * traj.positions_xyz[i - 1] + a * traj.positions_xyz[i]
    return pose


def place_with_start_pose(traj, truth):
    """A trajectory in its own frame (odom, map) put in the BIM frame by the true start pose:
    bim_T_frame = truth(t0) * traj(t0)^-1, applied to every pose (what a baseline that is told
    where it starts would report). Returns a new trajectory and the 4x4 transform."""
    import copy

    bim_T_frame = pose_at(truth, traj.timestamps[0]) @ np.linalg.inv(traj.poses_se3[0])
    placed = copy.deepcopy(traj)
    placed.transform(bim_T_frame)
    return placed, bim_T_frame


def draw_plan(ax, agraph_path, storey=""):
    """The storey's wall-surfaces and room names (A-Graph file) on `ax`; returns the graph."""
    with open(agraph_path) as f:
        graph = json.load(f)
    storeys = {str(s["id"]) for s in graph["storeys"]}
    if storey not in ("", None):
        storeys = {str(s["id"]) for s in graph["storeys"] if str(storey) in (s["name"], str(s["id"]))}
    for s in graph["wall_surfaces"]:
        if str(s["storey"]) in storeys:
            ax.plot([s["start"][0], s["end"][0]], [s["start"][1], s["end"][1]], color="0.45", lw=1.2)
    for r in graph["rooms"]:
        if str(r["storey"]) in storeys:
            ax.text(r["center"][0], r["center"][1], r["name"], fontsize=9, color="0.2",
                    ha="center", va="center", zorder=5,
                    bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.75})
    ax.set_aspect("equal")
    ax.set_xlabel("x [m] (bim)")
    ax.set_ylabel("y [m] (bim)")
    return graph
