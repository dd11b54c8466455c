#!/usr/bin/python3
"""Writes test robots for bench/ros_realtime.sh: URDFs whose links wear
separate OBJ meshes, as real robots' visual meshes come.

usage: make_robot.py quadruped|pieces OUT_DIR

quadruped: a four-legged robot built like the Solo (base, hips, upper and lower
    legs, feet: 17 links, 16 revolute joints), about 15,000 triangles in 51
    pieces: each link a smooth shell plus a few screws and covers.
pieces: a humanoid of 19 links whose meshes come in many pieces, as exported
    CAD does: each link a shell plus 70 small parts (covers of 12
    triangles, screws of 4, knobs of 48), about 50,000 triangles in over 1,300
    pieces, some of only four vertices.

Writes OUT_DIR/robot.urdf and OUT_DIR/meshes/LINK.obj (file:// paths, no
package needed). Deterministic: the same files every time.
"""
import math
import os
import random
import sys


def ellipsoid(c, r, nu, nv):
    """A closed ellipsoid of 2 nu (nv - 1) triangles centred at c, radii r."""
    v, f = [], []
    v.append((c[0], c[1], c[2] - r[2]))
    for j in range(1, nv):
        th = math.pi * j / nv
        for i in range(nu):
            ph = 2 * math.pi * i / nu
            v.append((c[0] + r[0] * math.sin(th) * math.cos(ph),
                      c[1] + r[1] * math.sin(th) * math.sin(ph),
                      c[2] - r[2] * math.cos(th)))
    v.append((c[0], c[1], c[2] + r[2]))
    top = len(v) - 1
    ring = lambda j, i: 1 + (j - 1) * nu + (i % nu)
    for i in range(nu):
        f.append((0, ring(1, i + 1), ring(1, i)))
    for j in range(1, nv - 1):
        for i in range(nu):
            a, b, cc, d = ring(j, i), ring(j, i + 1), ring(j + 1, i), ring(j + 1, i + 1)
            f.append((a, b, d))
            f.append((a, d, cc))
    for i in range(nu):
        f.append((ring(nv - 1, i), ring(nv - 1, i + 1), top))
    return v, f


def box(c, s):
    """A closed box (8 vertices, 12 triangles), centre c, half sizes s."""
    v = [(c[0] + sx * s[0], c[1] + sy * s[1], c[2] + sz * s[2])
         for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    f = []
    for a, b, cc, d in quads:
        f.append((a, b, cc))
        f.append((a, cc, d))
    return v, f


def tetra(c, s):
    """A screw head: a tetrahedron of 4 vertices, 4 triangles."""
    v = [(c[0] + s, c[1] + s, c[2] + s), (c[0] + s, c[1] - s, c[2] - s),
         (c[0] - s, c[1] + s, c[2] - s), (c[0] - s, c[1] - s, c[2] + s)]
    return v, [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)]


class Mesh:
    def __init__(self):
        self.v, self.f, self.pieces = [], [], 0

    def add(self, part):
        v, f = part
        o = len(self.v)
        self.v.extend(v)
        self.f.extend((a + o, b + o, c + o) for a, b, c in f)
        self.pieces += 1

    def write(self, path):
        with open(path, "w") as out:
            out.write("# written by bench/make_robot.py\n")
            for p in self.v:
                out.write("v %.6f %.6f %.6f\n" % p)
            for a, b, c in self.f:
                out.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


def on_surface(rng, c, r, lift):
    """A point just outside ellipsoid (c, r), lifted by lift."""
    th, ph = math.acos(2 * rng.random() - 1), 2 * math.pi * rng.random()
    n = (math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th))
    return tuple(c[k] + (r[k] + lift) * n[k] for k in range(3))


def shell_with_parts(rng, c, r, nu, nv, ncover, nscrew, nknob):
    m = Mesh()
    m.add(ellipsoid(c, r, nu, nv))
    size = min(r)
    for _ in range(ncover):
        m.add(box(on_surface(rng, c, r, 0.12 * size), (0.08 * size, 0.06 * size, 0.03 * size)))
    for _ in range(nscrew):
        m.add(tetra(on_surface(rng, c, r, 0.1 * size), 0.03 * size))
    for _ in range(nknob):
        m.add(ellipsoid(on_surface(rng, c, r, 0.15 * size), (0.05 * size,) * 3, 8, 4))
    return m


def urdf(name, links, joints, mesh_dir):
    out = ['<?xml version="1.0"?>', '<robot name="%s">' % name]
    for ln in links:
        out.append('  <link name="%s"><visual><geometry><mesh filename="file://%s/%s.obj"/>'
                   '</geometry></visual></link>' % (ln, mesh_dir, ln))
    for jn, parent, child, xyz, axis in joints:
        out.append('  <joint name="%s" type="revolute"><parent link="%s"/><child link="%s"/>'
                   '<origin xyz="%g %g %g"/><axis xyz="%g %g %g"/>'
                   '<limit lower="-1.5" upper="1.5" effort="10" velocity="10"/></joint>'
                   % ((jn, parent, child) + xyz + axis))
    out.append('</robot>')
    return "\n".join(out) + "\n"


def quadruped(rng):
    meshes, joints = {}, []
    meshes["base_link"] = shell_with_parts(rng, (0, 0, 0), (0.22, 0.1, 0.05), 64, 33, 2, 4, 0)
    for side, (sx, sy) in {"FL": (1, 1), "FR": (1, -1), "HL": (-1, 1), "HR": (-1, -1)}.items():
        hip, up, low, foot = side + "_HIP", side + "_UPPER_LEG", side + "_LOWER_LEG", side + "_FOOT"
        meshes[hip] = shell_with_parts(rng, (0, 0.03 * sy, 0), (0.04, 0.03, 0.04), 24, 13, 1, 3, 0)
        meshes[up] = shell_with_parts(rng, (0, 0, -0.08), (0.025, 0.02, 0.09), 32, 19, 0, 2, 0)
        meshes[low] = shell_with_parts(rng, (0, 0, -0.08), (0.015, 0.015, 0.09), 24, 17, 0, 1, 0)
        meshes[foot] = shell_with_parts(rng, (0, 0, 0), (0.02, 0.02, 0.02), 16, 9, 0, 0, 0)
        joints.append((side + "_HAA", "base_link", hip, (0.19 * sx, 0.1 * sy, 0), (1, 0, 0)))
        joints.append((side + "_HFE", hip, up, (0, 0.06 * sy, 0), (0, 1, 0)))
        joints.append((side + "_KFE", up, low, (0, 0, -0.16), (0, 1, 0)))
        joints.append((side + "_ANKLE", low, foot, (0, 0, -0.17), (0, 1, 0)))
    return meshes, joints


def pieces(rng):
    meshes, joints = {}, []
    def link(name, c, r, nu, nv):
        meshes[name] = shell_with_parts(rng, c, r, nu, nv, 25, 25, 20)
    link("pelvis", (0, 0, 0), (0.15, 0.1, 0.08), 48, 25)
    link("torso", (0, 0, 0.2), (0.16, 0.11, 0.2), 64, 33)
    link("head", (0, 0, 0.1), (0.09, 0.08, 0.11), 48, 25)
    joints.append(("torso_twist", "pelvis", "torso", (0, 0, 0.08), (0, 0, 1)))
    joints.append(("neck", "torso", "head", (0, 0, 0.42), (0, 1, 0)))
    for side, s in (("l", 1), ("r", -1)):
        link(side + "_shoulder", (0, 0, 0), (0.05, 0.05, 0.05), 24, 13)
        link(side + "_upper_arm", (0, 0.14 * s, 0), (0.04, 0.14, 0.04), 32, 17)
        link(side + "_forearm", (0, 0.12 * s, 0), (0.035, 0.12, 0.035), 32, 17)
        link(side + "_hand", (0, 0.05 * s, 0), (0.03, 0.05, 0.015), 24, 13)
        link(side + "_hip", (0, 0, 0), (0.06, 0.06, 0.06), 24, 13)
        link(side + "_thigh", (0, 0, -0.2), (0.06, 0.06, 0.2), 40, 21)
        link(side + "_shin", (0, 0, -0.2), (0.05, 0.05, 0.2), 40, 21)
        link(side + "_foot", (0.05, 0, -0.03), (0.1, 0.045, 0.03), 32, 17)
        joints.append((side + "_shoulder_pitch", "torso", side + "_shoulder", (0, 0.2 * s, 0.35), (0, 1, 0)))
        joints.append((side + "_shoulder_roll", side + "_shoulder", side + "_upper_arm", (0, 0.04 * s, 0), (1, 0, 0)))
        joints.append((side + "_elbow", side + "_upper_arm", side + "_forearm", (0, 0.29 * s, 0), (0, 0, 1)))
        joints.append((side + "_wrist", side + "_forearm", side + "_hand", (0, 0.25 * s, 0), (1, 0, 0)))
        joints.append((side + "_hip_pitch", "pelvis", side + "_hip", (0, 0.1 * s, -0.1), (0, 1, 0)))
        joints.append((side + "_hip_roll", side + "_hip", side + "_thigh", (0, 0, -0.04), (1, 0, 0)))
        joints.append((side + "_knee", side + "_thigh", side + "_shin", (0, 0, -0.42), (0, 1, 0)))
        joints.append((side + "_ankle", side + "_shin", side + "_foot", (0, 0, -0.42), (0, 1, 0)))
    return meshes, joints


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("quadruped", "pieces"):
        sys.stderr.write(__doc__)
        return 2
    kind, out = sys.argv[1], os.path.abspath(sys.argv[2])
    rng = random.Random(1)
    meshes, joints = quadruped(rng) if kind == "quadruped" else pieces(rng)
    os.makedirs(os.path.join(out, "meshes"), exist_ok=True)
    for name, m in meshes.items():
        m.write(os.path.join(out, "meshes", name + ".obj"))
    with open(os.path.join(out, "robot.urdf"), "w") as f:
        f.write(urdf(kind, list(meshes), joints, os.path.join(out, "meshes")))
    ntri = sum(len(m.f) for m in meshes.values())
    npiece = sum(m.pieces for m in meshes.values())
    print("make_robot: %s: %d links, %d joints, %d triangles in %d pieces -> %s/robot.urdf"
          % (kind, len(meshes), len(joints), ntri, npiece, out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
