#!/usr/bin/python3
"""Compares the skin_mesh streams of two bags byte for byte (tests/ros/test_rosbag_roundtrip.sh).

usage: bag_compare.py INPUT_BAG REPLAY_A REPLAY_B

Every skin_mesh message is compared in its serialized form except the first four
bytes, header.seq, which roscpp rewrites on every publish: stamp, frame_id,
topology_id, every position and every triangle must be identical. Also checks that
each replay has one skin_mesh per kinematic_mesh of INPUT_BAG, with its stamp.
Prints one line per finding; exit 0 when identical.
"""
import sys

import rosbag


def raw_stream(path, topic):
    out = []
    with rosbag.Bag(path) as bag:
        for t, msg, _ in bag.read_messages(raw=True):
            if t.lstrip("/") == topic:
                out.append(bytes(msg[1]))
    return out


def stamps(stream):
    # header: uint32 seq, uint32 sec, uint32 nsec
    return [s[4:12] for s in stream]


def main():
    inp, a_path, b_path = sys.argv[1:4]
    kin = raw_stream(inp, "kinematic_mesh")
    a = raw_stream(a_path, "skin_mesh")
    b = raw_stream(b_path, "skin_mesh")
    ok = True
    print("input: %d kinematic_mesh; replay A: %d skin_mesh (%d bytes each); replay B: %d skin_mesh"
          % (len(kin), len(a), len(a[0]) if a else 0, len(b)))
    for name, s in (("A", a), ("B", b)):
        if stamps(s) != stamps(kin):
            got = set(stamps(s))
            missing = [i for i, k in enumerate(stamps(kin)) if k not in got]
            print("replay %s: skin_mesh stamps are not those of the kinematic meshes "
                  "(missing input messages %s)" % (name, missing[:20]))
            ok = False
    if len(a) != len(b):
        print("different message counts")
        ok = False
    diff = [i for i, (x, y) in enumerate(zip(a, b)) if x[4:] != y[4:]]
    if diff:
        print("%d skin_mesh differ; first at message %d" % (len(diff), diff[0]))
        ok = False
    if ok:
        print("identical: %d skin_mesh, %d bytes compared (all but header.seq)"
              % (len(a), sum(len(x) - 4 for x in a)))
    return 0 if ok and a else 1


if __name__ == "__main__":
    sys.exit(main())
