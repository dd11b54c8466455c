#!/usr/bin/python3
"""Listens to the skin node for test_skin_carry.sh (real nodes, real master):

  carry_probe.py SECONDS OUT_JSON

Subscribes kinematic_mesh, skin_mesh and skin_stats for SECONDS (and on, at most 120 s
more, until 3 skin_mesh came). For every skin_mesh whose stamp is a kinematic_mesh's it
measures the largest distance between a skin vertex and the body vertex of the same index
(meaningful where the skin is the body's own), and keeps the first and the last skin_mesh:
their vertex count, topology_id, and the largest change of distance between any skin
vertex and skin vertex 0 from the first to the last (0 for a skin moved rigidly) and the
largest displacement (did it move at all). The last skin_stats' fields go out as they
are. Writes OUT_JSON and prints it; exit 0 if any skin_mesh came, 1 otherwise."""
import json
import sys
import time

import numpy as np
import rospy
from skin_sim.msg import SkinMesh, SkinStats

seconds, out_path = float(sys.argv[1]), sys.argv[2]
kin, state = {}, {"n": 0, "match": 0, "body_diff": 0.0, "first": None, "last": None,
                  "kin_topology": None, "stats": None}


def on_kin(m):
    kin[m.header.stamp.to_nsec()] = np.asarray(m.positions, dtype=np.float64).reshape(-1, 3)
    state["kin_topology"] = m.topology_id
    state["kin_nvert"] = len(m.positions) // 3
    while len(kin) > 200:
        del kin[min(kin)]


def on_skin(m):
    p = np.asarray(m.positions, dtype=np.float64).reshape(-1, 3)
    state["n"] += 1
    k = kin.get(m.header.stamp.to_nsec())
    if k is not None and k.shape == p.shape:
        state["match"] += 1
        state["body_diff"] = max(state["body_diff"], float(np.abs(k - p).max()))
    if state["first"] is None:
        state["first"] = (p, m.topology_id)
    state["last"] = (p, m.topology_id)


def on_stats(m):
    state["stats"] = {f: getattr(m, f) for f in m.__slots__ if f != "header"}


rospy.init_node("carry_probe", anonymous=True, disable_signals=True)
rospy.Subscriber("kinematic_mesh", SkinMesh, on_kin, queue_size=50)
rospy.Subscriber("skin_mesh", SkinMesh, on_skin, queue_size=50)
rospy.Subscriber("skin_stats", SkinStats, on_stats, queue_size=50)
t0 = time.time()
while time.time() - t0 < seconds or (state["n"] < 3 and time.time() - t0 < seconds + 120):
    time.sleep(0.1)
out = {"skin_meshes": state["n"], "matched": state["match"], "body_diff": state["body_diff"],
       "kin_topology": state["kin_topology"], "kin_nvert": state.get("kin_nvert", 0),
       "stats": state["stats"]}
if state["first"] is not None:
    (p0, t0_), (p1, t1_) = state["first"], state["last"]
    d0 = np.linalg.norm(p0 - p0[0], axis=1)
    d1 = np.linalg.norm(p1 - p1[0], axis=1)
    out.update({"nvert": len(p1), "topology": t1_, "rigid_change": float(np.abs(d1 - d0).max()),
                "moved": float(np.linalg.norm(p1 - p0, axis=1).max()),
                "finite": bool(np.isfinite(p1).all())})
with open(out_path, "w") as f:
    json.dump(out, f)
print(json.dumps(out))
sys.exit(0 if state["n"] else 1)
