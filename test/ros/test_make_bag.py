"""End-to-end checks of make_bag: the bag's topics, frames and tf tree, its point layout, that two
runs give byte-identical bags, the robustness options (scan dropouts, kidnap) as seen in the bag,
and that bad input fails cleanly (exit 2, the field named, no bag left behind). Runs with the
system Python (rosbag): /usr/bin/python3 -m pytest test/ros.

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


OUSTER = np.dtype({"names": ["x", "y", "z", "intensity", "t", "reflectivity", "ring", "ambient",
                             "range"],
                   "formats": ["<f4", "<f4", "<f4", "<f4", "<u4", "<u2", "<u2", "<u2", "<u4"],
                   "offsets": [0, 4, 8, 16, 20, 24, 26, 28, 32], "itemsize": 48})
HESAI = np.dtype({"names": ["x", "y", "z", "intensity", "timestamp", "ring"],
                  "formats": ["<f4", "<f4", "<f4", "<f4", "<f8", "<u2"],
                  "offsets": [0, 4, 8, 16, 24, 32], "itemsize": 48})


def model_bag(tmp_path, model):
    scenario = tmp_path / f"{model}.yaml"
    scenario.write_text("building: bim/office.ifc\nseed: 3\nduration: 1\n"
                        "trajectory: {rooms: [Corridor, \"102\"]}\n"
                        f"sensor: {{model: {model}}}\n")
    out = str(tmp_path / f"{model}.bag")
    r = make_bag(str(scenario), out, "--root", ROOT)
    assert r.returncode == 0, r.stderr
    return out


def static_edges(bag):
    return {(t.header.frame_id, t.child_frame_id)
            for _, m, _ in bag.read_messages(topics=["tf_static"]) for t in m.transforms}


def test_os1_64_bag_has_the_ouster_ros_layout(tmp_path):
    out = model_bag(tmp_path, "os1_64")
    with rosbag.Bag(out) as bag:
        info = bag.get_type_and_topic_info().topics
        assert "velodyne_points" not in info and info["ouster/points"].message_count == 10
        assert static_edges(bag) == {("base_link", "os_sensor"), ("os_sensor", "os_lidar")}
        for _, msg, t in bag.read_messages(topics=["ouster/points"]):
            assert [(f.name, f.offset, f.datatype) for f in msg.fields] == [
                ("x", 0, 7), ("y", 4, 7), ("z", 8, 7), ("intensity", 16, 7), ("t", 20, 6),
                ("reflectivity", 24, 4), ("ring", 26, 4), ("ambient", 28, 4), ("range", 32, 6)]
            assert (msg.height, msg.width, msg.point_step) == (64, 1024, 48)
            assert msg.header.frame_id == "os_lidar" and not msg.is_dense
            assert (t - msg.header.stamp).to_sec() == pytest.approx(0.1, abs=1e-6)
            pts = np.frombuffer(msg.data, dtype=OUSTER).reshape(64, 1024)
            # Row = ring; every column's t is its measurement time (ns after the stamp).
            assert np.all(pts["ring"] == np.arange(64)[:, None])
            assert np.abs(pts["t"] - np.arange(1024) * 1e8 / 1024).max() <= 0.5 + 1e-6
            # No return: NaN x y z and range 0; a return: range = |xyz| in mm.
            hit = np.isfinite(pts["x"])
            assert 0.5 * hit.size < hit.sum() < hit.size  # the body hides some beams
            assert np.all(pts["range"][~hit] == 0)
            r = np.sqrt(pts["x"] ** 2 + pts["y"] ** 2 + pts["z"] ** 2)[hit]
            assert np.abs(pts["range"][hit] - 1000 * r).max() <= 1.0
            assert r.min() >= 0.5


def test_hesai_xt32_bag_has_the_hesai_driver_layout(tmp_path):
    out = model_bag(tmp_path, "hesai_xt32")
    with rosbag.Bag(out) as bag:
        info = bag.get_type_and_topic_info().topics
        assert "velodyne_points" not in info and info["hesai/pandar"].message_count == 10
        assert static_edges(bag) == {("base_link", "hesai_lidar")}
        for _, msg, t in bag.read_messages(topics=["hesai/pandar"]):
            assert [(f.name, f.offset, f.datatype) for f in msg.fields] == [
                ("x", 0, 7), ("y", 4, 7), ("z", 8, 7), ("intensity", 16, 7),
                ("timestamp", 24, 8), ("ring", 32, 4)]
            assert msg.height == 1 and msg.point_step == 48 and msg.is_dense
            assert msg.header.frame_id == "hesai_lidar"
            pts = np.frombuffer(msg.data, dtype=HESAI)
            # Absolute times in firing order; the stamp is the first point's.
            assert pts["timestamp"][0] == pytest.approx(msg.header.stamp.to_sec(), abs=1e-9)
            assert np.all(np.diff(pts["timestamp"]) >= 0)
            assert pts["timestamp"][-1] - pts["timestamp"][0] < 0.1
            assert (t.to_sec() - pts["timestamp"][0]) == pytest.approx(0.1, abs=1e-3)
            assert pts["ring"].max() == 31
            assert set(np.unique(pts["intensity"])) <= set(range(256))


def test_unknown_lidar_model_is_named(tmp_path):
    scenario = tmp_path / "bad.yaml"
    scenario.write_text("building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\n"
                        "sensor: {model: vlp32}\n")
    r = make_bag(str(scenario), str(tmp_path / "bad.bag"), "--root", ROOT)
    assert r.returncode == 2
    assert "sensor.model: unknown model 'vlp32'" in r.stderr


ROBUSTNESS = """building: bim/office.ifc
seed: 3
duration: 6
trajectory: {rooms: [Corridor, "102"], speed: 1.0, pause: 0.2}
sensor: {dropouts: [[1.5, 2.5]]}
kidnap: {time: 4, rooms: [Meeting, Corridor]}
"""


def test_dropouts_and_kidnap_in_the_bag(tmp_path):
    scenario = tmp_path / "robust.yaml"
    scenario.write_text(ROBUSTNESS)
    out = str(tmp_path / "robust.bag")
    r = make_bag(str(scenario), out, "--root", ROOT)
    assert r.returncode == 0, r.stderr
    with rosbag.Bag(out) as bag:
        t0 = bag.get_start_time()
        scans = [t.to_sec() - t0 for _, _, t in bag.read_messages(topics=["velodyne_points"])]
        truth = [(t.to_sec() - t0, m.pose.position) for _, m, t in
                 bag.read_messages(topics=["ground_truth/pose"])]
        odom = [(t.to_sec() - t0, m.pose.pose.position) for _, m, t in
                bag.read_messages(topics=["odom"])]
    # Scans sweeping any of [1.5, 2.5) are missing: the last before is recorded at 1.5 s, the
    # first after at 2.6 s (sweep 2.5-2.6).
    assert len(scans) == 60 - 10
    assert not [t for t in scans if 1.5 + 1e-6 < t < 2.6 - 1e-6]
    assert [t for t in scans if 1.4 < t < 2.7] == pytest.approx([1.5, 2.6], abs=1e-6)
    # Odometry and ground truth go on at 50 Hz.
    assert len(odom) == len(truth) == 301
    assert np.diff([t for t, _ in odom]) == pytest.approx(0.02, abs=1e-6)

    def steps(poses):
        xy = np.array([(p.x, p.y) for _, p in poses])
        return np.linalg.norm(np.diff(xy, axis=0), axis=1)

    # At 4 s the ground truth jumps (carried to the meeting room); the odometry does not.
    jump = int(np.argmax(steps(truth)))
    assert truth[jump + 1][0] == pytest.approx(4.0, abs=1e-6)
    assert steps(truth)[jump] > 3.0
    assert steps(odom)[jump] == 0.0
    assert steps(odom).max() < 0.03  # 1 m/s at 50 Hz
    # Deterministic with both as well.
    again = str(tmp_path / "again.bag")
    assert make_bag(str(scenario), again, "--root", ROOT).returncode == 0
    with open(out, "rb") as a, open(again, "rb") as b:
        assert hashlib.sha256(a.read()).digest() == hashlib.sha256(b.read()).digest()


@pytest.mark.parametrize("yaml_text, field", [
    ("building: bim/no_such_building.ifc\ntrajectory: {rooms: [A]}\n", "building:"),
    ("building: bim/office.ifc\ntrajectory: {rooms: [Corridor, \"101\"], speed: -1}\n",
     "trajectory.speed"),
    ("building: bim/office.ifc\ntrajectory: {rooms: [Corridor, Lobby]}\n", "trajectory.rooms[1]"),
    ("building: bim/office.ifc\ntrajectory: {rooms: [Corridor\n", "invalid YAML"),
    ("building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\nsensor: {dropouts: [[3, 2]]}\n",
     "sensor.dropouts[0]"),
    ("building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\n"
     "kidnap: {time: 2, rooms: [Lobby]}\n", "kidnap.rooms[0]"),
    ("building: bim/tower.ifc\nstorey: Second floor\n"
     "trajectory: {rooms: [\"2.07\", \"0.03 @ Basement\"]}\n",
     "trajectory.rooms[1]: '0.03 @ Basement': unknown storey \"Basement\" (storeys: 0"),
    ("building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\nscene:\n  people:\n"
     "    - {type: person, waypoints: [[2.6, 9.5], [5.0, 2.5]]}\n",
     "bad.yaml:5: scene.people[0].waypoints: the walk from (2.60, 9.50) to (5.00, 2.50) is "
     "blocked at"),
])
def test_bad_input_fails_cleanly(tmp_path, yaml_text, field):
    scenario = tmp_path / "bad.yaml"
    scenario.write_text(yaml_text)
    out = tmp_path / "bad.bag"
    r = make_bag(str(scenario), str(out), "--root", ROOT)
    assert r.returncode == 2
    assert field in r.stderr
    assert not out.exists() and not (tmp_path / "bad.bag.tmp").exists()


# realpath: ROOT may be the build tree's symlink to the sources (.ws/src/is_graphs).
KIT_EDC = os.path.realpath(os.path.join(ROOT, "..", "shared", "bim", "KIT-EDC_with_SB.ifc"))


@pytest.mark.skipif(not os.path.exists(KIT_EDC), reason="no ../shared/bim/KIT-EDC_with_SB.ifc")
def test_a_route_across_storeys_without_stairs_is_named(tmp_path):
    # KIT-EDC's IFC has three storeys and no IfcStair: rooms on two of them cannot be joined.
    scenario = tmp_path / "kit.yaml"
    scenario.write_text(f"building: {KIT_EDC}\nstorey: EG\n"
                        "trajectory: {rooms: [\"45\", \"27 @ 1.OG\"]}\n")
    out = tmp_path / "kit.bag"
    r = make_bag(str(scenario), str(out), "--root", ROOT)
    assert r.returncode == 2
    assert "trajectory.rooms[1] ('27 @ 1.OG'): not reachable from '45'" in r.stderr
    assert "no walkable stair was found in the building's mesh" in r.stderr
    assert not out.exists()


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))
