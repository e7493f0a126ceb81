#!/usr/bin/python3
"""Node faults for the fault suite (test/ros/faults_*.test): signals one node of the pipeline at
a bag time. Private parameters:
  ~fault     none | sgraph_stop | kill_sgraph | kill_matcher | kill_merger
  ~start     s of bag time after the first `raw/odom` message (as test/ros/fault_relay.py)
  ~duration  s sgraph_stop holds the process stopped
sgraph_stop: SIGSTOP to sgraph_node (a hung S-Graph), SIGCONT after `duration`.
kill_*:      SIGKILL to the node; the launch file respawns it (respawn="true"). "back" is when the
             master knows a new process under the node's name (its getPid answers another pid).
The process id is asked of the node through the master (getPid), and its command line is checked
to be that node's before it is signalled. Each step is logged and sent on `fault_events`
(std_msgs/String, JSON: fault, event begin|end|back, t, stamp, pid).
"""
import json
import os
import signal
import struct
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
from std_msgs.msg import String

NODES = {"sgraph_stop": "sgraph_node", "kill_sgraph": "sgraph_node",
         "kill_matcher": "matcher_node", "kill_merger": "merger_node"}


class TimeoutTransport(xmlrpc.client.Transport):
    """XML-RPC with a timeout (a stopped node would never answer)."""

    def make_connection(self, host):
        conn = super().make_connection(host)
        conn.timeout = 3.0
        return conn


def node_pid(name):
    """The pid of the node registered as `name` (None when it does not answer)."""
    try:
        uri = rosgraph.Master("/fault_signal").lookupNode(name)
        proxy = xmlrpc.client.ServerProxy(uri, transport=TimeoutTransport())
        code, _, pid = proxy.getPid("/fault_signal")
        return pid if code == 1 else None
    except (OSError, xmlrpc.client.Error, rosgraph.MasterError):
        return None


class FaultSignal:
    def __init__(self):
        self.fault = rospy.get_param("~fault", "none")
        if self.fault != "none" and self.fault not in NODES:
            raise ValueError(f"fault_signal: unknown fault {self.fault!r}")
        self.node = "/" + NODES.get(self.fault, "")
        self.start = float(rospy.get_param("~start", 10.0))
        self.duration = float(rospy.get_param("~duration", 0.0))
        self.t0 = None
        self.step = "wait"  # wait -> (stopped ->) done
        self.pid = None
        self.lock = threading.Lock()
        self.events = rospy.Publisher("fault_events", String, queue_size=10, latch=True)
        rospy.on_shutdown(self.resume)
        if self.fault != "none":
            rospy.Subscriber("raw/odom", rospy.AnyMsg, self.on_odom, queue_size=10)
            rospy.loginfo("fault_signal: %s of %s at %.1f s for %.1f s (bag time)", self.fault,
                          self.node, self.start, self.duration)

    def event(self, what, stamp, **extra):
        t = stamp - self.t0
        rospy.loginfo("fault_signal: %s %s at %.2f s (stamp %.3f) %s", self.fault, what, t, stamp,
                      extra)
        self.events.publish(String(json.dumps(
            dict(fault=self.fault, event=what, t=t, stamp=stamp, **extra))))

    def signal(self, sig):
        pid = node_pid(self.node)
        if pid is None:
            rospy.logerr("fault_signal: %s has no pid from the master", self.node)
            return None
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            cmdline = f.read().replace(b"\0", b" ").decode(errors="replace")
        if NODES[self.fault] not in cmdline:
            rospy.logerr("fault_signal: pid %d is not %s: %s", pid, self.node, cmdline)
            return None
        os.kill(pid, sig)
        return pid

    def on_odom(self, raw):
        _, secs, nsecs = struct.unpack_from("<3I", raw._buff, 0)
        stamp = secs + nsecs * 1e-9
        with self.lock:
            if self.t0 is None:
                self.t0 = stamp
            t = stamp - self.t0
            if self.step == "wait" and t >= self.start:
                if self.fault == "sgraph_stop":
                    self.pid = self.signal(signal.SIGSTOP)
                    self.step = "stopped"
                    self.event("begin", stamp, pid=self.pid)
                else:
                    self.pid = self.signal(signal.SIGKILL)
                    self.step = "done"
                    self.event("begin", stamp, pid=self.pid)
                    threading.Thread(target=self.wait_back, daemon=True).start()
            elif self.step == "stopped" and t >= self.start + self.duration:
                self.resume()
                self.step = "done"
                self.event("end", stamp, pid=self.pid)
            self.last_stamp = stamp

    def wait_back(self):
        """Sends "back" once the master has a new process under the node's name."""
        deadline = time.monotonic() + 60.0
        while not rospy.is_shutdown() and time.monotonic() < deadline:
            pid = node_pid(self.node)
            if pid is not None and pid != self.pid:
                with self.lock:
                    self.event("back", self.last_stamp, pid=pid)
                return
            time.sleep(0.05)
        rospy.logerr("fault_signal: %s not back within 60 s", self.node)

    def resume(self):
        """SIGCONT to a stopped sgraph_node (also at shutdown, so that it can end)."""
        if self.fault == "sgraph_stop" and self.step == "stopped" and self.pid:
            try:
                os.kill(self.pid, signal.SIGCONT)
            except ProcessLookupError:
                pass


if __name__ == "__main__":
    rospy.init_node("fault_signal")
    FaultSignal()
    rospy.spin()
