"""scripts/roslaunch_checked.py on real roslaunch runs (each with a master of its own on a free
port): test/data/roslaunch_checked/nodes.launch, whose flaky_node exits as told and whose
required player stands in for rosbag play; and launch/localize.launch on a building that is not
there (needs the built workspace .ws/devel, else skipped)."""
import os
import shutil
import socket
import subprocess
import time

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
CHECKED = os.path.join(REPO, "scripts", "roslaunch_checked.py")
NODES = os.path.join(REPO, "test", "data", "roslaunch_checked", "nodes.launch")
DEVEL = os.environ.get("IS_GRAPHS_DEVEL", os.path.join(REPO, ".ws", "devel"))
if shutil.which("roslaunch", path="/usr/bin") is None:
    pytest.skip("roslaunch not installed (make setup installs it)", allow_module_level=True)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def checked(tmp_path, *launch_args, options=(), source=None, timeout=60):
    """Runs the wrapper on roslaunch -p PORT LAUNCH_ARGS: (exit code, stderr, log, seconds)."""
    port = free_port()
    log = tmp_path / "roslaunch.log"
    env = dict(os.environ, PATH="/usr/bin:/bin:" + os.environ.get("PATH", ""),
               ROS_HOME=str(tmp_path / "ros_home"), ROS_MASTER_URI=f"http://localhost:{port}",
               ROS_HOSTNAME="localhost")
    env.pop("ROS_IP", None)
    env.pop("ROSCONSOLE_FORMAT", None)
    command = [CHECKED, "--log", str(log), *options, "--", "-p", str(port), *launch_args]
    if source:     # a workspace's setup.bash first (its packages on ROS_PACKAGE_PATH)
        command = ["bash", "-c", f'source "{source}" && exec "$@"', "bash", *command]
    start = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=timeout,
                          stdin=subprocess.DEVNULL)
    return (done.returncode, done.stderr, log.read_text() if log.exists() else "",
            time.monotonic() - start)


def test_a_node_that_exits_1_fails_the_run_naming_it(tmp_path):
    rc, err, log, _ = checked(tmp_path, NODES, "node_args:=--exit 1")
    assert rc == 1, err + log
    assert "flaky_node died with exit code 1 and was not restarted" in err
    assert "failed: flaky_node" in err
    assert "process has died" in log           # roslaunch's own output is kept
    assert "failed: flaky_node" in log         # and the verdict after it


def test_nodes_that_exit_0_and_the_player_ending_are_success(tmp_path):
    rc, err, log, _ = checked(tmp_path, NODES, "node_args:=--exit 0")
    assert rc == 0, err + log
    assert "REQUIRED process [player" in log   # the launch ended with the player, exit 0
    assert "error" not in err


def test_a_required_node_that_exits_non_zero_fails_the_run(tmp_path):
    rc, err, log, _ = checked(tmp_path, NODES, "required:=true", "node_args:=--exit 3",
                              "end_after:=30")
    assert rc == 1, err + log
    assert "flaky_node (required) died with exit code 3" in err


def test_a_node_that_came_back_is_a_warning(tmp_path):
    once = tmp_path / "once"
    rc, err, log, _ = checked(tmp_path, NODES, "respawn:=true",
                              f"node_args:=--exit 1 --once {once}", "end_after:=4")
    assert rc == 0, err + log
    assert "[flaky_node-" in log and "restarting process" in log
    assert "warning: flaky_node died and was restarted 1 time (exit codes 1)" in err


def test_a_fatal_in_a_respawning_node_stops_the_launch_and_fails(tmp_path):
    rc, err, log, seconds = checked(
        tmp_path, NODES, "respawn:=true", "end_after:=40",
        "node_args:=--exit 1 --fatal 'flaky_node: parameter ~x: not a number'")
    assert rc == 1, err + log
    assert "flaky_node logged FATAL: flaky_node: parameter ~x: not a number" in err
    assert "stopping the launch" in log
    assert seconds < 30, f"the launch ran {seconds:.0f} s: not stopped at the FATAL"


def test_too_many_restarts_fail_with_max_restarts(tmp_path):
    rc, err, log, seconds = checked(tmp_path, NODES, "respawn:=true", "end_after:=40",
                                    "node_args:=--exit 2", options=("--max-restarts", "2"))
    assert rc == 1, err + log
    assert "flaky_node restarted 3 times (more than --max-restarts 2)" in err
    assert seconds < 30


def test_a_launch_file_roslaunch_cannot_read_is_exit_3(tmp_path):
    rc, err, _, _ = checked(tmp_path, str(tmp_path / "no_such.launch"))
    assert rc == 3, err
    assert "roslaunch exited" in err


def test_usage_errors(tmp_path):
    assert subprocess.run([CHECKED], capture_output=True).returncode == 2
    assert subprocess.run([CHECKED, "--tee", "--", "x.launch"], capture_output=True).returncode == 2


def test_localize_on_a_missing_building_fails_naming_agraph_node(tmp_path):
    setup = os.path.join(DEVEL, "setup.bash")
    if not os.path.exists(os.path.join(DEVEL, "lib", "is_graphs", "agraph_node")):
        pytest.skip(f"no built agraph_node in {DEVEL} (make build)")
    rc, err, log, _ = checked(tmp_path, "is_graphs", "localize.launch",
                              f"bim:={tmp_path}/no_such_building.ifc", source=setup)
    assert rc == 1, err + log
    assert "agraph_node (required) died with exit code 1" in err
    assert "cannot load the BIM" in err
    assert "failed: agraph_node" in err
