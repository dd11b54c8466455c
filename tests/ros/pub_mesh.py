#!/usr/bin/python3
"""Publishes SkinMesh messages with rospy (not rosc) for test_rosc.sh: one whose
frame_id is too long for the C view (the subscriber must drop it and count it), then a
good one. Waits (bounded) for a subscriber first, then stays up to 10 s. Usage: pub_mesh.py TOPIC."""
import sys
import time

import rospy
from skin_sim.msg import SkinMesh

topic = sys.argv[1]
rospy.init_node("pub_mesh", anonymous=True, disable_signals=True)
pub = rospy.Publisher(topic, SkinMesh, queue_size=10)
deadline = time.monotonic() + 15.0
while pub.get_num_connections() == 0:
    if time.monotonic() > deadline:
        sys.exit("pub_mesh: no subscriber on %s within 15 s" % topic)
    time.sleep(0.02)

bad = SkinMesh()
bad.header.frame_id = "x" * 300
bad.positions = [0.0, 0.0, 0.0]
pub.publish(bad)

good = SkinMesh()
good.header.stamp = rospy.Time(1234, 5678)
good.header.frame_id = "body"
good.topology_id = 9
good.positions = [0.1, -2.5, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]
good.triangles = [0, 1, 2]
pub.publish(good)
time.sleep(10.0)  # stay until the test stops it (TERM): the messages must leave first
rospy.signal_shutdown("done")
