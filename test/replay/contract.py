"""A scenario's contract, read from its test/ros/localize_<scenario>.test (the test node's
private parameters, the same the live rostest's test_localize reads), and the replay's outputs
it is checked against (replay_pipeline's PREFIX.json, PREFIX.pose_bim.tum, PREFIX.truth.tum).

The checks mirror test/ros/test_localize.cpp one for one; what only a live run has (the
LOCALIZED status's covariance, tf bim -> map) stays with the live rostests.
"""
import bisect
import json
import math
import os
import xml.etree.ElementTree as ET

import yaml

# A ground-truth step larger than this between two samples (50 Hz) is the kidnap's carry.
CARRY_JUMP = 1.0  # m
# A pose is paired with the ground truth of its stamp within this much.
PAIR_SLACK = 5e-3  # s
# Poses are stamped by odometry, LOST by the scan that found it, and a scan reaches the bag
# (and the replay) up to a cloud period after odometry of later stamps: this much slack, as
# test_localize.cpp's kStampSlack between its two clocks.
STAMP_SLACK = 0.25  # s

DEFAULTS = {
    "scenario": "?", "expect_localized": False, "max_seconds_to_localize": 0.0,
    "min_poses": 50, "max_ape_rmse": 0.05, "max_ape_max": 0.10, "max_yaw_rmse_deg": 1.0,
    "max_yaw_deg": 2.0, "max_wrong_distance": 0.5, "max_wrong_yaw_deg": 5.0,
    "max_ape_z_rmse": 0.05, "max_wrong_z": 1.0, "true_storey_id": -1, "storey_elevations": [],
    "storey_in_doubt": False, "ambiguous_names_storey": False, "kidnap_window": 0.0,
    "max_seconds_to_relocalize": 0.0, "max_seconds_to_ambiguous": 0.0,
    "max_metres_to_localize": 0.0,  # 0: unchecked; replay only (the distance walked before)
}


class ContractError(Exception):
    pass


def read_contract(test_file):
    """{param: value} with DEFAULTS filled in, plus "storey" (the localizer's storey, "" = the
    whole building) and "rate" (the live test's playback rate) from the included launch."""
    try:
        root = ET.parse(test_file).getroot()
    except (OSError, ET.ParseError) as e:
        raise ContractError(f"{test_file}: cannot read: {e}") from e
    tests = root.findall("test")
    if len(tests) != 1:
        raise ContractError(f"{test_file}: {len(tests)} <test> elements, expected 1")
    c = dict(DEFAULTS)
    for p in tests[0].findall("param"):
        name, value = p.get("name"), p.get("value")
        if name not in DEFAULTS:
            if name in ("max_wait", "bag_end_quiet"):
                continue  # live collection only
            raise ContractError(f"{test_file}: unknown contract parameter '{name}'")
        c[name] = type(DEFAULTS[name])(yaml.safe_load(value)) if not isinstance(
            DEFAULTS[name], str) else value
    for p in tests[0].findall("rosparam"):
        c[p.get("param")] = [float(x) for x in yaml.safe_load(p.text)]
    args = {a.get("name"): a.get("value") for a in root.iter("arg") if a.get("value") is not None}
    c["storey"] = args.get("storey", "")
    c["rate"] = float(args.get("rate", "1"))
    return c


def read_tum(path):
    """[(stamp, x, y, z, yaw)] of a TUM file (yaw from the quaternion qx qy qz qw)."""
    rows = []
    with open(path) as f:
        for line in f:
            v = line.split()
            if len(v) != 8 or line.startswith("#"):
                continue
            t, x, y, z, qx, qy, qz, qw = map(float, v)
            yaw = math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
            rows.append((t, x, y, z, yaw))
    return rows


def wrap(a):
    return math.atan2(math.sin(a), math.cos(a))


class Replay:
    """One replay's outputs, analysed as test_localize analyses a live run."""

    def __init__(self, prefix):
        with open(prefix + ".json") as f:
            self.run = json.load(f)
        self.t0 = self.run["first_stamp"]
        self.truth = read_tum(prefix + ".truth.tum")
        self.poses = read_tum(prefix + ".pose_bim.tum")
        self.truth_t = [r[0] for r in self.truth]
        self.events = self.run["events"]
        self.matches = self.run["matches"]
        loc = [e["t"] for e in self.events if e["kind"] == "localized"]
        self.first_localized = loc[0] if loc else None  # s into the bag
        self.carries = [self.truth[i + 1][0] for i in range(len(self.truth) - 1)
                        if math.hypot(self.truth[i + 1][1] - self.truth[i][1],
                                      self.truth[i + 1][2] - self.truth[i][2]) > CARRY_JUMP]
        self.paired = []  # (stamp, xy error, signed yaw error, signed z error)
        for p in self.poses:
            i = bisect.bisect_left(self.truth_t, p[0] - 1e-9)
            if i == len(self.truth) or abs(self.truth[i][0] - p[0]) > PAIR_SLACK:
                continue
            t = self.truth[i]
            self.paired.append((p[0], math.hypot(p[1] - t[1], p[2] - t[2]), wrap(p[4] - t[4]),
                                p[3] - t[3]))
        # LOST (the merge dropped: a lost event or the S-Graph restarted) to the next LOCALIZED.
        self.lost, start = [], None
        for e in self.events:
            if e["kind"] in ("lost", "sgraph_restarted") and start is None:
                start = self.t0 + e["t"]
            elif e["kind"] == "localized" and start is not None:
                self.lost.append((start, self.t0 + e["t"]))
                start = None
        if start is not None:
            self.lost.append((start, math.inf))

    def truth_z_at(self, t):
        i = min(bisect.bisect_left(self.truth_t, t), len(self.truth) - 1)
        return self.truth[i][3]


def storey_at(c, replay, stamp):
    """The storey the truth stands on at `stamp` (by storey_elevations), else true_storey_id."""
    if not c["storey_elevations"]:
        return c["true_storey_id"]
    z, best = replay.truth_z_at(stamp), -1
    for i, e in enumerate(c["storey_elevations"]):
        if e <= z + 0.05 and (best < 0 or e > c["storey_elevations"][best]):
            best = i
    return best


def in_carry_window(c, replay, stamp):
    return (c["kidnap_window"] > 0 and len(replay.carries) > 0
            and replay.carries[0] <= stamp < replay.carries[0] + c["kidnap_window"])
