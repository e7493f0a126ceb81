#!/usr/bin/python3
"""Relay of the bag's odometry and clouds that injects one fault (the fault suite,
test/ros/faults_*.test).

The player publishes the bag's `odom` and `velodyne_points` as `raw/odom` and
`raw/velodyne_points`; this node forwards them to `odom` and `velodyne_points`, and changes them
in the fault's window. Private parameters:
  ~fault     none | nan_odometry | odom_glitch | odom_step | nan_clouds | empty_clouds | pause
  ~start     s of bag time after the first message (header stamps) when the fault begins
  ~duration  s the window lasts (nan_odometry, nan_clouds, empty_clouds, pause)
The faults:
  nan_odometry  position.x and orientation.w NaN
  odom_glitch   one message (the first in the window) 50 m further in x
  odom_step     every message from `start` on 50 m further in x (lasting)
  nan_clouds    x, y, z of every point NaN (the header's is_dense left as it was)
  empty_clouds  width 0, row_step 0, no data
  pause         nothing forwarded on odom or the clouds (the bag's clock and tf go on)
Each begin and end is logged (rospy.loginfo) and sent on `fault_events` (std_msgs/String,
JSON: fault, event begin|end, t in s after the first message, stamp, count).

Cheap: a message outside the window is forwarded as the same bytes (rospy.AnyMsg, no parsing);
only a message to change is parsed, and a cloud's points are changed with numpy. nav_msgs has
no Python module on Debian's ROS: nav_msgs/Odometry is generated from its .msg files.
"""
import io
import json
import struct
import threading

import numpy as np
import rospy
from sensor_msgs.msg import PointCloud2
from std_msgs.msg import String

from fault_msgs import message_class, raw_class

FAULTS = ("none", "nan_odometry", "odom_glitch", "odom_step", "nan_clouds", "empty_clouds",
          "pause")
STEP = 50.0  # m, odom_glitch and odom_step


def header_stamp(buff):
    """The header stamp (s) of a serialized message that starts with std_msgs/Header."""
    _, secs, nsecs = struct.unpack_from("<3I", buff, 0)
    return secs + nsecs * 1e-9


class FaultRelay:
    def __init__(self):
        self.fault = rospy.get_param("~fault", "none")
        if self.fault not in FAULTS:
            raise ValueError(f"fault_relay: unknown fault {self.fault!r} (one of {FAULTS})")
        self.start = float(rospy.get_param("~start", 10.0))
        self.duration = float(rospy.get_param("~duration", 0.0))
        self.t0 = None       # the first message's stamp
        self.state = "before"  # before, in or after the window
        self.count = 0       # messages changed or dropped
        self.glitched = False
        self.lock = threading.Lock()  # the two subscribers' threads share the window
        self.odom_cls = message_class("nav_msgs/Odometry",
                                      ("nav_msgs", "std_msgs", "geometry_msgs"))
        self.RawOdom, self.RawCloud = raw_class(self.odom_cls), raw_class(PointCloud2)
        self.events = rospy.Publisher("fault_events", String, queue_size=10, latch=True)
        self.odom_pub = rospy.Publisher("odom", self.RawOdom, queue_size=100)
        self.cloud_pub = rospy.Publisher("velodyne_points", self.RawCloud, queue_size=5)
        rospy.Subscriber("raw/odom", rospy.AnyMsg, self.on_odom, queue_size=100)
        rospy.Subscriber("raw/velodyne_points", rospy.AnyMsg, self.on_cloud, queue_size=5)
        rospy.loginfo("fault_relay: %s from %.1f s for %.1f s (bag time after the first message)",
                      self.fault, self.start, self.duration)

    # --- the window ---
    def in_window(self, stamp, odometry=True):
        """Whether a message of this stamp is inside the fault's window; logs begin and end
        (from the messages the fault changes)."""
        with self.lock:
            if self.t0 is None:
                self.t0 = stamp  # the first message of either
            odom_fault = self.fault in ("nan_odometry", "odom_glitch", "odom_step")
            if odom_fault != odometry and self.fault != "pause":
                return False
            return self._in_window(stamp)

    def _in_window(self, stamp):
        # Per message: the clouds' stamps run 0.1 s behind the odometry's (a scan is stamped at
        # its first firing), so begin and end are each sent once, by the first message past them.
        t = stamp - self.t0
        if self.fault == "odom_step":
            inside = t >= self.start
        elif self.fault == "odom_glitch":
            inside = t >= self.start and not self.glitched
        else:
            inside = self.start <= t < self.start + self.duration
        if self.fault != "none":
            if self.state == "before" and t >= self.start:
                self.state = "in"
                self.event("begin", t, stamp)
            over = self.glitched if self.fault == "odom_glitch" else (
                self.fault != "odom_step" and t >= self.start + self.duration)
            if self.state == "in" and over:
                self.state = "after"
                self.event("end", t, stamp)
        return inside

    def event(self, what, t, stamp):
        rospy.loginfo("fault_relay: %s %s at %.2f s (stamp %.3f), %d messages changed so far",
                      self.fault, what, t, stamp, self.count)
        self.events.publish(String(json.dumps({"fault": self.fault, "event": what, "t": t,
                                               "stamp": stamp, "count": self.count})))

    # --- odometry ---
    def on_odom(self, raw):
        stamp = header_stamp(raw._buff)
        if not self.in_window(stamp):
            return self.forward(self.odom_pub, self.RawOdom, raw._buff)
        self.count += 1
        if self.fault == "pause":
            return
        msg = self.odom_cls()
        msg.deserialize(raw._buff)
        if self.fault == "nan_odometry":
            msg.pose.pose.position.x = float("nan")
            msg.pose.pose.orientation.w = float("nan")
        else:
            msg.pose.pose.position.x += STEP
            if self.fault == "odom_glitch":
                self.glitched = True
                rospy.loginfo("fault_relay: odom_glitch: odometry at stamp %.3f moved %.0f m "
                              "in x", stamp, STEP)
        self.forward(self.odom_pub, self.RawOdom, serialize(msg))
        if self.fault == "odom_glitch":  # the window (one message) ends here
            self.in_window(stamp)

    # --- clouds ---
    def on_cloud(self, raw):
        stamp = header_stamp(raw._buff)
        if not self.in_window(stamp, odometry=False):
            return self.forward(self.cloud_pub, self.RawCloud, raw._buff)
        self.count += 1
        if self.fault == "pause":
            return
        msg = PointCloud2()
        msg.deserialize(raw._buff)
        if self.fault == "empty_clouds":
            msg.width, msg.row_step, msg.data = 0, 0, b""
        else:
            msg.data = nan_points(msg)
        self.forward(self.cloud_pub, self.RawCloud, serialize(msg))

    @staticmethod
    def forward(pub, raw_cls, buff):
        out = raw_cls()
        out._buff = buff
        pub.publish(out)


def serialize(msg):
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


NAN32 = np.frombuffer(np.array([np.nan], dtype="<f4").tobytes(), dtype=np.uint8)


def nan_points(cloud):
    """The cloud's data with the float32 bytes of x, y and z NaN in every point."""
    data = np.frombuffer(cloud.data, dtype=np.uint8).copy()
    offsets = [f.offset for f in cloud.fields if f.name in ("x", "y", "z")]
    size = cloud.width * cloud.point_step
    for row in range(cloud.height):  # a view of each row's points (rows may be padded)
        begin = row * cloud.row_step
        points = data[begin:begin + size].reshape(cloud.width, cloud.point_step)
        for offset in offsets:
            points[:, offset:offset + 4] = NAN32
    return data.tobytes()


if __name__ == "__main__":
    rospy.init_node("fault_relay")
    FaultRelay()
    rospy.spin()
