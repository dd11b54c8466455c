#!/usr/bin/python3
"""Looks at the skin inside the body in frames written by `skinsim run --out DIR`:
the exact generalized winding number of the body around each skin vertex, the
split into clean / buried as the run measures it (src/core/inside.h: buried where
the body face nearest the vertex, or the face it is anchored on (the skin files'
anchor_face), lies inside the body itself, or where the vertex is in front of that
face: inside another part), and a picture. Files without anchor_face (written before
it was) judge by the nearest face alone.

  /usr/bin/python3 bench/inside_view.py DIR FRAME OUT.png [--title T] [--view ELEV,AZIM]

Prints the counts and depths (mean edge lengths of the body at frame 0) and draws the
body (grey) with the skin vertices inside it: clean in red (size by depth), buried
in blue, zoomed on the deepest clean vertex."""
import argparse, struct, sys
import numpy as np


def read_ply(path):
    """Positions, triangles and the vertices' other properties (by name) of a
    binary PLY as skinsim run --out writes it."""
    with open(path, "rb") as f:
        nv = nf = 0
        props = []
        while True:
            line = f.readline().decode().strip()
            if line.startswith("element vertex"): nv = int(line.split()[2])
            elif line.startswith("element face"): nf = int(line.split()[2])
            elif line.startswith("property") and nf == 0: props.append(line.split()[1:3])
            elif line == "end_header": break
        fmt = {"float": "f4", "double": "f8", "int": "i4"}
        dt = np.dtype([(name, "<" + fmt[t]) for t, name in props])
        v = np.frombuffer(f.read(nv * dt.itemsize), dtype=dt)
        extra = {name: v[name].copy() for _, name in props if name not in ("x", "y", "z")}
        v = np.stack([v["x"], v["y"], v["z"]], axis=1).astype(np.float64)
        fdt = np.dtype([("n", "u1"), ("i", "<i4", (3,))])
        fa = np.frombuffer(f.read(nf * fdt.itemsize), dtype=fdt)
        return v, fa["i"].astype(np.int64), extra


def winding(P, V, F, chunk=200):
    A, B, C = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    out = np.empty(len(P))
    for s in range(0, len(P), chunk):
        p = P[s:s + chunk, None, :]
        a, b, c = A[None] - p, B[None] - p, C[None] - p
        la, lb, lc = [np.linalg.norm(x, axis=2) for x in (a, b, c)]
        det = np.einsum("ijk,ijk->ij", a, np.cross(b, c))
        den = la * lb * lc + np.einsum("ijk,ijk->ij", a, b) * lc + \
            np.einsum("ijk,ijk->ij", b, c) * la + np.einsum("ijk,ijk->ij", c, a) * lb
        out[s:s + chunk] = (2 * np.arctan2(det, den)).sum(axis=1) / (4 * np.pi)
    return out


def own(P, V, Fs):
    """Each point's own face's term of `winding` (a point on its plane: 0 or +-1/2 by
    the sign of a rounding error), to take out."""
    return np.array([winding(P[i:i + 1], V, Fs[i:i + 1])[0] for i in range(len(P))])


def closest(P, V, F, chunk=100):
    """Distance and face of the nearest body point (Ericson 5.1.5, vectorised)."""
    A, B, C = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    d_out = np.empty(len(P)); f_out = np.empty(len(P), dtype=np.int64)
    ab, ac = B - A, C - A
    for s in range(0, len(P), chunk):
        p = P[s:s + chunk, None, :]
        ap = p - A[None]
        d1 = np.einsum("jk,ijk->ij", ab, ap); d2 = np.einsum("jk,ijk->ij", ac, ap)
        bp = p - B[None]
        d3 = np.einsum("jk,ijk->ij", ab, bp); d4 = np.einsum("jk,ijk->ij", ac, bp)
        cp = p - C[None]
        d5 = np.einsum("jk,ijk->ij", ab, cp); d6 = np.einsum("jk,ijk->ij", ac, cp)
        va = d3 * d6 - d5 * d4; vb = d5 * d2 - d1 * d6; vc = d1 * d4 - d3 * d2
        with np.errstate(divide="ignore", invalid="ignore"):
            den = va + vb + vc
            v = np.where(den != 0, vb / den, 0.0); w = np.where(den != 0, vc / den, 0.0)
            # regions
            t_ab = np.clip(np.where(d1 - d3 != 0, d1 / (d1 - d3), 0), 0, 1)
            t_ac = np.clip(np.where(d2 - d6 != 0, d2 / (d2 - d6), 0), 0, 1)
            t_bc = np.clip(np.where((d4 - d3) + (d5 - d6) != 0, (d4 - d3) / ((d4 - d3) + (d5 - d6)), 0), 0, 1)
        q = A[None] + v[..., None] * ab[None] + w[..., None] * ac[None]
        e_ab = A[None] + t_ab[..., None] * ab[None]
        e_ac = A[None] + t_ac[..., None] * ac[None]
        e_bc = B[None] + t_bc[..., None] * (C - B)[None]
        inside = (va >= 0) & (vb >= 0) & (vc >= 0) & (den > 0)
        cand = [np.where(inside[..., None], q, np.inf), e_ab, e_ac, e_bc]
        dist = np.min(np.stack([np.linalg.norm(x - p, axis=2) for x in cand]), axis=0)
        dist = np.where(np.isnan(dist), np.inf, dist)
        f_out[s:s + chunk] = np.argmin(dist, axis=1)
        d_out[s:s + chunk] = dist[np.arange(dist.shape[0]), f_out[s:s + chunk]]
    return d_out, f_out


def mean_edge(V, F):
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    e = np.unique(np.sort(e, axis=1), axis=0)
    return np.linalg.norm(V[e[:, 0]] - V[e[:, 1]], axis=1).mean()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir"); ap.add_argument("frame", type=int); ap.add_argument("png")
    ap.add_argument("--title", default=""); ap.add_argument("--view", default="20,-60")
    ap.add_argument("--zoom", type=float, default=8.0, help="half-width of the view in edges")
    a = ap.parse_args()
    V0, F, _ = read_ply("%s/body_%04d.ply" % (a.dir, 1))
    edge = mean_edge(V0, F)
    V, F, _ = read_ply("%s/body_%04d.ply" % (a.dir, a.frame))
    X, SF, skin_props = read_ply("%s/skin_%04d.ply" % (a.dir, a.frame))
    w = winding(X, V, F)
    d, f = closest(X, V, F)
    d /= edge
    ins = (w > 0.5) & (d > 1e-6)
    cen = V[F].mean(axis=1)
    idx = np.where(ins)[0]
    wf = winding(cen[f[idx]], V, F) - own(cen[f[idx]], V, F[f[idx]])
    buried = np.zeros(len(X), bool); buried[idx[np.abs(wf - 0.5) >= 0.25]] = True
    if "anchor_face" in skin_props:  # anchored on a buried face (another than the nearest)
        af = skin_props["anchor_face"][idx]
        other = (af >= 0) & (af < len(F)) & (af != f[idx])
        ja = idx[other]
        wa = winding(cen[af[other]], V, F) - own(cen[af[other]], V, F[af[other]])
        buried[ja[np.abs(wa - 0.5) >= 0.25]] = True
    # in front of the nearest face and yet inside: inside another part of the body
    # (the run judges by the pseudo-normal at the nearest point; the face's plane here)
    A, B, C = V[F[f[idx], 0]], V[F[f[idx], 1]], V[F[f[idx], 2]]
    front = np.einsum("ij,ij->i", X[idx] - A, np.cross(B - A, C - A)) > 0
    buried[idx[front]] = True
    clean = ins & ~buried
    print("frame %d: inside %d of %d; clean %d (deepest %.3f edges, >0.05: %d, >0.1: %d); "
          "buried %d (deepest %.3f); edge %.4g m" % (a.frame, ins.sum(), len(X), clean.sum(),
          d[clean].max() if clean.any() else 0, (d[clean] > 0.05).sum(), (d[clean] > 0.1).sum(),
          buried.sum(), d[buried].max() if buried.any() else 0, edge))
    import matplotlib; matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    c0 = X[np.argmax(np.where(clean, d, -1))] if clean.any() else V.mean(axis=0)
    r = a.zoom * edge
    near = np.all(np.abs(cen - c0) < r, axis=1)
    fig = plt.figure(figsize=(8, 8)); ax = fig.add_subplot(111, projection="3d")
    ax.add_collection3d(Poly3DCollection(V[F[near]], facecolor=(0.7, 0.7, 0.7, 0.35),
                                         edgecolor=(0.3, 0.3, 0.3, 0.3), linewidths=0.3))
    snear = np.all(np.abs(X[SF].mean(axis=1) - c0) < r, axis=1)
    ax.add_collection3d(Poly3DCollection(X[SF[snear]], facecolor=(0, 0, 0, 0),
                                         edgecolor=(0.1, 0.5, 0.1, 0.6), linewidths=0.4))
    sel = clean & np.all(np.abs(X - c0) < r, axis=1)
    ax.scatter(*X[sel].T, c="red", s=10 + 200 * d[sel], label="clean inside (size: depth)")
    selb = buried & np.all(np.abs(X - c0) < r, axis=1)
    ax.scatter(*X[selb].T, c="blue", s=6, label="buried inside")
    for k in range(3): getattr(ax, "set_%slim" % "xyz"[k])(c0[k] - r, c0[k] + r)
    el, az = [float(t) for t in a.view.split(",")]
    ax.view_init(el, az)
    ax.set_title("%s frame %d: clean deepest %.3f edges, %d deeper than 0.05" % (
        a.title, a.frame, d[clean].max() if clean.any() else 0, (d[clean] > 0.05).sum()))
    ax.legend(loc="lower left")
    fig.savefig(a.png, dpi=110)


if __name__ == "__main__":
    main()
