#!/usr/bin/env python3
"""Test helper node: publishes static bim -> map -> odom -> base_link (as a localized robot
would have them), so rviz can draw everything in the bim frame without the whole pipeline."""
import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped


def frame(parent, child, x, y, z=0.0):
    t = TransformStamped()
    t.header.stamp = rospy.Time.now()
    t.header.frame_id = parent
    t.child_frame_id = child
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = x, y, z
    t.transform.rotation.w = 1.0
    return t


if __name__ == "__main__":
    rospy.init_node("static_frames")
    broadcaster = tf2_ros.StaticTransformBroadcaster()
    x = rospy.get_param("~x", 15.0)
    y = rospy.get_param("~y", 4.0)
    broadcaster.sendTransform([frame("bim", "map", 0.0, 0.0), frame("map", "odom", 0.0, 0.0),
                               frame("odom", "base_link", x, y, 0.525)])
    rospy.spin()
