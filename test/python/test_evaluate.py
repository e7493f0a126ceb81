"""The pieces of `make evaluate` (scripts/evaluate.py, evaluation_common.py, evaluation_report.py)
on inputs with known answers: the start-pose placement of a baseline, the APE without
alignment, one dataset's numbers from replay_pipeline-like files, the bag discovery with its
fallback, and the report. (The wrong-match and map-cloud measures are C++: test_core.)"""
import json
import math
import os
import sys

import numpy as np
import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
sys.path.insert(0, os.path.join(REPO, "scripts"))
evo_trajectory = pytest.importorskip("evo.core.trajectory", reason="evo not installed (make setup)")

import evaluate  # noqa: E402
import evaluation_common  # noqa: E402
import evaluation_report  # noqa: E402


def se2(x, y, yaw, z=0.0):
    m = np.eye(4)
    m[:2, :2] = [[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]]
    m[:3, 3] = [x, y, z]
    return m


def walk(stamps):
    """Ground truth: along x at 0.5 m/s, turning 0.02 rad/s, from (2, 1) in the BIM frame."""
    return [se2(2.0 + 0.5 * t, 1.0 + 0.01 * t * t, 0.02 * t, 0.5) for t in stamps]


def traj(stamps, poses):
    return evo_trajectory.PoseTrajectory3D(poses_se3=poses, timestamps=np.asarray(stamps))


def write_tum(path, stamps, poses):
    if len(stamps):
        traj(stamps, poses)  # validates
    with open(path, "w") as f:
        for t, p in zip(stamps, poses):
            yaw = math.atan2(p[1, 0], p[0, 0])
            f.write(f"{t:.6f} {p[0, 3]:.6f} {p[1, 3]:.6f} {p[2, 3]:.6f} 0 0 "
                    f"{math.sin(yaw / 2):.9f} {math.cos(yaw / 2):.9f}\n")


def test_start_pose_placement_recovers_the_frame():
    stamps = np.arange(0.0, 20.0, 0.02)
    truth = traj(stamps, walk(stamps))
    bim_T_odom = se2(-3.0, 7.0, 1.2)
    odom_poses = [np.linalg.inv(bim_T_odom) @ p for p in walk(stamps)]
    # The odometry drifts: from t = 10 s on, 0.2 m off along its own x.
    for i, t in enumerate(stamps):
        if t >= 10.0:
            odom_poses[i] = odom_poses[i].copy()
            odom_poses[i][0, 3] += 0.2
    placed, transform = evaluation_common.place_with_start_pose(traj(stamps[::5], odom_poses[::5]),
                                                                truth)
    np.testing.assert_allclose(transform, bim_T_odom, atol=1e-9)
    numbers = evaluation_common.ape(truth, placed)
    assert numbers["ape_xy_max_m"] == pytest.approx(0.2, abs=1e-9)
    assert numbers["ape_xy_rmse_m"] == pytest.approx(0.2 * math.sqrt(0.5), abs=0.01)
    assert numbers["yaw_max_deg"] == pytest.approx(0.0, abs=1e-6)


def test_ape_is_not_aligned():
    stamps = np.arange(0.0, 20.0, 0.02)
    truth = traj(stamps, walk(stamps))
    est = traj(stamps[250::5], [se2(0.03, -0.04, 0.0) @ p @ se2(0, 0, math.radians(0.5))
                                for p in walk(stamps[250::5])])
    numbers = evaluation_common.ape(truth, est)
    assert numbers["poses_evaluated"] == len(stamps[250::5])
    assert numbers["ape_xy_rmse_m"] == pytest.approx(0.05, abs=1e-9)
    assert numbers["ape_xy_max_m"] == pytest.approx(0.05, abs=1e-9)
    assert numbers["ape_z_rmse_m"] == pytest.approx(0.0, abs=1e-9)
    assert numbers["yaw_rmse_deg"] == pytest.approx(0.5, abs=1e-6)


def test_ape_reports_the_height_apart():
    # The pose 0.25 m too high for the second half (a wrong storey elevation, a floor missing
    # from the BIM): x-y untouched, z RMSE sqrt(1/2) x 0.25, max 0.25.
    stamps = np.arange(0.0, 20.0, 0.02)
    truth = traj(stamps, walk(stamps))
    poses = []
    for t, p in zip(stamps, walk(stamps)):
        p = p.copy()
        if t >= 10.0:
            p[2, 3] += 0.25
        poses.append(p)
    numbers = evaluation_common.ape(truth, traj(stamps, poses))
    assert numbers["ape_xy_rmse_m"] == pytest.approx(0.0, abs=1e-9)
    assert numbers["ape_z_max_m"] == pytest.approx(0.25, abs=1e-9)
    assert numbers["ape_z_rmse_m"] == pytest.approx(0.25 * math.sqrt(0.5), abs=0.01)


def fake_replay(prefix, localized=True):
    """What replay_pipeline --out-prefix writes, for a 20 s walk: odometry in a frame turned by
    90 deg, the S-Graph's keyframes exact, the BIM pose 4 cm off from 5 s on."""
    stamps = np.arange(100.0, 120.0, 0.02)
    bim_T_odom = se2(1.0, -1.0, math.pi / 2)
    write_tum(prefix + ".truth.tum", stamps, walk(stamps - 100.0))
    write_tum(prefix + ".odom.tum", stamps, [np.linalg.inv(bim_T_odom) @ p
                                             for p in walk(stamps - 100.0)])
    write_tum(prefix + ".sgraph.tum", stamps[::40], [np.linalg.inv(bim_T_odom) @ p
                                                    for p in walk(stamps[::40] - 100.0)])
    # Online S-Graph: 3 cm off along its map's x (the BIM's y: turned by 90 deg) throughout.
    write_tum(prefix + ".sgraph_online.tum", stamps, [se2(0.03, 0.0, 0.0) @ np.linalg.inv(
        bim_T_odom) @ p for p in walk(stamps - 100.0)])
    est = stamps[250:] if localized else stamps[:0]
    write_tum(prefix + ".pose_bim.tum", est, [se2(0.0, 0.04, 0.0) @ p for p in walk(est - 100.0)])
    run = {"first_stamp": 100.0, "bag_seconds": 20.0, "walked_m": 10.0, "keyframes": 13,
           "real_time_factor": 20.0, "wall_seconds": 1.0, "peak_rss_mib": 70.0,
           "localized_at_end": localized, "seconds_to_localize": 5.0 if localized else -1.0,
           "distance_to_localize": 2.5 if localized else -1.0,
           "unique_matches": [{"t": 4.0, "wrong": False}, {"t": 4.8, "wrong": True}]
           if localized else [],
           "wrong_matches": 1 if localized else 0,
           "map_cloud_error": {"rmse_m": 0.02, "median_m": 0.01, "used_share": 0.6,
                               "points": 1000} if localized else None}
    with open(prefix + ".json", "w") as f:
        json.dump(run, f)


def test_one_dataset_from_the_replay_files(tmp_path):
    prefix = str(tmp_path / "run")
    fake_replay(prefix)
    r = evaluate.evaluate_outputs(prefix)
    assert r["localized"] and r["wrong_matches"] == 1 and r["unique_matches"] == 2
    assert r["first_unique_s"] == pytest.approx(4.0)
    # Walked by odometry in 4 s: x 2.0 m, y 0.16 m, nearly straight.
    assert r["first_unique_m"] == pytest.approx(math.hypot(2.0, 0.16), abs=0.01)
    assert r["isgraphs"]["ape_xy_rmse_m"] == pytest.approx(0.04, abs=1e-6)
    assert r["isgraphs"]["poses_evaluated"] == 750
    assert r["odometry"]["ape_xy_max_m"] == pytest.approx(0.0, abs=1e-5)
    assert r["sgraph"]["ape_xy_max_m"] == pytest.approx(0.0, abs=1e-5)
    assert r["odometry_after_localization"]["poses_evaluated"] == 750
    # Placed by its own (offset) start pose, the online S-Graph's constant offset cancels.
    assert r["sgraph_online"]["ape_xy_max_m"] == pytest.approx(0.0, abs=1e-5)

    fake_replay(prefix, localized=False)
    r = evaluate.evaluate_outputs(prefix)
    assert not r["localized"] and "isgraphs" not in r and "first_unique_s" not in r
    assert "odometry" in r and "sgraph" in r


def test_bags_found_with_the_short_fallback(tmp_path):
    for name in ("D3_office", "D4_site", "R1_drift", "R2_drops"):
        (tmp_path / f"{name}.yaml").write_text("building: bim/office.ifc\n")
    (tmp_path / "D3_office.bag").write_text("")
    (tmp_path / "R1_drift_short.bag").write_text("")
    found, missing = evaluate.find_bags(sorted(str(p) for p in tmp_path.glob("*.yaml")))
    assert [(f[0], os.path.basename(f[2]), bool(f[3])) for f in found] == [
        ("D3_office", "D3_office.bag", False), ("R1_drift", "R1_drift_short.bag", True)]
    assert missing == ["D4_site", "R2_drops"]


def test_localizer_storey(tmp_path):
    s = tmp_path / "M.yaml"
    s.write_text("building: bim/office.ifc\nstorey: '1.OG'\nlocalizer_storey: ''\n")
    assert evaluate.read_scenario(str(s))[1:] == ("1.OG", "")
    s.write_text("building: bim/office.ifc\nstorey: '1.OG'\n")
    assert evaluate.read_scenario(str(s))[1:] == ("1.OG", "1.OG")


def test_bad_scenario_is_named(tmp_path):
    bad = tmp_path / "X.yaml"
    bad.write_text("storey: 0\n")
    with pytest.raises(evaluate.EvaluationError, match="no 'building:'"):
        evaluate.read_scenario(str(bad))
    bad.write_text("building: [unclosed\n")
    with pytest.raises(evaluate.EvaluationError, match="cannot read"):
        evaluate.read_scenario(str(bad))


def test_report_tables(tmp_path):
    prefix = str(tmp_path / "run")
    fake_replay(prefix)
    ok = evaluate.public(evaluate.evaluate_outputs(prefix))
    fake_replay(prefix, localized=False)
    lost = evaluate.public(evaluate.evaluate_outputs(prefix))
    lost["note"] = "full bag absent: its _short bag used"
    md = evaluation_report.write_reports({"D5": ok, "R1": lost}, ["D2"], str(tmp_path))
    text = open(md).read()
    assert "| D5 | 0.040 m, 0.00° | 0.000 m, 0.00° | 0.000 m, 0.00° | 0.000 m, 0.00° |" in text
    assert "| R1 | not localized |" in text
    assert "| D5 | yes | 4.0 | 2.0 | 5.0 s, 2.5 m | 2 / 1 | 0.040 / 0.040 |" in text
    assert "| R1 | **no** | – | – |" in text
    assert "R1: full bag absent" in text and "D2: bag missing" in text
    saved = json.load(open(tmp_path / "results.json"))
    assert saved["missing_bags"] == ["D2"] and saved["datasets"]["D5"]["wrong_matches"] == 1


def test_per_storey_time_to_localize(tmp_path):
    """Issue 22: up a stair from a storey localized at 5 s to the next (3 m up) at 20 s, where the
    pose follows at once; a third storey never reached is not listed."""
    storeys = [{"name": "EG", "elevation": 0.0}, {"name": "1.OG", "elevation": 3.0},
               {"name": "2.OG", "elevation": 6.0}]
    assert evaluate.storey_at(storeys, 0.4) == 0 and evaluate.storey_at(storeys, 2.97) == 1
    assert evaluate.storey_at(storeys, -1.0) == -1
    t = np.arange(0.0, 30.0, 1.0)
    z = np.where(t < 15, 0.5, np.minimum(0.5 + (t - 15) * 0.6, 3.5))  # climbs from 15 s to 20 s
    truth = np.stack([t, np.zeros_like(t), z], axis=1)  # walks 1 m/s along x
    est_t = t[t >= 5]
    est = truth[t >= 5].copy()
    est[:, 0] += 0.1
    rows = evaluate.per_storey(storeys, t, truth, est_t, est, t, truth[:, :2])
    assert [r["storey"] for r in rows] == ["EG", "1.OG"]
    assert rows[0]["arrived_s"] == 0.0 and rows[0]["localized_after_s"] == 5.0
    assert rows[0]["localized_after_m"] == pytest.approx(5.0)
    assert rows[1]["arrived_s"] == 20.0  # 2.9 m up at 19 s is still below the floor
    assert rows[1]["localized_after_s"] == 0.0 and rows[1]["localized_after_m"] == 0.0
    # A pose on the wrong floor (3 m off in z) is no localization there.
    est[t[t >= 5] >= 20, 2] -= 3.0
    rows = evaluate.per_storey(storeys, t, truth, est_t, est, t, truth[:, :2])
    assert rows[1]["localized_after_s"] is None and rows[1]["localized_after_m"] is None
    md = evaluation_report.storeys({"M9": {"localizer_storey": "", "storeys": rows},
                                    "D5": {"localizer_storey": "0", "storeys": rows}})
    assert "| M9 | EG | 0.0 | 5.0 | 5.0 |" in md and "| M9 | 1.OG | 20.0 | never | – |" in md
    assert not any("D5" in line for line in md)
    # A run never localized (M6, the duplex: AMBIGUOUS throughout) still lists the storeys walked.
    rows = evaluate.per_storey(storeys, t, truth, [], [], t, truth[:, :2])
    assert [(r["storey"], r["localized_after_s"]) for r in rows] == [("EG", None), ("1.OG", None)]
