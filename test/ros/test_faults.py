#!/usr/bin/python3
"""Checker of the fault suite (test/ros/faults_*.test): the whole pipeline
(fault_pipeline.launch) on a bag with faults injected, against the contract of the .test file.

It collects pose_bim, localization_status, ground_truth/pose and fault_events until the bag has
played (no ground truth for ~bag_end_quiet wall seconds, or the bag's next loop after ~plays
plays), then checks. Times are "played" bag seconds after the first ground truth: with plays 2
the second play counts on from the first one's end (its jump back in time is the time_back
fault).

Private parameters (the contract):
  scenario                  name in the messages
  faults                    list of {name, start, duration, and the expectations below}; start
                            and duration in bag seconds as given to fault_relay.py /
                            fault_signal.py (their fault_events, when sent, give the times used);
                            time_back: the start is the jump back
    max_seconds_to_leave_localized  > 0: a status other than LOCALIZED within that many s after
                                    the start (DEGRADED or LOST)
    max_seconds_to_lost             > 0: LOST within that many s after the start
    max_seconds_to_relocalize       > 0: LOCALIZED again that many s after `relocalize_from`
                                    (end: the window's end; back: the killed node's respawn;
                                    start)
    require_localized               the pipeline must be LOCALIZED at the start (default true:
                                    otherwise the fault tests nothing)
  max_seconds_to_localize   the first LOCALIZED within that many s of the bag start
  max_wrong_distance, max_wrong_yaw_deg
                            no finite pose_bim further (x, y) or more turned (yaw) from the ground
                            truth at its stamp (and none with a quaternion of norm != 1)
  expect_localized_at_end   the last status is LOCALIZED
  plays                     how many plays of the bag (2: time_back)
  max_wait, bag_end_quiet   wall seconds
Always: no pose_bim with a non-finite field (position, orientation, covariance); no pose_bim
while the last status said LOST or NOT_LOCALIZED; no restart of a node that was not killed.
"""
import bisect
import json
import math
import threading
import time
import unittest
import xmlrpc.client

import rosgraph
import rospy
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped
from std_msgs.msg import String

from fault_msgs import Decoder

# is_graphs/LocalizationStatus, decoded with the merger's own definition (fault_msgs.py).
NOT_LOCALIZED, LOCALIZED, LOST, DEGRADED = 0, 1, 2, 3
STATE_NAMES = {NOT_LOCALIZED: "NOT_LOCALIZED", LOCALIZED: "LOCALIZED", LOST: "LOST",
               DEGRADED: "DEGRADED"}
# pose_bim carries odometry's stamps, localization_status the merger's clock when sent: two
# clocks of one simulated time, this much slack between them.
STAMP_SLACK = 0.25  # s
PAIR_TOLERANCE = 0.005  # s between a pose_bim and its ground truth
NODES = ("/sgraph_node", "/matcher_node", "/merger_node")
KILLED = {"kill_sgraph": "/sgraph_node", "kill_matcher": "/matcher_node",
          "kill_merger": "/merger_node"}


def yaw_of(q):
    """Yaw of a quaternion (x, y, z, w), normalized first; None when its norm is off 1."""
    n = math.sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w)
    if not abs(n - 1.0) < 1e-3:  # NaN fails too
        return None
    x, y, z, w = q.x / n, q.y / n, q.z / n, q.w / n
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def angle_diff(a, b):
    return math.atan2(math.sin(a - b), math.cos(a - b))


def pose_finite(p):
    pp = p.pose.pose
    return all(math.isfinite(v) for v in (pp.position.x, pp.position.y, pp.position.z,
                                          pp.orientation.x, pp.orientation.y,
                                          pp.orientation.z, pp.orientation.w))


class TimeoutTransport(xmlrpc.client.Transport):
    """XML-RPC with a timeout (a stopped node would never answer)."""

    def make_connection(self, host):
        conn = super().make_connection(host)
        conn.timeout = 3.0
        return conn


def node_pids():
    """pid of each of NODES, asked through the master (None: not answering)."""
    pids = {}
    for name in NODES:
        try:
            uri = rosgraph.Master("/test_faults").lookupNode(name)
            proxy = xmlrpc.client.ServerProxy(uri, transport=TimeoutTransport())
            code, _, pid = proxy.getPid("/test_faults")
            pids[name] = pid if code == 1 else None
        except Exception:  # not registered, not answering
            pids[name] = None
    return pids


class Collector:
    """pose_bim, statuses, ground truth and fault events, each with its played time."""

    def __init__(self, plays):
        self.plays = plays
        self.lock = threading.Lock()
        self.truth = {}      # stamp ns -> (x, y, yaw)
        self.poses = []      # (played s, PoseWithCovarianceStamped)
        self.statuses = []   # (played s, LocalizationStatus), in arrival order
        self.events = []     # dicts from fault_events
        self.t0 = None       # first ground truth stamp
        self.epoch = 0       # plays begun - 1
        self.period = 0.0    # the bag's length (set at the first jump back)
        self.last_truth = None
        self.last_truth_wall = None
        self.done = False    # the next play began after `plays` plays
        self.first_pids = None
        rospy.Subscriber("ground_truth/pose", PoseStamped, self.on_truth, queue_size=2000)
        rospy.Subscriber("pose_bim", PoseWithCovarianceStamped, self.on_pose, queue_size=2000)
        self.decode = Decoder()
        rospy.Subscriber("localization_status", rospy.AnyMsg, self.on_status, queue_size=200)
        rospy.Subscriber("fault_events", String, self.on_event, queue_size=50)

    def played(self, stamp):
        """Played seconds of a stamp: a late message of the previous play keeps its play."""
        if self.t0 is None:
            return stamp - 1e9
        epoch = self.epoch
        if epoch > 0 and self.last_truth is not None and stamp > self.last_truth + 2.0:
            epoch -= 1
        return stamp - self.t0 + epoch * self.period

    def on_truth(self, m):
        s = m.header.stamp.to_sec()
        with self.lock:
            if self.done:
                return
            if self.t0 is None:
                self.t0 = s
            if self.last_truth is not None and s < self.last_truth - 1.0:
                if self.epoch == 0:
                    self.period = self.last_truth - self.t0 + 0.02  # 50 Hz
                self.epoch += 1
                if self.epoch >= self.plays:
                    self.done = True
                    return
            self.last_truth = s
            self.last_truth_wall = time.monotonic()
            q = m.pose.orientation
            self.truth[m.header.stamp.to_nsec()] = (m.pose.position.x, m.pose.position.y,
                                                    yaw_of(q))

    def on_pose(self, m):
        with self.lock:
            if not self.done:
                self.poses.append((self.played(m.header.stamp.to_sec()), m))

    def on_status(self, raw):
        m = self.decode(raw)
        with self.lock:
            if self.done:
                return
            # A node just (re)started sends its first status before it has the clock: stamp 0,
            # taken as the newest ground truth's time.
            stamp = m.header.stamp.to_sec()
            if stamp == 0.0 and self.last_truth is not None:
                stamp = self.last_truth
            self.statuses.append((self.played(stamp), m))

    def on_event(self, m):
        with self.lock:
            self.events.append(json.loads(m.data))

    def wait(self, max_wait, quiet):
        """Waits for the bag's end; asks the nodes' pids once the bag plays."""
        start = time.monotonic()
        while not rospy.is_shutdown() and time.monotonic() - start < max_wait:
            time.sleep(0.2)
            if self.first_pids is None and self.t0 is not None:
                self.first_pids = node_pids()
            with self.lock:
                if self.done or (self.last_truth_wall is not None
                                 and time.monotonic() - self.last_truth_wall > quiet):
                    break
        with self.lock:
            self.done = True
        return time.monotonic() - start


class FaultTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_faults")
        get = lambda name, default: rospy.get_param("~" + name, default)  # noqa: E731
        cls.scenario = get("scenario", "?")
        cls.faults = [dict(f) for f in get("faults", [])]
        cls.max_seconds_to_localize = float(get("max_seconds_to_localize", 10.0))
        cls.max_wrong_distance = float(get("max_wrong_distance", 0.5))
        cls.max_wrong_yaw = math.radians(float(get("max_wrong_yaw_deg", 5.0)))
        cls.expect_localized_at_end = bool(get("expect_localized_at_end", True))
        plays = int(get("plays", 1))
        c = Collector(plays)
        cls.c = c
        cls.wall = c.wait(float(get("max_wait", 150.0)), float(get("bag_end_quiet", 2.5)))
        cls.last_pids = node_pids()
        cls.analyze()

    # --- analysis ---
    @classmethod
    def analyze(cls):
        c = cls.c
        cls.out(f"collected {cls.wall:.1f} s wall: {len(c.truth)} ground truth, "
                f"{len(c.poses)} pose_bim, {len(c.statuses)} statuses, {c.epoch + 1} play(s), "
                f"events {c.events}")
        for f in cls.faults:  # the fault's times: its events where sent, else the .test's
            name = f["name"]
            evs = {}
            for e in c.events:  # the first of each
                if e.get("fault") == name:
                    evs.setdefault(e["event"], e["t"])
            if name == "time_back":  # the first play's last ground truth
                f["begin"] = c.period - 0.02 if c.epoch > 0 else math.inf
            else:
                f["begin"] = evs.get("begin", float(f.get("start", 0.0)))
            f["end"] = evs.get("end", f["begin"] + float(f.get("duration", 0.0)))
            f["back"] = evs.get("back")
        cls.keys = sorted(c.truth)
        # Status timeline: (played s, state) in arrival order.
        cls.timeline = [(p, s.state) for p, s in c.statuses]
        cls.first_localized = next((p for p, st in cls.timeline if st == LOCALIZED), None)
        # Every change of state with its message: what a failure below is read against.
        changes, last = [], None
        for p, s in c.statuses:
            if s.state != last:
                changes.append(f"{p:.2f} s {STATE_NAMES.get(s.state, s.state)} ({s.message})")
                last = s.state
        cls.out("status changes: " + "; ".join(changes))

    @classmethod
    def out(cls, text):
        print(f"[ {cls.scenario} ] {text}", flush=True)

    def where(self, played):
        """The fault a time falls after (the latest begun), for the messages."""
        begun = [f for f in self.faults if f["begin"] <= played + 1e-9]
        if not begun:
            return "before any fault"
        f = max(begun, key=lambda f: f["begin"])
        return f"{f['name']} (+{played - f['begin']:.2f} s after its start)"

    def state_at(self, played):
        state = None
        for p, st in self.timeline:
            if p > played:
                break
            state = st
        return state

    def truth_at(self, stamp):
        ns = int(round(stamp * 1e9))
        i = bisect.bisect_left(self.keys, ns)
        best = None
        for k in self.keys[max(0, i - 1):i + 1]:
            if abs(k - ns) <= PAIR_TOLERANCE * 1e9 and (best is None or
                                                        abs(k - ns) < abs(best - ns)):
                best = k
        return None if best is None else self.c.truth[best]

    # --- tests ---
    def test_00_bag_played(self):
        self.assertTrue(self.c.truth, f"[{self.scenario}] no ground truth: the bag did not play")
        self.assertTrue(self.c.statuses, f"[{self.scenario}] no localization_status")

    def test_01_localized_before_faults(self):
        t = self.first_localized
        self.out(f"first LOCALIZED at {t} s into the bag")
        self.assertIsNotNone(t, f"[{self.scenario}] never LOCALIZED")
        self.assertLessEqual(t, self.max_seconds_to_localize,
                             f"[{self.scenario}] first LOCALIZED at {t:.1f} s")
        for f in self.faults:
            if not f.get("require_localized", True):
                continue
            state = self.state_at(f["begin"] - STAMP_SLACK)
            self.assertEqual(state, LOCALIZED,
                             f"[{self.scenario}] {f['name']}: not LOCALIZED at its start "
                             f"({f['begin']:.1f} s) but {STATE_NAMES.get(state)}: the fault "
                             "tests nothing")

    def test_no_non_finite_pose(self):
        bad = [(p, m) for p, m in self.c.poses if not pose_finite(m)]
        bad_cov = [(p, m) for p, m in self.c.poses
                   if not all(math.isfinite(v) for v in m.pose.covariance)]
        self.out(f"{len(self.c.poses)} pose_bim: {len(bad)} with a non-finite position or "
                 f"orientation, {len(bad_cov)} with a non-finite covariance")
        for what, lst in (("position or orientation", bad), ("covariance", bad_cov)):
            if lst:
                p, m = lst[0]
                pp = m.pose.pose
                self.fail(f"[{self.scenario}] {len(lst)} pose_bim with a non-finite {what}, the "
                          f"first at {p:.2f} s, during {self.where(p)}: position "
                          f"({pp.position.x}, {pp.position.y}, {pp.position.z}), orientation w "
                          f"{pp.orientation.w}")

    def test_no_wrong_pose(self):
        checked, unpaired, wrong, worst = 0, 0, [], None
        for p, m in self.c.poses:
            if not pose_finite(m):
                continue  # counted by test_no_non_finite_pose
            truth = self.truth_at(m.header.stamp.to_sec())
            if truth is None:
                unpaired += 1
                continue
            checked += 1
            pos = m.pose.pose.position
            err = math.hypot(pos.x - truth[0], pos.y - truth[1])
            yaw = yaw_of(m.pose.pose.orientation)
            err_yaw = math.inf if yaw is None else abs(angle_diff(yaw, truth[2]))
            if worst is None or err > worst[1]:
                worst = (p, err, err_yaw)
            if err > self.max_wrong_distance or err_yaw > self.max_wrong_yaw:
                wrong.append((p, err, err_yaw))
        self.out(f"{checked} pose_bim paired with ground truth ({unpaired} without one): "
                 f"{len(wrong)} more than {self.max_wrong_distance} m or "
                 f"{math.degrees(self.max_wrong_yaw):.1f} deg off; max error "
                 + (f"{worst[1]:.3f} m at {worst[0]:.2f} s" if worst else "-"))
        per_fault = {}
        for p, err, _ in wrong:
            per_fault.setdefault(self.where(p).split(" (")[0], []).append(err)
        for name, errs in per_fault.items():
            self.out(f"  wrong poses after {name}: {len(errs)}, max {max(errs):.2f} m")
        if wrong:
            p, err, err_yaw = max(wrong, key=lambda w: w[1])
            self.fail(f"[{self.scenario}] {len(wrong)} of {checked} pose_bim wrong "
                      f"({', '.join(f'{k}: {len(v)}' for k, v in per_fault.items())}); the worst "
                      f"at {p:.2f} s, during {self.where(p)}: {err:.2f} m, "
                      f"{math.degrees(err_yaw):.1f} deg off")

    def test_no_pose_while_not_localized(self):
        """No pose_bim while the last status (after the first LOCALIZED) said LOST or
        NOT_LOCALIZED."""
        intervals, from_p = [], None
        seen_localized = False
        for p, st in self.timeline:
            seen_localized = seen_localized or st == LOCALIZED
            if st in (LOST, NOT_LOCALIZED) and seen_localized and from_p is None:
                from_p = p
            elif st in (LOCALIZED, DEGRADED) and from_p is not None:
                intervals.append((from_p, p))
                from_p = None
        if from_p is not None:
            intervals.append((from_p, math.inf))
        bad = [p for p, _ in self.c.poses
               if any(a + STAMP_SLACK < p < b - STAMP_SLACK for a, b in intervals)]
        self.out(f"not localized (LOST / NOT_LOCALIZED) after the first LOCALIZED: "
                 + ", ".join(f"{a:.1f}-{b:.1f} s" for a, b in intervals)
                 + f"; {len(bad)} pose_bim in them")
        if bad:
            self.fail(f"[{self.scenario}] {len(bad)} pose_bim while LOST or NOT_LOCALIZED, the "
                      f"first at {bad[0]:.2f} s, during {self.where(bad[0])}")

    def test_status_per_fault(self):
        """Each fault's status contract: leave LOCALIZED, LOST, LOCALIZED again in time."""
        failures = []
        for f in self.faults:
            name, begin = f["name"], f["begin"]
            if not math.isfinite(begin):
                failures.append(f"{name}: never happened (no time jump / no event)")
                continue
            after = [(max(0.0, p - begin), st) for p, st in self.timeline
                     if p >= begin - STAMP_SLACK]
            leave = next((t for t, st in after if st != LOCALIZED), None)
            lost = next((t for t, st in after if st == LOST), None)
            ref = {"end": f["end"], "back": f["back"], "start": begin}[
                f.get("relocalize_from", "end")]
            reloc = None
            bound = float(f.get("max_seconds_to_relocalize", 0.0))
            if ref is not None:
                # The LOCALIZED stretch that holds at ref + bound (or at the end): its start.
                at = ref + bound if bound > 0 else math.inf
                since = None
                for p, st in self.timeline:
                    if p > at:
                        break
                    if st == LOCALIZED and since is None:
                        since = p
                    elif st != LOCALIZED:
                        since = None
                reloc = None if since is None else max(0.0, since - ref)
            # Measured whatever the bound: the first LOCALIZED after it left LOCALIZED.
            first_back = None
            if leave is not None:
                first_back = next((p - begin for p, st in self.timeline
                                   if p >= begin + leave and st == LOCALIZED), None)
            fmt = lambda v: "never" if v is None else f"{v:.2f} s"  # noqa: E731
            self.out(f"{name}: from {begin:.2f} s to {f['end']:.2f} s"
                     + (f", node back at {f['back']:.2f} s" if f["back"] is not None else "")
                     + f"; left LOCALIZED after {fmt(leave)}, LOST after {fmt(lost)}, "
                     + f"LOCALIZED again {fmt(first_back)} after the start; "
                     + f"LOCALIZED again {fmt(reloc)} after its {f.get('relocalize_from', 'end')}"
                     + f" (state there + bound: {STATE_NAMES.get(self.state_at(ref + bound)) if ref is not None else '-'})")
            b = float(f.get("max_seconds_to_leave_localized", 0.0))
            if b > 0 and (leave is None or leave > b):
                failures.append(f"{name}: left LOCALIZED after {fmt(leave)} (bound {b} s)")
            b = float(f.get("max_seconds_to_lost", 0.0))
            if b > 0 and (lost is None or lost > b):
                failures.append(f"{name}: LOST after {fmt(lost)} (bound {b} s)")
            if bound > 0:
                if ref is None:
                    failures.append(f"{name}: no '{f.get('relocalize_from')}' time (the node "
                                    "did not come back?)")
                elif reloc is None:
                    failures.append(f"{name}: not LOCALIZED {bound} s after its "
                                    f"{f.get('relocalize_from', 'end')} ({ref:.2f} s): "
                                    f"{STATE_NAMES.get(self.state_at(ref + bound))}")
        if failures:
            self.fail(f"[{self.scenario}] " + "; ".join(failures))

    def test_localized_at_end(self):
        if not self.expect_localized_at_end:
            self.skipTest("not expected")
        self.assertTrue(self.c.statuses, "no status")
        p, last = self.c.statuses[-1]
        self.out(f"last status at {p:.1f} s: {STATE_NAMES.get(last.state)}: {last.message}")
        self.assertEqual(last.state, LOCALIZED,
                         f"[{self.scenario}] not LOCALIZED at the end ({p:.1f} s) after "
                         f"{', '.join(f['name'] for f in self.faults)}: "
                         f"{STATE_NAMES.get(last.state)}: {last.message}")

    def test_no_unexpected_restart(self):
        first = self.c.first_pids if isinstance(self.c.first_pids, dict) else {}
        killed = {KILLED[f["name"]] for f in self.faults if f["name"] in KILLED}
        self.out(f"node pids at the start {first}, at the end {self.last_pids}; killed: "
                 f"{sorted(killed) or 'none'}")
        for name in NODES:
            a, b = first.get(name), self.last_pids.get(name)
            if name in killed:
                self.assertTrue(a is not None and b is not None and a != b,
                                f"[{self.scenario}] {name} killed but not respawned "
                                f"(pid {a} -> {b})")
            else:
                self.assertEqual(a, b, f"[{self.scenario}] {name} restarted (crashed?) during "
                                       f"{', '.join(f['name'] for f in self.faults)}: pid {a} "
                                       f"-> {b}")


if __name__ == "__main__":
    import rostest
    rostest.rosrun("is_graphs", "test_faults", FaultTest)
