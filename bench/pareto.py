#!/usr/bin/python3
"""Speed against accuracy for the real-time solver on one body: for each
configuration (substeps x iterations) `skinsim run --truth` gives the error
against the converged truth (cached, shared by all configurations) and
bench_sim the per-frame medians (CPU ms at one thread: the figure to compare
on a shared machine; wall ms at the given thread counts). Prints a table,
marks the Pareto front and, with --png, draws it. --save FILE writes the
rows (JSON); --load FILE draws and prints saved rows without running anything.

  /usr/bin/python3 bench/pareto.py SKINSIM BENCH_SIM [--tris 19000] [--frames 60] [--configs 1x8,2x8,...]
                  [--cache DIR] [--threads 1,2] [--png FILE] [--default 4x2] [--save FILE]
  /usr/bin/python3 bench/pareto.py --load FILE [--png FILE] [--default 4x2]
"""
import argparse
import json
import os
import re
import subprocess
import sys


def skinsim_error(skinsim, tris, frames, sub, it, cache):
    out = subprocess.run([skinsim, "run", "--scene", "quadruped", "--tris", str(tris), "--frames", str(frames),
                          "--substeps", str(sub), "--iterations", str(it), "--threads", "1", "--truth",
                          "--cache", cache, "--json", "-"], check=True, capture_output=True, text=True,
                         env=dict(os.environ, OPENBLAS_NUM_THREADS="1")).stdout
    j = json.loads(out)
    return j["error_vs_truth"], j.get("final_hash")


def bench(bench_sim, tris, frames, sub, it, threads):
    out = subprocess.run([bench_sim, "quadruped", str(tris), str(frames), "quasi-newton", str(sub), str(it), "1e-4",
                          "walk", str(threads)], check=True, capture_output=True, text=True).stdout
    get = lambda k: float(re.search(r"\b%s ([0-9.]+)" % k, out).group(1))
    return {"total": get("total"), "cpu": get("cpu"), "iterations": get("iterations")}


def place_labels(fig, ax, points, names):
    """Each point's name beside it where it meets no other name and no marker:
    the first free of a few offsets around the point (points taken left to
    right), else the last of them."""
    offsets = [(4, 2), (4, -10), (-6, 6), (-6, -12), (6, 10), (6, -16), (-10, 12), (-10, -18)]
    fig.canvas.draw()
    render = fig.canvas.get_renderer()
    taken = []
    for (x, y) in points:  # the markers' own boxes (about 8 points across)
        px, py = ax.transData.transform((x, y))
        taken.append((px - 4, py - 4, px + 4, py + 4))
    meets = lambda a, b: a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]
    order = sorted(range(len(points)), key=lambda i: points[i])
    for i in order:
        others = taken[:i] + taken[i + 1:]  # the other markers and the names placed so far
        for k, (dx, dy) in enumerate(offsets):
            ha = "left" if dx >= 0 else "right"
            t = ax.annotate(names[i], points[i], fontsize=8, xytext=(dx, dy), textcoords="offset points", ha=ha)
            e = t.get_window_extent(render)
            box = (e.x0, e.y0, e.x1, e.y1)
            if not any(meets(box, b) for b in others):
                break
            if k < len(offsets) - 1:
                t.remove()
        taken.append(box)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("skinsim", nargs="?")
    ap.add_argument("bench_sim", nargs="?")
    ap.add_argument("--tris", type=int, default=19000)
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--configs", default="1x8,1x16,1x32,2x4,2x8,2x16,3x8,4x4,4x8")
    ap.add_argument("--cache", default=os.path.expanduser("~/.cache/skin_sim"))
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--png")
    ap.add_argument("--default", default="4x2", help="the configuration ringed on the chart (the defaults')")
    ap.add_argument("--save", help="write the rows to this JSON file")
    ap.add_argument("--load", help="draw and print the rows of this JSON file (from --save); runs nothing")
    a = ap.parse_args()
    if not a.load and not (a.skinsim and a.bench_sim):
        ap.error("SKINSIM and BENCH_SIM are needed (or --load FILE)")
    if a.load:
        try:
            with open(a.load) as f:
                saved = json.load(f)
            a.tris, a.frames, threads, rows = saved["tris"], saved["frames"], saved["threads"], saved["rows"]
        except (OSError, ValueError, KeyError, TypeError) as e:
            print("pareto.py: cannot read the rows of %s: %s" % (a.load, e), file=sys.stderr)
            return 2
        for r in rows:
            print("substeps %d iterations %2d: error_vs_truth %.4f, %s, %.2f iterations/frame" %
                  (r["substeps"], r["iterations"], r["error"],
                   ", ".join("%d thread(s) cpu %.2f wall %.2f ms/frame" % (t, r["cpu%d" % t], r["wall%d" % t])
                             for t in threads), r["its"]))
    else:
        threads = [int(t) for t in a.threads.split(",")]
        rows = []
    for cfg in ([] if a.load else a.configs.split(",")):
        sub, it = (int(v) for v in cfg.split("x"))
        err, fh = skinsim_error(a.skinsim, a.tris, a.frames, sub, it, a.cache)
        r = {"substeps": sub, "iterations": it, "error": err, "hash": fh}
        for t in threads:
            b = bench(a.bench_sim, a.tris, a.frames, sub, it, t)
            r["cpu%d" % t], r["wall%d" % t] = b["cpu"], b["total"]
            r["its"] = b["iterations"]
        rows.append(r)
        print("substeps %d iterations %2d: error_vs_truth %.4f, %s, %.2f iterations/frame" %
              (sub, it, err, ", ".join("%d thread(s) cpu %.2f wall %.2f ms/frame" % (t, r["cpu%d" % t], r["wall%d" % t])
                                        for t in threads), r["its"]), flush=True)
    if a.save:
        with open(a.save, "w") as f:
            json.dump({"tris": a.tris, "frames": a.frames, "threads": threads, "rows": rows}, f, indent=1)
    key = "cpu%d" % threads[0]
    front = [r for r in rows if not any(o[key] <= r[key] and o["error"] < r["error"] for o in rows if o is not r)]
    print("Pareto front (cpu ms at %d thread(s) vs error): %s" %
          (threads[0], ", ".join("%dx%d" % (r["substeps"], r["iterations"]) for r in front)))
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        names = []
        for r in rows:
            ax.plot(r[key], r["error"], "o", color="C0" if r in front else "C7")
            name = "%dx%d" % (r["substeps"], r["iterations"])
            if name == a.default:
                ax.plot(r[key], r["error"], "o", mfc="none", mec="C3", ms=12)
                name += " (default)"
            names.append(name)
        ax.axvline(33.3, color="gray", lw=0.8)
        one = [r for r in rows if r["substeps"] == 1 and r["iterations"] == 8]
        if one:  # the bar drawn: half of the error of 1 substep of 8 iterations
            ax.axhline(0.5 * one[0]["error"], color="gray", lw=0.8, ls="--")
            ax.annotate("half of 1x8's error", (ax.get_xlim()[0], 0.5 * one[0]["error"]), fontsize=7,
                        xytext=(4, 2), textcoords="offset points", color="gray")
        ax.set_xlabel("CPU ms per frame, %d thread" % threads[0])
        ax.set_ylabel("error vs truth (mean edge lengths)")
        ax.set_title("quadruped %d triangles, %d frames: substeps x iterations" % (a.tris, a.frames))
        fig.tight_layout()
        place_labels(fig, ax, [(r[key], r["error"]) for r in rows], names)
        fig.savefig(a.png, dpi=90)


if __name__ == "__main__":
    sys.exit(main())
