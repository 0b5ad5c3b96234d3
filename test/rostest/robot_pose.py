"""Shared by the Python rostests: places the robot in tf (global frame -> base frame, broadcast at 20 Hz
from a thread) and waits, on the costmap node's ~footprint (published once a cycle at the pose that
cycle used), until the node has run cycles at the new pose: no guessed sleeps."""
import math
import threading

import rospy
import tf2_ros
from geometry_msgs.msg import PolygonStamped, TransformStamped


class RobotPose:
    def __init__(self, ns, x, y, yaw=0.0, parent="map", child="base_link"):
        self.parent, self.child = parent, child
        self.pose = (x, y, yaw)
        self.lock = threading.Lock()
        self.cond = threading.Condition()
        self.centre = None
        self.cycles = 0
        self.broadcaster = tf2_ros.TransformBroadcaster()
        rospy.Subscriber(ns + "/footprint", PolygonStamped, self._on_footprint)
        self.timer = rospy.Timer(rospy.Duration(0.05), self._broadcast)

    def _broadcast(self, _):
        with self.lock:
            x, y, yaw = self.pose
        t = TransformStamped()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id = self.parent
        t.child_frame_id = self.child
        t.transform.translation.x = x
        t.transform.translation.y = y
        t.transform.rotation.z = math.sin(yaw / 2.0)
        t.transform.rotation.w = math.cos(yaw / 2.0)
        self.broadcaster.sendTransform(t)

    def _on_footprint(self, msg):
        pts = msg.polygon.points
        with self.cond:
            if pts:
                self.centre = (sum(p.x for p in pts) / len(pts), sum(p.y for p in pts) / len(pts))
            self.cycles += 1
            self.cond.notify_all()

    def place(self, x, y, yaw=0.0):
        """Puts the robot at (x, y, yaw) without waiting (the caller waits on what the pose changes)."""
        with self.lock:
            self.pose = (x, y, yaw)

    def move_to(self, x, y, yaw=0.0, cycles=2, timeout=20.0):
        """Puts the robot at (x, y, yaw); returns once the node ran `cycles` cycles there (False on timeout).
        The footprint's centroid is the robot's position for the symmetric footprints the tests use."""
        with self.lock:
            self.pose = (x, y, yaw)
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.cond:
            while not rospy.is_shutdown() and rospy.Time.now() < deadline:
                if self.centre is not None and math.hypot(self.centre[0] - x, self.centre[1] - y) < 1e-3:
                    break
                self.cond.wait(0.2)
            else:
                return False
            target = self.cycles + cycles
            while self.cycles < target and not rospy.is_shutdown() and rospy.Time.now() < deadline:
                self.cond.wait(0.2)
            return self.cycles >= target
