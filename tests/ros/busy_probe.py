#!/usr/bin/python3
"""Drives skin_sim_node through one long step for test_skin_busy.sh: a torus of
TRIS triangles (default 20160) at t = 1 s (the skin is created), then the same torus
turned a little at t = 1.033 s, which the node (started with many substeps and no
step budget) takes long to step. Collects the node's /diagnostics statuses between
sending that mesh and its answer on skin_mesh, and the first one after the answer.
Prints them, then `figures in_progress=N level_max=L after="MESSAGE" step_ms=MS`.
Exit 0 if the node answered both meshes, 1 if not (no wall-clock bound but a
generous one on waiting). Usage: busy_probe.py [TRIS]."""
import math
import sys
import threading
import time

import rospy
from diagnostic_msgs.msg import DiagnosticArray
from skin_sim.msg import SkinMesh, SkinStats

tris = int(sys.argv[1]) if len(sys.argv) > 1 else 20160
K = 36
M = max(3, tris // (2 * K))


def torus(turn, stamp):
    m = SkinMesh()
    m.header.stamp = rospy.Time(stamp // 10**9, stamp % 10**9)
    m.header.frame_id = "body"
    m.topology_id = 11
    pos = []
    for i in range(M):
        a = 2 * math.pi * i / M + turn
        for j in range(K):
            b = 2 * math.pi * j / K
            r = 0.3 + 0.1 * math.cos(b)
            pos += [r * math.cos(a), r * math.sin(a), 0.1 * math.sin(b)]
    tri = []
    for i in range(M):
        for j in range(K):
            v00, v10 = i * K + j, ((i + 1) % M) * K + j
            v01, v11 = i * K + (j + 1) % K, ((i + 1) % M) * K + (j + 1) % K
            tri += [v00, v10, v11, v00, v11, v01]
    m.positions = pos
    m.triangles = tri
    return m


lock = threading.Lock()
answers, statuses, stats = [], [], []


def on_diag(a):
    with lock:
        for s in a.status:
            if "skin" in s.name:
                statuses.append((time.monotonic(), s.level, s.message))


def on_skin(m):
    with lock:
        answers.append((time.monotonic(), m.header.stamp.to_nsec()))


rospy.init_node("busy_probe", anonymous=True, disable_signals=True)
rospy.Subscriber("/diagnostics", DiagnosticArray, on_diag)
rospy.Subscriber("skin_mesh", SkinMesh, on_skin)
rospy.Subscriber("skin_stats", SkinStats, lambda m: stats.append(m.total_ms))
pub = rospy.Publisher("kinematic_mesh", SkinMesh, queue_size=10)
deadline = time.monotonic() + 60.0
while pub.get_num_connections() == 0:
    if time.monotonic() > deadline:
        sys.exit("busy_probe: no subscriber on kinematic_mesh within 60 s")
    time.sleep(0.02)
time.sleep(1.0)


def wait_answer(stamp, timeout, resend=None):
    end = time.monotonic() + timeout
    last = time.monotonic()
    while True:
        with lock:
            hit = [t for t, s in answers if s == stamp]
        if hit:
            return hit[0]
        if time.monotonic() > end:
            return None
        if resend is not None and time.monotonic() - last > 5.0:
            pub.publish(resend)
            last = time.monotonic()
        time.sleep(0.02)


first = torus(0.0, 10**9)
pub.publish(first)
if wait_answer(10**9, 600.0, resend=first) is None:
    sys.exit("busy_probe: the first mesh was not answered within 600 s")
t_send = time.monotonic()
pub.publish(torus(0.01, 10**9 + 33 * 10**6))
t_ans = wait_answer(10**9 + 33 * 10**6, 1800.0)
if t_ans is None:
    sys.exit("busy_probe: the long step was not answered within 1800 s")
end = time.monotonic() + 30.0
while time.monotonic() < end:  # the first status after the answer
    with lock:
        after = [s for s in statuses if s[0] > t_ans]
    if after:
        break
    time.sleep(0.05)
with lock:
    during = [s for s in statuses if t_send < s[0] < t_ans]
    after = [s for s in statuses if s[0] > t_ans]
for t, level, msg in during:
    print("during the step: +%.2f s level %d \"%s\"" % (t - t_send, level, msg))
busy = [s for s in during if "step in progress for" in s[2]]
print("figures in_progress=%d level_max=%d step_ms=%d after=\"%s\"" %
      (len(busy), max([s[1] for s in busy] or [-1]), int(1e3 * (t_ans - t_send)),
       after[0][2] if after else ""), flush=True)
rospy.signal_shutdown("done")
