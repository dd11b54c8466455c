#!/usr/bin/python3
"""Drives avatar_node + skin_sim_node with joint_states and measures the skin's seams,
for test_skin_seams.sh (no mocks: real nodes, real master).

  seam_probe.py URDF SECONDS OUT_JSON [RATE_HZ]

Publishes joint_states at RATE_HZ (default 30) for SECONDS (and on, at most 180 s more,
until 3 skin_mesh came): every movable joint of URDF
swings through most of its range (sinusoids, a phase per joint, 1 Hz). Subscribes
kinematic_mesh and skin_mesh. Seam copies are the vertices of the first kinematic_mesh
at bit-identical positions (what the node welds at its default ~weld_tol); for every
skin_mesh it measures the largest distance between two copies of one welded vertex (the
seam gap, 0 when no seam opened), the number of seams open by more than 1 mm, and
whether every value is finite and the layout (vertex count, triangles, topology_id) is
the body's. skin_marker must be a TRIANGLE_LIST over the body's triangles whose corners of
one welded vertex share one point and one colour. At the end: skin pieces = connected components of the last skin_mesh with
its vertices at bit-identical positions joined (the pieces of skin as a user sees them),
and of the body's own index graph. Writes OUT_JSON and prints it, and OUT_JSON.npz: the skin_mesh with the widest seam gap
(pos, tri, copies, rep) for a picture. Exit 0 if it could
measure (skin_mesh received), 1 otherwise; the test judges the figures."""
import json
import math
import sys
import threading
import time
import xml.etree.ElementTree as ET

import numpy as np
import rospy
from sensor_msgs.msg import JointState
from skin_sim.msg import SkinMesh
from visualization_msgs.msg import Marker

urdf, seconds, out_path = sys.argv[1], float(sys.argv[2]), sys.argv[3]
rate_hz = float(sys.argv[4]) if len(sys.argv) > 4 else 30.0

joints = []
for j in ET.parse(urdf).getroot().iter("joint"):
    if j.get("type") not in ("revolute", "continuous", "prismatic"):
        continue
    lim = j.find("limit")
    lo, hi = -1.0, 1.0
    if lim is not None and j.get("type") != "continuous":
        lo, hi = float(lim.get("lower", lo)), float(lim.get("upper", hi))
    if j.get("type") == "prismatic" and lim is None:
        lo, hi = -0.05, 0.05
    if not hi > lo:
        continue
    if hi - lo > 2.0:  # a wide range: +-1 rad around its middle
        mid = 0.5 * (lo + hi)
        lo, hi = mid - 1.0, mid + 1.0
    joints.append((j.get("name"), lo, hi))


def components(nvert, tri, ident):
    """Connected components of triangles over vertex ids ident[v]."""
    parent = np.arange(nvert)

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    t = ident[tri.reshape(-1, 3)]
    for a, b, c in t:
        ra, rb, rc = find(a), find(b), find(c)
        r = min(ra, rb, rc)
        parent[ra] = parent[rb] = parent[rc] = r
    used = np.unique(t)
    return len({find(v) for v in used})


def same_position_ids(pos):
    """For each vertex the smallest vertex at the bit-identical position."""
    keys = np.ascontiguousarray(pos).view(np.dtype((np.void, 12))).ravel()
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    return first[inverse]


st = {"kin": None, "n_kin": 0, "n_skin": 0, "max_gap": 0.0, "max_open_1mm": 0,
      "nonfinite": 0, "bad_layout": 0, "last": None, "gaps": [], "markers": 0, "markers_ok": 0,
      "worst": None}


lock = threading.Lock()


def on_marker(m):
    """skin_marker: a TRIANGLE_LIST over the body's triangles, a colour per corner,
    corners of one welded vertex at one point with one colour."""
    k = st["kin"]
    if k is None:
        return
    pts = np.array([(p.x, p.y, p.z) for p in m.points])
    col = np.array([(c.r, c.g, c.b, c.a) for c in m.colors])
    why = None
    if m.type != Marker.TRIANGLE_LIST:
        why = "type %d" % m.type
    elif len(pts) != len(k["tri"]) or len(col) != len(pts):
        why = "%d points, %d colours for %d corners" % (len(pts), len(col), len(k["tri"]))
    elif not np.all(np.isfinite(pts)):
        why = "non-finite points"
    elif not np.all((col >= 0) & (col <= 1)):
        why = "colours outside [0, 1]: %g .. %g" % (col.min(), col.max())
    else:
        w = k["rep"][k["tri"]]  # welded vertex of each corner
        order = np.argsort(w, kind="stable")
        ws, ps, cs = w[order], pts[order], col[order]
        same = ws[1:] == ws[:-1]
        if not np.all(ps[1:][same] == ps[:-1][same]):
            why = "corners of one welded vertex at different points"
        elif not np.all(cs[1:][same] == cs[:-1][same]):
            why = "corners of one welded vertex in different colours"
    # counted when judged (a big marker takes a while in Python: the summary must not
    # count one whose judgement is still under way)
    with lock:
        if why is None:
            st["markers_ok"] += 1
        else:
            st["marker_why"] = why
        st["markers"] += 1


def on_kin(m):
    st["n_kin"] += 1
    if st["kin"] is None:
        pos = np.array(m.positions, dtype=np.float32).reshape(-1, 3)
        tri = np.array(m.triangles, dtype=np.int64)
        rep = same_position_ids(pos)
        copies = np.nonzero(rep != np.arange(len(rep)))[0]
        st["kin"] = {"nvert": len(pos), "tri": tri, "topo": m.topology_id, "rep": rep,
                     "copies": copies, "raw": tri.copy()}


def on_skin(m):
    k = st["kin"]
    if k is None:
        return
    st["n_skin"] += 1
    pos = np.array(m.positions, dtype=np.float64).reshape(-1, 3)
    if (len(pos) != k["nvert"] or m.topology_id != k["topo"] or
            not np.array_equal(np.array(m.triangles, dtype=np.int64), k["tri"])):
        st["bad_layout"] += 1
        return
    if not np.all(np.isfinite(pos)):
        st["nonfinite"] += 1
        return
    c = k["copies"]
    gap = np.linalg.norm(pos[c] - pos[k["rep"][c]], axis=1) if len(c) else np.zeros(1)
    g = float(gap.max())
    st["gaps"].append(g)
    if g > st["max_gap"] or st["worst"] is None:
        st["worst"] = pos.astype(np.float32)
    st["max_gap"] = max(st["max_gap"], g)
    st["max_open_1mm"] = max(st["max_open_1mm"], int((gap > 1e-3).sum()))
    st["last"] = pos.astype(np.float32)


rospy.init_node("seam_probe", anonymous=True, disable_signals=True)
pub = rospy.Publisher("joint_states", JointState, queue_size=10)
rospy.Subscriber("kinematic_mesh", SkinMesh, on_kin, queue_size=5)
subs = [rospy.Subscriber("skin_mesh", SkinMesh, on_skin, queue_size=5),
        rospy.Subscriber("skin_marker", Marker, on_marker, queue_size=2)]
deadline = time.monotonic() + 60.0
while pub.get_num_connections() == 0 and time.monotonic() < deadline:
    time.sleep(0.05)
# the first pose (rest) until the skin exists
t_start = time.monotonic()
while st["n_skin"] == 0 and time.monotonic() < deadline:
    js = JointState()
    js.header.stamp = rospy.Time.now()
    js.name = [j[0] for j in joints]
    js.position = [0.5 * (lo + hi) for _, lo, hi in joints]
    pub.publish(js)
    time.sleep(1.0 / rate_hz)
t0 = time.monotonic()
n_sent = 0
# at least SECONDS, and on until MIN_SKIN skin_mesh came (a slow machine, a big robot),
# at most 180 s more
MIN_SKIN = 3
while time.monotonic() - t0 < seconds or (st["n_skin"] < MIN_SKIN and time.monotonic() - t0 < seconds + 180):
    t = time.monotonic() - t0
    js = JointState()
    js.header.stamp = rospy.Time.now()
    js.name = [j[0] for j in joints]
    js.position = [0.5 * (lo + hi) + 0.45 * (hi - lo) * math.sin(2 * math.pi * t + 0.7 * i)
                   for i, (_, lo, hi) in enumerate(joints)]
    pub.publish(js)
    n_sent += 1
    time.sleep(max(0.0, t0 + n_sent / rate_hz - time.monotonic()))
time.sleep(2.0)
for sub in subs:
    sub.unregister()
time.sleep(1.0)  # callbacks under way finish

k = st["kin"]
res = {"urdf": urdf, "joints": len(joints), "joint_states": n_sent,
       "kinematic_mesh": st["n_kin"], "skin_mesh": st["n_skin"], "max_gap_m": st["max_gap"],
       "max_seams_open_1mm": st["max_open_1mm"], "nonfinite_skin_mesh": st["nonfinite"],
       "bad_layout_skin_mesh": st["bad_layout"]}
with lock:
    res.update({"skin_marker": st["markers"], "skin_marker_ok": st["markers_ok"],
                "skin_marker_bad": st.get("marker_why", "")})
if k is not None:
    res["vertices"] = k["nvert"]
    res["triangles"] = len(k["tri"]) // 3
    res["seam_copies"] = int(len(k["copies"]))
    res["welded_vertices"] = int(len(np.unique(k["rep"])))
    res["pieces_body_indices"] = components(k["nvert"], k["tri"], np.arange(k["nvert"]))
    res["pieces_body_welded"] = components(k["nvert"], k["tri"], k["rep"])
    if st["last"] is not None:
        res["pieces_skin_last"] = components(k["nvert"], k["tri"], same_position_ids(st["last"]))
    if st["gaps"]:
        g = sorted(st["gaps"])
        res["median_gap_m"] = g[len(g) // 2]
if k is not None and st["worst"] is not None:  # the skin_mesh of the widest seam gap
    np.savez_compressed(out_path + ".npz", pos=st["worst"], tri=k["tri"].reshape(-1, 3),
                        copies=k["copies"], rep=k["rep"])
with open(out_path, "w") as f:
    json.dump(res, f, indent=1)
print(json.dumps(res))
rospy.signal_shutdown("done")
sys.exit(0 if st["n_skin"] > 0 else 1)
