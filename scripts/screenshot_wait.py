#!/usr/bin/env python3
"""Waits, for scripts/screenshot.sh, until the pipeline has localized the robot and the bag has
played SHOT_AT seconds (sim time since its first /clock), then exits 0. Exits non-zero with a
message naming what went wrong: the launch ended first (a node died, the bag ended), the robot
was not localized by then, or the wall-clock timeout passed.

  screenshot_wait.py --shot-at 140 --launch-pid PID [--timeout 600]
"""
import argparse
import os
import sys
import time

import rospy
from rosgraph_msgs.msg import Clock

from is_graphs.msg import LocalizationStatus


def alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shot-at", type=float, required=True, help="bag seconds to wait for")
    parser.add_argument("--launch-pid", type=int, required=True)
    parser.add_argument("--timeout", type=float, default=600.0, help="wall-clock seconds")
    args = parser.parse_args(rospy.myargv()[1:])

    state = {"first": None, "now": None, "status": None}

    def on_clock(msg):
        t = msg.clock.to_sec()
        if state["first"] is None:
            state["first"] = t
        state["now"] = t

    def on_status(msg):
        state["status"] = msg

    rospy.init_node("screenshot_wait", anonymous=True, disable_signals=True)
    rospy.Subscriber("/clock", Clock, on_clock, queue_size=10)
    rospy.Subscriber("localization_status", LocalizationStatus, on_status, queue_size=10)
    start = time.monotonic()
    while True:
        time.sleep(0.5)
        status = state["status"]
        localized = status is not None and status.state == LocalizationStatus.LOCALIZED
        played = None if state["first"] is None else state["now"] - state["first"]
        if played is not None and played >= args.shot_at:
            if not localized:
                what = "no localization_status" if status is None else status.message or "-"
                sys.exit(f"screenshot: error: not localized after {played:.0f} s of the bag "
                         f"(localization_status: {what})")
            print(f"screenshot: localized after {status.seconds_to_localize:.1f} s, "
                  f"{status.distance_to_localize:.1f} m; {played:.0f} s of the bag played")
            return
        if not alive(args.launch_pid):
            sys.exit("screenshot: error: the launch ended before the shot "
                     f"({played if played is not None else 0:.0f} s of the bag played)")
        if time.monotonic() - start > args.timeout:
            sys.exit(f"screenshot: error: timed out after {args.timeout:.0f} s "
                     f"({played if played is not None else 0:.0f} s of the bag played)")


if __name__ == "__main__":
    main()
