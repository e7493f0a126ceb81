#!/usr/bin/python3
"""A stand-in node for test/python/test_roslaunch_checked.py, started by nodes.launch through
launch-prefix (roslaunch appends the real node's command and __name:= arguments: ignored).

  fake_node.py [--after SECONDS] [--exit CODE] [--fatal MESSAGE] [--once FILE]

Sleeps SECONDS, prints MESSAGE as a ROS FATAL line (stderr) and exits with CODE. --once FILE:
only the first run (FILE absent: it is created) does so; later runs (after a respawn) stay up."""
import argparse
import os
import sys
import time

parser = argparse.ArgumentParser()
parser.add_argument("--after", type=float, default=0.3)
parser.add_argument("--exit", type=int, default=0)
parser.add_argument("--fatal")
parser.add_argument("--once")
args, _ = parser.parse_known_args()
if args.once:
    if os.path.exists(args.once):
        time.sleep(3600)
    open(args.once, "w").close()
time.sleep(args.after)
if args.fatal:
    print(f"[FATAL] [{time.time():.6f}]: {args.fatal}", file=sys.stderr, flush=True)
sys.exit(args.exit)
