"""config/is_graphs.rviz loads in a real rviz under Xvfb and draws the A-Graph and the robot:
a screenshot of the 3-D view that is not empty. Runs roslaunch with a master of its own."""
import colorsys
import os
import shutil
import signal
import socket
import subprocess
import time

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
OUT_DIR = os.environ.get("IS_GRAPHS_TEST_TMP_DIR", "/tmp/is_graphs_test")
for tool in ("Xvfb", "import", "roslaunch", "rviz"):
    if shutil.which(tool) is None:
        pytest.skip(f"{tool} not installed (make setup installs it)", allow_module_level=True)
Image = pytest.importorskip("PIL.Image")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def free_display():
    for n in range(90, 200):
        if not os.path.exists(f"/tmp/.X11-unix/X{n}") and not os.path.exists(f"/tmp/.X{n}-lock"):
            return f":{n}"
    pytest.fail("no free X display number")


@pytest.fixture(scope="module")
def screenshot():
    os.makedirs(OUT_DIR, exist_ok=True)
    display, port = free_display(), free_port()
    xvfb = subprocess.Popen(["Xvfb", display, "-screen", "0", "1280x800x24", "-nolisten", "tcp"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    env = dict(os.environ, DISPLAY=display, ROS_MASTER_URI=f"http://localhost:{port}")
    log = open(os.path.join(OUT_DIR, "rviz_check.log"), "w")
    launch = subprocess.Popen(["roslaunch", "-p", str(port), "is_graphs", "rviz_check.launch"],
                              env=env, stdout=log, stderr=subprocess.STDOUT,
                              start_new_session=True)
    png = os.path.join(OUT_DIR, "rviz_screenshot.png")
    try:
        time.sleep(25)  # rviz starts, the A-Graph is converted (cached) and drawn
        alive = launch.poll() is None
        subprocess.run(["import", "-display", display, "-window", "root", png], check=True,
                       timeout=30)
        yield png, alive
    finally:
        if launch.poll() is None:
            os.killpg(launch.pid, signal.SIGINT)
            try:
                launch.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(launch.pid, signal.SIGKILL)
        xvfb.terminate()
        xvfb.wait(timeout=10)
        log.close()


def test_rviz_stays_up_with_the_config(screenshot):
    _, alive = screenshot
    assert alive, f"rviz or agraph_node exited; see {OUT_DIR}/rviz_check.log"


def test_the_3d_view_shows_the_a_graph_and_the_robot(screenshot):
    png, _ = screenshot
    image = Image.open(png).convert("RGB")
    width, height = image.size
    view = image.crop((int(width * 0.3), 70, width - 10, height - 40))  # right of the panel
    pixels = list(view.get_flattened_data()) if hasattr(view, "get_flattened_data") else list(view.getdata())
    background = sum(1 for p in pixels if abs(p[0] - 48) < 6 and abs(p[1] - 48) < 6
                     and abs(p[2] - 48) < 6)
    drawn = 1.0 - background / len(pixels)
    surfaces = sum(1 for r, g, b in pixels if b > 150 and b > r + 60)       # wall-surfaces
    # The yellow body, lit from the camera's side: hue 40-56 deg, saturated, not dark.
    hsv = [colorsys.rgb_to_hsv(r / 255, g / 255, b / 255) for r, g, b in pixels]
    robot = sum(1 for h, s, v in hsv if 40 <= h * 360 <= 56 and s > 0.6 and v > 0.45)
    assert drawn > 0.05, f"the 3-D view is empty ({drawn:.1%} drawn): {png}"
    assert surfaces > 2000, f"no A-Graph wall-surfaces drawn ({surfaces} px): {png}"
    assert robot > 20, f"no robot model drawn ({robot} px): {png}"
