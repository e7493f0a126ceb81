"""End-to-end checks of make_bag: the bag's topics, frames and tf tree, its point layout, that two
runs give byte-identical bags, and that bad input fails cleanly (exit 2, the field named, no bag
left behind). Runs with the system Python (rosbag): /usr/bin/python3 -m pytest test/ros.

IS_GRAPHS_MAKE_BAG names the binary (default: the workspace in .ws/).
"""
import hashlib
import os
import subprocess
import sys

import numpy as np
import pytest

rosbag = pytest.importorskip("rosbag")

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MAKE_BAG = os.environ.get("IS_GRAPHS_MAKE_BAG",
                          os.path.join(ROOT, ".ws", "devel", "lib", "is_graphs", "make_bag"))
SCENARIO = os.path.join(ROOT, "bags", "D4_construction_site_short.yaml")
XYZIRT = np.dtype({"names": ["x", "y", "z", "intensity", "ring", "time"],
                   "formats": ["<f4", "<f4", "<f4", "<f4", "<u2", "<f4"],
                   "offsets": [0, 4, 8, 12, 16, 18], "itemsize": 22})

pytestmark = pytest.mark.skipif(not os.path.exists(MAKE_BAG), reason=f"{MAKE_BAG} not built")


def make_bag(scenario, out, *extra):
    return subprocess.run([MAKE_BAG, scenario, "-o", out, "--quiet", *extra],
                          capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module")
def bag_path(tmp_path_factory):
    out = str(tmp_path_factory.mktemp("bags") / "d4.bag")
    r = make_bag(SCENARIO, out, "--duration-scale", "0.2")  # 6 s
    assert r.returncode == 0, r.stderr
    return out


def test_topics_types_and_rates(bag_path):
    with rosbag.Bag(bag_path) as bag:
        info = bag.get_type_and_topic_info().topics
        duration = bag.get_end_time() - bag.get_start_time()
    assert info["velodyne_points"].msg_type == "sensor_msgs/PointCloud2"
    assert info["odom"].msg_type == "nav_msgs/Odometry"
    assert info["tf"].msg_type == "tf2_msgs/TFMessage"
    assert info["tf_static"].msg_type == "tf2_msgs/TFMessage"
    assert info["ground_truth/pose"].msg_type == "geometry_msgs/PoseStamped"
    assert duration == pytest.approx(6.0, abs=1e-6)
    assert info["velodyne_points"].message_count == 60
    assert info["odom"].message_count == info["ground_truth/pose"].message_count == 301
    assert info["tf_static"].message_count == 1


def test_tf_tree_is_complete(bag_path):
    edges = set()
    latched = None
    with rosbag.Bag(bag_path) as bag:
        for topic, msg, _, conn in bag.read_messages(topics=["tf", "tf_static"],
                                                     return_connection_header=True):
            for t in msg.transforms:
                edges.add((t.header.frame_id, t.child_frame_id, topic))
            if topic == "tf_static":
                latched = conn.get("latching")
                (t,) = msg.transforms
                assert (t.transform.translation.x, t.transform.translation.y,
                        t.transform.translation.z) == pytest.approx((0.1, 0.0, 0.1877))
        frames = {(m.header.frame_id, getattr(m, "child_frame_id", None))
                  for _, m, _ in bag.read_messages(topics=["odom", "ground_truth/pose",
                                                           "velodyne_points"])}
    assert edges == {("odom", "base_link", "tf"), ("base_link", "velodyne", "tf_static")}
    assert latched in ("1", b"1")
    assert frames == {("odom", "base_link"), ("bim", None), ("velodyne", None)}


def test_clouds_have_the_velodyne_layout(bag_path):
    with rosbag.Bag(bag_path) as bag:
        for i, (_, msg, t) in enumerate(bag.read_messages(topics=["velodyne_points"])):
            assert [(f.name, f.offset, f.datatype) for f in msg.fields] == [
                ("x", 0, 7), ("y", 4, 7), ("z", 8, 7), ("intensity", 12, 7), ("ring", 16, 4),
                ("time", 18, 7)]
            assert msg.point_step == 22 and msg.height == 1 and msg.is_dense
            pts = np.frombuffer(msg.data, dtype=XYZIRT)
            assert len(pts) > 10000
            assert pts["ring"].max() == 15 and pts["ring"].min() >= 0
            assert pts["time"].min() >= 0.0 and pts["time"].max() < 0.1
            assert np.all(np.diff(pts["time"]) >= 0)
            # Published when complete: bag time = stamp + one scan period.
            assert (t - msg.header.stamp).to_sec() == pytest.approx(0.1, abs=1e-6)
            r = np.sqrt(pts["x"] ** 2 + pts["y"] ** 2 + pts["z"] ** 2)
            assert r.min() >= 0.4 and r.max() <= 100.0
            if i >= 5:
                break


def test_two_runs_give_identical_bags(bag_path, tmp_path):
    again = str(tmp_path / "again.bag")
    assert make_bag(SCENARIO, again, "--duration-scale", "0.2").returncode == 0

    def digest(path):
        with open(path, "rb") as fh:
            return hashlib.sha256(fh.read()).hexdigest()

    assert digest(again) == digest(bag_path)


@pytest.mark.parametrize("yaml_text, field", [
    ("building: bim/no_such_building.ifc\ntrajectory: {rooms: [A]}\n", "building:"),
    ("building: bim/office.ifc\ntrajectory: {rooms: [Corridor, \"101\"], speed: -1}\n",
     "trajectory.speed"),
    ("building: bim/office.ifc\ntrajectory: {rooms: [Corridor, Lobby]}\n", "trajectory.rooms[1]"),
    ("building: bim/office.ifc\ntrajectory: {rooms: [Corridor\n", "invalid YAML"),
])
def test_bad_input_fails_cleanly(tmp_path, yaml_text, field):
    scenario = tmp_path / "bad.yaml"
    scenario.write_text(yaml_text)
    out = tmp_path / "bad.bag"
    r = make_bag(str(scenario), str(out), "--root", ROOT)
    assert r.returncode == 2
    assert field in r.stderr
    assert not out.exists() and not (tmp_path / "bad.bag.tmp").exists()


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))
