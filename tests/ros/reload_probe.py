#!/usr/bin/python3
"""Drives avatar_node's ~reload for test_avatar_reload.sh (rospy, not rosc).

Usage: reload_probe.py NODE STEP...   where each STEP is
  mesh=PATH   set NODE's ~mesh
  param=NAME=VALUE  set NODE's ~NAME (VALUE as YAML: 0.001, abc, ...)
  ok | fail   call NODE/reload, which must succeed | fail
Before the steps and after each call, joint_states are published until a
kinematic_mesh comes back; one line per call says its result and the body in
the next message: "reload ok|failed: N vertices, topology T". Exits 1 when a
call does not end as its step says or no mesh comes back within 30 s."""
import sys
import threading
import time

import rospy
from sensor_msgs.msg import JointState
from skin_sim.msg import SkinMesh
from std_srvs.srv import Empty

node = sys.argv[1].rstrip("/")
rospy.init_node("reload_probe", anonymous=True, disable_signals=True)
lock = threading.Condition()
last = {"n": 0}


def on_mesh(m):
    with lock:
        last["n"] += 1
        last["body"] = (len(m.positions) // 3, m.topology_id)
        lock.notify_all()


sub = rospy.Subscriber("kinematic_mesh", SkinMesh, on_mesh, queue_size=10)
pub = rospy.Publisher("joint_states", JointState, queue_size=10)


def next_body():
    """Publishes joint_states until a mesh newer than now comes back."""
    with lock:
        n0 = last["n"]
    deadline = time.monotonic() + 30.0
    k = 0
    while time.monotonic() < deadline:
        js = JointState()
        js.header.stamp = rospy.Time.now()
        js.name = ["l_elbow"]
        js.position = [0.1 * (k % 10)]
        k += 1
        pub.publish(js)
        with lock:
            lock.wait(0.1)
            if last["n"] > n0:
                return last["body"]
    return None


status = 0
body = next_body()
if body is None:
    sys.exit("reload_probe: no kinematic_mesh within 30 s")
print("start: %d vertices, topology %d" % body)
rospy.wait_for_service(node + "/reload", 30.0)
reload = rospy.ServiceProxy(node + "/reload", Empty)
for step in sys.argv[2:]:
    if step.startswith("mesh="):
        rospy.set_param(node + "/mesh", step[5:])
        continue
    if step.startswith("param="):
        name, _, value = step[6:].partition("=")
        try:
            value = float(value)
        except ValueError:
            pass
        rospy.set_param(node + "/" + name, value)
        continue
    try:
        reload()
        result = "ok"
    except rospy.ServiceException:
        result = "failed"
    body = next_body()
    if body is None:
        print("reload %s: no kinematic_mesh within 30 s after it" % result)
        status = 1
        continue
    print("reload %s: %d vertices, topology %d" % ((result,) + body))
    if (result == "ok") != (step == "ok"):
        print("reload_probe: the call should have %s" % ("succeeded" if step == "ok" else "failed"))
        status = 1
sys.exit(status)
