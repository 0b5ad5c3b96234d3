#!/usr/bin/env python3
"""A dynamic_reconfigure server (/vanishing_server) that declares max_vel_x and exits, without
answering, as soon as a set_parameters call arrives: a server that disappears in the middle of a call."""
import os
import sys

import rospy
from dynamic_reconfigure.msg import ConfigDescription
from dynamic_reconfigure.srv import Reconfigure

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fake_reconfigure import description  # noqa: E402


def on_set(_req):
    sys.stdout.flush()
    os._exit(0)  # no answer, the connection closes with the process


if __name__ == "__main__":
    rospy.init_node("vanishing_server")
    pub = rospy.Publisher("~parameter_descriptions", ConfigDescription, queue_size=1, latch=True)
    pub.publish(description())
    rospy.Service("~set_parameters", Reconfigure, on_set)
    rospy.spin()
