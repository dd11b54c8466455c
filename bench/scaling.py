#!/usr/bin/python3
"""Scaling of one step with the skin's size: bench_sim on the quadruped at
growing triangle counts, one process per size, recording per-frame medians
(wall and CPU ms), walk ms and the process's peak RSS; fits ms = c tris^k by
least squares in log-log over all sizes and prints a table (and with --png
FILE a chart: ms per frame and peak RSS per triangle against triangles).

  /usr/bin/python3 bench/scaling.py BENCH_SIM [--sizes 2000,5000,...] [--frames N] [--threads T]
                  [--substeps S] [--iterations I] [--repeat R] [--png FILE]

Read "cpu" (CPU time of the process per step) at one thread on a shared
machine: wall-clock there mostly measures the other jobs.
"""
import argparse
import math
import re
import resource
import statistics
import subprocess
import sys


def run(bench, tris, frames, threads, substeps, iterations):
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    out = subprocess.run([bench, "quadruped", str(tris), str(frames), "quasi-newton", str(substeps),
                          str(iterations), "1e-4", "walk", str(threads)],
                         check=True, capture_output=True, text=True).stdout
    # ru_maxrss of RUSAGE_CHILDREN is the largest child so far: sizes run in
    # increasing order, so each run's peak is the new maximum
    rss_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    if rss_kb <= before:
        rss_kb = float("nan")
    get = lambda k: float(re.search(r"\b%s ([0-9.]+)" % k, out).group(1))
    return {"tris": int(re.search(r"tris (\d+)", out).group(1)), "total": get("total"), "cpu": get("cpu"),
            "walk": get("walk"), "assemble": get("assemble"), "solve": get("solve"),
            "iterations": get("iterations"), "rss_mb": rss_kb / 1024.0}


def fit(rows, key):
    xs = [math.log(r["tris"]) for r in rows]
    ys = [math.log(r[key]) for r in rows]
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bench")
    ap.add_argument("--sizes", default="2000,5000,10000,19000,38000,80000")
    ap.add_argument("--frames", type=int, default=20)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--substeps", type=int, default=4, help="per frame (default: the sim's default, 4)")
    ap.add_argument("--iterations", type=int, default=2, help="per substep (default: the sim's default, 2)")
    ap.add_argument("--repeat", type=int, default=1,
                    help="runs per size, their medians reported (one run of the same binary can be "
                         "a third slower than the next on this machine)")
    ap.add_argument("--png")
    a = ap.parse_args()
    rows = []
    for tris in sorted(int(s) for s in a.sizes.split(",")):
        runs = [run(a.bench, tris, a.frames, a.threads, a.substeps, a.iterations) for _ in range(max(1, a.repeat))]
        r = dict(runs[0])  # tris, and the peak RSS of the first (later runs of a size do not raise the maximum)
        for k in ("total", "cpu", "walk", "assemble", "solve", "iterations"):
            r[k] = statistics.median(x[k] for x in runs)
        rows.append(r)
        print("%7d tris: total %.2f cpu %.2f walk %.2f assemble %.2f solve %.2f ms/frame, %.2f iterations, "
              "peak RSS %.1f MB (%.2f kB per triangle)" % (r["tris"], r["total"], r["cpu"], r["walk"], r["assemble"],
                                                          r["solve"], r["iterations"], r["rss_mb"],
                                                          1024.0 * r["rss_mb"] / r["tris"]), flush=True)
    if len(rows) >= 2:
        print("exponent k in ms = c tris^k, %d..%d triangles: cpu %.2f, total %.2f" %
              (rows[0]["tris"], rows[-1]["tris"], fit(rows, "cpu"), fit(rows, "total")))
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
        t = [r["tris"] for r in rows]
        ax1.loglog(t, [r["cpu"] for r in rows], "o-", label="cpu ms/frame (k=%.2f)" % fit(rows, "cpu"))
        ax1.loglog(t, [r["total"] for r in rows], "s--", label="wall ms/frame")
        ax1.axhline(33.3, color="gray", lw=0.8)
        ax1.set_xlabel("triangles")
        ax1.set_ylabel("ms per frame")
        ax1.legend()
        ax2.semilogx(t, [1024.0 * r["rss_mb"] / r["tris"] for r in rows], "o-")
        ax2.set_xlabel("triangles")
        ax2.set_ylabel("peak RSS per triangle (kB)")
        fig.suptitle("quadruped, quasi-Newton, %d substep(s) x %d iterations, %d thread(s)" %
                     (a.substeps, a.iterations, a.threads))
        fig.tight_layout()
        fig.savefig(a.png, dpi=90)


if __name__ == "__main__":
    sys.exit(main())
