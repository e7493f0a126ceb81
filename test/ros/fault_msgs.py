"""Message helpers of the fault suite's nodes (fault_relay.py, test_faults.py), so that they
need no generated Python message module: nav_msgs has none on Debian's ROS, and is_graphs'
own may be older than the nodes' (a rebuild regenerates the C++ headers first)."""
import os

import genmsg
import genmsg.msg_loader
import genpy.dynamic
import rospkg
import rospy


def message_class(msg_type, packages):
    """`msg_type` (e.g. nav_msgs/Odometry) as a genpy class, from the .msg files of `packages`
    (its own and those it uses)."""
    packs = rospkg.RosPack()
    path = {p: [os.path.join(packs.get_path(p), "msg")] for p in packages}
    ctx = genmsg.MsgContext.create_default()
    spec = genmsg.msg_loader.load_msg_by_type(ctx, msg_type, path)
    genmsg.msg_loader.load_depends(ctx, spec, path)
    text = genmsg.compute_full_text(ctx, spec)
    return genpy.dynamic.generate_dynamic(msg_type, text)[msg_type]


def raw_class(cls):
    """A rospy.AnyMsg that publishes serialized `cls` bytes as they are."""
    return type("Raw" + cls.__name__, (rospy.AnyMsg,),
                {"_type": cls._type, "_md5sum": cls._md5sum, "_full_text": cls._full_text})


class Decoder:
    """Decodes a rospy.AnyMsg with the definition its publisher sent (connection header)."""

    def __init__(self):
        self.classes = {}

    def __call__(self, raw):
        header = raw._connection_header
        key = header["md5sum"]
        if key not in self.classes:
            self.classes[key] = genpy.dynamic.generate_dynamic(
                header["type"], header["message_definition"])[header["type"]]
        msg = self.classes[key]()
        msg.deserialize(raw._buff)
        return msg
