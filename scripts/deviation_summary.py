#!/usr/bin/env python3
"""Prints the as-built summary (issue 21) of a run bag: the last message on `deviations`
(deviation_node, recorded by make demo). Exit 0 with a note when the bag has none.

  deviation_summary.py RUN.bag
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

STATUS = ["AS_PLANNED", "MOVED", "NOT_BUILT", "EXTRA", "NOT_SEEN"]


def as_dict(w):
    return {"wall_id": w.wall_id, "guid": w.guid, "name": w.name, "status": STATUS[w.status],
            "offset_m": w.offset, "angle_deg": math.degrees(w.angle), "sigma_m": w.sigma,
            "start": [w.start.x, w.start.y], "end": [w.end.x, w.end.y],
            "length_m": math.hypot(w.end.x - w.start.x, w.end.y - w.start.y),
            "rays_through": w.rays_through}


DOOR_STATUS = ["PRESENT", "CLOSED", "NOT_SEEN"]


def as_door(d):
    return {"doorway_id": d.doorway_id, "guid": d.guid, "name": d.name,
            "status": DOOR_STATUS[d.status], "position": [d.position.x, d.position.y],
            "blocked_views": d.blocked_views}


def main(argv):
    import rosbag  # Debian's ROS Python (the venv sees the system packages)
    from deviation_report import summary
    last = None
    with rosbag.Bag(argv[1]) as bag:
        for _, msg, _ in bag.read_messages(topics=["deviations", "/deviations"]):
            last = msg
    if last is None:
        print("demo: no deviations message in %s (not localized?)" % argv[1])
        return 0
    print("as built vs as planned (S-Graph revision %d):" % last.s_graph_revision)
    print(summary([as_dict(w) for w in last.walls],
                  [as_door(d) for d in getattr(last, "doorways", [])]))
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv))
