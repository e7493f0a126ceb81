"""scripts/evaluate_run.py on run bags written here with known errors: the numbers it prints
must be the errors put in (evo computes the APE; nothing is aligned)."""
import json
import math
import os
import subprocess
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
SCRIPT = os.path.join(REPO, "scripts", "evaluate_run.py")

rosbag = pytest.importorskip("rosbag", reason="ROS 1 Python (python3-rosbag) not installed")
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped  # noqa: E402
import rospy  # noqa: E402


def quat_z(yaw):
    return math.cos(yaw / 2.0), math.sin(yaw / 2.0)


def write_run(path, offset_xy=(0.0, 0.0), yaw_error_deg=0.0, localize_at=5.0, localized=True,
              prefix="/"):
    """Ground truth: a 20 s walk along x at 0.5 m/s, 50 Hz, turning slowly; pose_bim from
    `localize_at` on, displaced by offset_xy and rotated by yaw_error_deg."""
    with rosbag.Bag(path, "w") as bag:
        for i in range(0, 1001):
            t = 1000.0 + i * 0.02
            yaw = 0.02 * (t - 1000.0)
            gt = PoseStamped()
            gt.header.stamp = rospy.Time.from_sec(t)
            gt.header.frame_id = "bim"
            gt.pose.position.x = 0.5 * (t - 1000.0)
            gt.pose.position.y = 2.0
            gt.pose.position.z = 0.525
            gt.pose.orientation.w, gt.pose.orientation.z = quat_z(yaw)
            bag.write(prefix + "ground_truth/pose", gt, gt.header.stamp)
            if localized and t - 1000.0 >= localize_at - 1e-9 and i % 5 == 0:
                est = PoseWithCovarianceStamped()
                est.header = gt.header
                est.pose.pose.position.x = gt.pose.position.x + offset_xy[0]
                est.pose.pose.position.y = gt.pose.position.y + offset_xy[1]
                est.pose.pose.position.z = gt.pose.position.z
                w, z = quat_z(yaw + math.radians(yaw_error_deg))
                est.pose.pose.orientation.w, est.pose.pose.orientation.z = w, z
                bag.write(prefix + "pose_bim", est, est.header.stamp)


def run(tmp_path, bag, *extra):
    out = tmp_path / "numbers.json"
    proc = subprocess.run([sys.executable, SCRIPT, str(bag), "--json", str(out), *extra],
                          capture_output=True, text=True, timeout=120)
    numbers = json.loads(out.read_text()) if out.exists() else None
    return proc, numbers


def test_reports_the_offset_put_in(tmp_path):
    bag = tmp_path / "run.bag"
    write_run(str(bag), offset_xy=(0.03, -0.04), yaw_error_deg=0.5, localize_at=5.0)
    proc, n = run(tmp_path, bag)
    assert proc.returncode == 0, proc.stderr
    assert n["localized"]
    assert n["time_to_localize_s"] == pytest.approx(5.0, abs=0.02)
    assert n["distance_to_localize_m"] == pytest.approx(2.5, abs=0.02)
    assert n["ape_xy_rmse_m"] == pytest.approx(0.05, abs=1e-4)
    assert n["ape_rmse_m"] == pytest.approx(0.05, abs=1e-4)
    assert n["yaw_max_deg"] == pytest.approx(0.5, abs=1e-3)
    assert n["poses_evaluated"] == pytest.approx(151, abs=1)
    assert "localized after 5.0 s" in proc.stdout
    # make demo reports the height apart (issue 24): here the pose is at the right height.
    assert n["ape_z_rmse_m"] == pytest.approx(0.0, abs=1e-6)
    assert "z RMSE 0.000 m, max 0.000 m" in proc.stdout


def test_relative_topic_names_as_rosbag_record_writes_them(tmp_path):
    bag = tmp_path / "run.bag"
    write_run(str(bag), offset_xy=(0.0, 0.02), prefix="")
    proc, n = run(tmp_path, bag)
    assert proc.returncode == 0, proc.stderr
    assert n["ape_xy_rmse_m"] == pytest.approx(0.02, abs=1e-4)


def test_never_localized_exits_1_and_says_so(tmp_path):
    bag = tmp_path / "run.bag"
    write_run(str(bag), localized=False)
    proc, n = run(tmp_path, bag)
    assert proc.returncode == 1
    assert "NOT LOCALIZED" in proc.stdout
    assert n["localized"] is False


def test_plot_is_written(tmp_path):
    bag = tmp_path / "run.bag"
    write_run(str(bag), offset_xy=(0.1, 0.0))
    graph = {"building": "test", "storeys": [{"id": 0, "name": "G"}],
             "wall_surfaces": [{"storey": 0, "start": [0, 0], "end": [10, 0]},
                               {"storey": 0, "start": [10, 4], "end": [0, 4]}],
             "rooms": [{"storey": 0, "name": "R", "center": [5, 2, 1.5]}]}
    agraph = tmp_path / "b.agraph.json"
    agraph.write_text(json.dumps(graph))
    png = tmp_path / "plot.png"
    proc, _ = run(tmp_path, bag, "--agraph", str(agraph), "--plot", str(png))
    assert proc.returncode == 0, proc.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert png.stat().st_size > 10_000


def test_a_bag_without_ground_truth_is_a_clear_error(tmp_path):
    bag = tmp_path / "empty.bag"
    with rosbag.Bag(str(bag), "w"):
        pass
    proc, _ = run(tmp_path, bag)
    assert proc.returncode == 2
    assert "no ground_truth/pose" in proc.stderr
