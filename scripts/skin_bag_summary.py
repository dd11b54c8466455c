#!/usr/bin/python3
"""Summarises a bag recorded from the skin nodes (scripts/demo.sh, record.launch).

usage: skin_bag_summary.py BAG

Prints frames in (kinematic_mesh), frames out (skin_mesh), how many skin_mesh
stamps match a kinematic_mesh stamp, ms per frame from skin_stats (median and
95th percentile of total_ms), the last counters (rejected, dropped, skipped, resets),
and the end-to-end latency: the time the recorder received each skin_mesh
minus its header stamp (the joint state's stamp), median and 95th percentile.
Needs Debian's python3 with python3-rosbag and the package's generated
messages on PYTHONPATH (source devel/setup.bash).
"""
import sys

import rosbag


def pct(values, p):
    if not values:
        return float("nan")
    v = sorted(values)
    k = min(len(v) - 1, max(0, int(round(p / 100.0 * (len(v) - 1)))))
    return v[k]


def main():
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    path = sys.argv[1]
    kin, skin, total, lat = [], [], [], []
    last = None
    with rosbag.Bag(path) as bag:
        for topic, msg, t in bag.read_messages():
            name = topic.lstrip("/")
            if name == "kinematic_mesh":
                kin.append(msg.header.stamp.to_nsec())
            elif name == "skin_mesh":
                skin.append(msg.header.stamp.to_nsec())
                lat.append((t.to_nsec() - msg.header.stamp.to_nsec()) / 1e6)
            elif name == "skin_stats":
                total.append(msg.total_ms)
                last = msg
    kin_set = set(kin)
    # the recorder may subscribe after the first meshes went by: judge from the first
    # recorded kinematic_mesh on
    since = [s for s in skin if kin and s >= min(kin)]
    matched = sum(1 for s in since if s in kin_set)
    print("bag:              %s" % path)
    print("frames in:        %d kinematic_mesh" % len(kin))
    print("frames out:       %d skin_mesh (%d of the %d since the first recorded kinematic_mesh carry "
          "the stamp of one)" % (len(skin), matched, len(since)))
    print("ms per frame:     median %.2f, 95th percentile %.2f (skin_stats total_ms, %d steps)"
          % (pct(total, 50), pct(total, 95), len(total)))
    print("latency:          median %.1f ms, 95th percentile %.1f ms (joint state stamp to skin_mesh at the recorder)"
          % (pct(lat, 50), pct(lat, 95)))
    if last is not None:
        # skipped: received while the node was busy and never stepped (it stepped a
        # newer one): frames in without a frame out, that dropped (lost before the
        # node) does not count
        print("inputs rejected:  %d, dropped: %d, skipped: %d, resets: %d; last step: %d iterations, "
              "residual %.2g, max slide %.1f mm, %d anchors stopped at creases"
              % (last.inputs_rejected, last.inputs_dropped, last.inputs_skipped, last.resets,
                 last.iterations, last.residual, 1e3 * last.max_slide, last.anchors_at_crease))
    return 0 if skin else 1


if __name__ == "__main__":
    sys.exit(main())
