#!/usr/bin/env python3
"""skin_rviz.py: rviz on a URDF robot and its skin, the fixed frame at the robot's root link.

    skin_rviz.py --urdf FILE --config FILE [--frame-prefix PREFIX] [--fit] [--print] [rviz args...]

Reads the URDF, finds its root link (the one link that is no joint's child) and starts
rviz with a copy of the rviz config whose fixed frame is PREFIX/ROOT (ROOT without a
prefix) and whose RobotModel display takes PREFIX as its TF prefix. With --fit the view
is fitted to the robot's skeleton (its link origins at the zero pose): the camera looks at
their middle from three times their extent, the grid lies at their lowest point, its cells
a quarter of the extent. The copy is written
to $ROS_HOME/skin_sim/NODE.rviz (ROS_HOME defaults to ~/.ros; NODE is the node's name,
from roslaunch's __name:=, else "rviz"), overwritten at each start. Arguments it does
not know (roslaunch's __name:= and __log:=, remappings) go to rviz.
--print prints the fixed frame and the config's path and exits (no rviz).
Used by launch/robot.launch and launch/demo.launch.
"""
import argparse
import math
import os
import re
import sys
import xml.etree.ElementTree as ET


def root_link(urdf_path):
    """The URDF's root link: the one link that is no joint's child."""
    robot = ET.parse(urdf_path).getroot()
    links = [l.get("name") for l in robot.findall("link")]
    children = {c.get("link") for j in robot.findall("joint") for c in j.findall("child")}
    roots = [l for l in links if l not in children]
    if len(roots) != 1:
        raise ValueError("%s: %d root links (%s); a URDF has exactly one"
                         % (urdf_path, len(roots), ", ".join(roots) or "none"))
    return roots[0]


def rpy_matrix(r, p, y):
    """URDF's fixed-axis roll, pitch, yaw as a rotation matrix (Rz Ry Rx)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def link_origins(urdf_path, root):
    """Every link's origin in the root link's frame, all joints at zero."""
    robot = ET.parse(urdf_path).getroot()
    kids = {}
    for j in robot.findall("joint"):
        o = j.find("origin")
        xyz = [float(t) for t in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
        rpy = [float(t) for t in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
        kids.setdefault(j.find("parent").get("link"), []).append((j.find("child").get("link"), xyz, rpy))
    out, todo = [], [(root, [0.0, 0.0, 0.0], [[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]])]
    while todo:
        link, p, rot = todo.pop()
        out.append(p)
        for child, xyz, rpy in kids.get(link, []):
            d = [sum(rot[i][k] * xyz[k] for k in range(3)) for i in range(3)]
            r2 = rpy_matrix(*rpy)
            rot2 = [[sum(rot[i][k] * r2[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
            todo.append((child, [p[i] + d[i] for i in range(3)], rot2))
    return out


def fit_view(text, pts):
    """The config's orbit view and grid fitted to the points."""
    lo = [min(p[i] for p in pts) for i in range(3)]
    hi = [max(p[i] for p in pts) for i in range(3)]
    ext = max(max(math.dist(a, b) for a in pts for b in pts), 0.1)
    mid = [(lo[i] + hi[i]) / 2 for i in range(3)]
    cell = float("%.1g" % (ext / 4))

    text = re.sub(r"(?m)^(\s*Distance:) .*$", lambda m: "%s %.3g" % (m.group(1), 3 * ext), text, count=1)
    text = re.sub(r"(?m)^(\s*Cell Size:) .*$", lambda m: "%s %g" % (m.group(1), cell), text, count=1)
    for key, val in (("Focal Point", mid), ("Offset", [0.0, 0.0, lo[2]])):
        m = re.search(r"(?m)^(\s*)%s:\n\s*X: .*\n\s*Y: .*\n\s*Z: .*$" % key, text)
        if m:
            ind = m.group(1) + "  "
            text = text[:m.start()] + "%s%s:\n%sX: %.3g\n%sY: %.3g\n%sZ: %.3g" % (
                m.group(1), key, ind, val[0], ind, val[1], ind, val[2]) + text[m.end():]
    return text


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--urdf", required=True, help="the robot's URDF file")
    ap.add_argument("--config", required=True, help="rviz config to start from")
    ap.add_argument("--frame-prefix", default="", help="tf prefix: frames are PREFIX/link")
    ap.add_argument("--fit", action="store_true", help="fit the view and grid to the robot")
    ap.add_argument("--print", action="store_true", help="print the fixed frame and exit")
    opts, rest = ap.parse_known_args(argv)
    try:
        root = root_link(opts.urdf)
    except (OSError, ET.ParseError, ValueError) as e:
        sys.stderr.write("skin_rviz.py: cannot read the URDF's root link: %s\n" % e)
        return 2
    prefix = opts.frame_prefix.strip("/")
    fixed = prefix + "/" + root if prefix else root
    node = "rviz"
    for a in rest:
        if a.startswith("__name:="):
            node = a.split(":=", 1)[1]
    home = os.environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
    out = os.path.join(home, "skin_sim", node + ".rviz")
    with open(opts.config) as f:
        text = f.read()
    text = re.sub(r"(?m)^(\s*Fixed Frame:).*$", lambda m: m.group(1) + " " + fixed, text)
    text = re.sub(r"(?m)^(\s*TF Prefix:).*$", lambda m: m.group(1) + ' "%s"' % prefix, text)
    if opts.fit:
        text = fit_view(text, link_origins(opts.urdf, root))
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out, "w") as f:
        f.write(text)
    if opts.print:
        print("fixed frame: %s\nconfig: %s" % (fixed, out))
        return 0
    sys.stdout.flush()
    os.execvp("rviz", ["rviz", "-d", out] + rest)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
