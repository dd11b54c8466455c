#!/usr/bin/python3
"""Sends skin_sim_node SkinMesh messages as raw bytes (rospy, not rosc) for
test_skin_sizes.sh, and reads the node's memory from /proc/PID/status between them.
MODE lie:
  1. a good mesh (an octahedron), answered on skin_mesh: VmRSS and VmHWM before;
  2. the 56-byte SkinMesh whose positions claim 0x40000002 floats (roscpp's own
     deserialiser allocates 4 GiB for it), then a good mesh: answered; VmHWM after;
  3. a large message of valid sizes (LARGE_MB, default 72: 2M vertices and 4M
     triangles, the default ~max_vertices and ~max_triangles) whose triangles name a
     vertex beyond the last (the node rejects it once it has read it), then a good
     mesh: answered; VmRSS after.
MODE limit: 1, then the large message (the node runs with a smaller ~max_vertices:
refused unread), then a good mesh: answered; VmHWM after.
Prints one line `figures KEY=VALUE ...` (kB, counts: rejectedN is skin_stats'
inputs_rejected after step N) for the test to judge; exits non-zero only if the node
stopped answering. Usage: raw_mesh.py NODE_PID MODE [LARGE_MB]."""
import os
import struct
import sys
import time

import rospy
from skin_sim.msg import SkinMesh, SkinStats

try:
    import genpy
    Base = genpy.Message
except ImportError:  # rospy's own name for it
    Base = rospy.Message


class Raw(Base):
    """A SkinMesh on the wire (type and MD5 of skin_sim/SkinMesh) whose bytes are given."""
    _type = SkinMesh._type
    _md5sum = SkinMesh._md5sum
    _full_text = SkinMesh._full_text
    _has_header = False
    __slots__ = ["data"]

    def __init__(self, data=b""):
        self.data = data

    def serialize(self, buff):
        buff.write(self.data)


def mesh_bytes(stamp_ns, topology_id, positions_bytes, n_pos, triangles_bytes, n_tri, seq=0,
               frame=b"body"):
    return (struct.pack("<IIII", seq, stamp_ns // 10**9, stamp_ns % 10**9, len(frame)) + frame +
            struct.pack("<I", topology_id) + struct.pack("<I", n_pos) + positions_bytes +
            struct.pack("<I", n_tri) + triangles_bytes + struct.pack("<I", 0))


OCTA_P = [0, 0, 0.1, 0.1, 0, 0, 0, 0.1, 0, -0.1, 0, 0, 0, -0.1, 0, 0, 0, -0.1]
OCTA_T = [0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1, 5, 2, 1, 5, 3, 2, 5, 4, 3, 5, 1, 4]


def octa(stamp_ns):
    return mesh_bytes(stamp_ns, 7, struct.pack("<18f", *OCTA_P), 18, struct.pack("<24I", *OCTA_T), 24)


def status(pid):
    out = {}
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            k, _, v = line.partition(":")
            if k in ("VmRSS", "VmHWM"):
                out[k] = int(v.split()[0])
    return out


pid = int(sys.argv[1])
mode = sys.argv[2]
large_mb = int(sys.argv[3]) if len(sys.argv) > 3 else 72
rospy.init_node("raw_mesh", anonymous=True, disable_signals=True)
answers = []
stats = []
rospy.Subscriber("skin_mesh", SkinMesh, lambda m: answers.append(m.header.stamp.to_nsec()))
rospy.Subscriber("skin_stats", SkinStats, lambda m: stats.append(m.inputs_rejected))
pub = rospy.Publisher("kinematic_mesh", Raw, queue_size=10)
deadline = time.monotonic() + 60.0
while pub.get_num_connections() == 0:
    if time.monotonic() > deadline:
        sys.exit("raw_mesh: no subscriber on kinematic_mesh within 60 s")
    time.sleep(0.02)
time.sleep(1.0)  # the skin_mesh and skin_stats subscriptions connect too


def answered(stamp_ns, what, timeout=120.0):
    """Sends the octahedron at stamp_ns until the node answers it (a bounded wait)."""
    end = time.monotonic() + timeout
    last = 0.0
    while stamp_ns not in answers:
        if time.monotonic() > end:
            sys.exit("raw_mesh: no skin_mesh for the good mesh after %s within %g s" % (what, timeout))
        if time.monotonic() - last > 5.0:  # a first send may meet a connection still settling
            pub.publish(Raw(octa(stamp_ns)))
            last = time.monotonic()
        time.sleep(0.02)
    time.sleep(0.5)  # its skin_stats too


fig = {}
answered(1 * 10**9, "start")
fig.update({"rss0": status(pid)["VmRSS"], "hwm0": status(pid)["VmHWM"]})


def send_large(stamp_ns, after_ns):
    """A large message of valid sizes the node rejects once read (a triangle names
    vertex nv), then the good mesh until answered."""
    nv = (large_mb * 10**6) // 36
    nt = 2 * nv
    tri = struct.pack("<3I", 0, 1, nv) + bytes(12 * (nt - 1))
    big = mesh_bytes(stamp_ns, 7, bytes(12 * nv), 3 * nv, tri, 3 * nt, seq=2)
    fig["large_bytes"] = len(big)
    del tri
    t = time.monotonic()
    pub.publish(Raw(big))
    del big
    time.sleep(0.5)
    answered(after_ns, "the large message")
    fig["large_ms"] = int(1e3 * (time.monotonic() - t))  # reported, never judged
    time.sleep(1.0)


if mode == "lie":
    # 2. the 56-byte lie: positions claim 0x40000002 floats; 8 bytes follow
    lie = mesh_bytes(1100 * 10**6, 7, bytes(8), 0x40000002, b"", 0, seq=1, frame=b"kinematic_body_0")
    fig["lie_bytes"] = len(lie)
    t = time.monotonic()
    pub.publish(Raw(lie))
    time.sleep(0.5)
    answered(1200 * 10**6, "the 56-byte message")
    fig["lie_ms"] = int(1e3 * (time.monotonic() - t))  # reported, never judged
    fig.update({"hwm1": status(pid)["VmHWM"], "rss1": status(pid)["VmRSS"],
                "rejected1": stats[-1] if stats else -1})
    # 3. a large message of valid sizes, read and rejected; memory handed back
    send_large(1300 * 10**6, 1400 * 10**6)
    fig.update({"rss2": status(pid)["VmRSS"], "hwm2": status(pid)["VmHWM"],
                "rejected2": stats[-1] if stats else -1})
else:
    send_large(1300 * 10**6, 1400 * 10**6)
    fig.update({"hwm1": status(pid)["VmHWM"], "rss1": status(pid)["VmRSS"],
                "rejected1": stats[-1] if stats else -1})
print("figures " + " ".join("%s=%s" % kv for kv in sorted(fig.items())), flush=True)
rospy.signal_shutdown("done")
