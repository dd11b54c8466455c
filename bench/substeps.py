#!/usr/bin/python3
"""Is the physics independent of the step? For each body,
error_vs_truth (`skinsim run --truth`, cached) at 1, 2, 4, 8, 16 substeps per
frame, with the default solver settings and, with --newton, also with Newton
converged (1e-6, the truth's own solver: at 16 substeps that run IS the truth,
error 0). The error must fall steadily as the step shrinks. Prints a Markdown
table (and --csv FILE).

  /usr/bin/python3 bench/substeps.py SKINSIM [--bodies quadruped:2000:40,quadruped:19000:20,demo:3000:15]
                  [--substeps 1,2,4,8,16] [--newton] [--cache DIR] [--csv FILE]
A body is scene:tris:frames, or demo:tris:frames for the demo avatar.
"""
import argparse
import json
import os
import subprocess
import sys
import time


def run(skinsim, body, sub, newton, cache):
    name, tris, frames = body.split(":")
    cmd = [skinsim, "run"]
    cmd += ["--avatar", "demo", "--avatar-tris", tris] if name == "demo" else ["--scene", name, "--tris", tris]
    cmd += ["--frames", frames, "--substeps", str(sub), "--truth", "--cache", cache, "--json", "-"]
    if newton:
        cmd += ["--solver", "newton", "--iterations", "100", "--tol", "1e-6"]
    t0 = time.time()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    j = json.loads(out)
    return j, time.time() - t0, " ".join(os.path.basename(c) if i == 0 else c for i, c in enumerate(cmd))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("skinsim")
    ap.add_argument("--bodies", default="quadruped:2000:40,quadruped:19000:20,demo:3000:15")
    ap.add_argument("--substeps", default="1,2,4,8,16")
    ap.add_argument("--newton", action="store_true", help="also Newton converged")
    ap.add_argument("--cache", default=os.path.expanduser("~/.cache/skin_sim"))
    ap.add_argument("--csv")
    a = ap.parse_args()
    subs = [int(s) for s in a.substeps.split(",")]
    solvers = [False, True] if a.newton else [False]
    rows = []
    for body in a.bodies.split(","):
        for newton in solvers:
            errs = []
            for sub in subs:
                j, sec, cmd = run(a.skinsim, body, sub, newton, a.cache)
                errs.append(j["error_vs_truth"])
                rows.append((body, "newton 1e-6" if newton else "default", sub, j["error_vs_truth"],
                             j["ms_per_frame_median"], j["snags"], j["failures"], sec, cmd))
                print("%s %s substeps %d: error_vs_truth %.4g, %.1f ms/frame, %d snags, %d failures [%.0f s]" %
                      (body, "newton" if newton else "default", sub, j["error_vs_truth"], j["ms_per_frame_median"],
                       j["snags"], j["failures"], sec), file=sys.stderr, flush=True)
            steady = all(errs[i + 1] < errs[i] for i in range(len(errs) - 1) if errs[i] > 0)
            print("%s, %s solver: %s -> %s" % (body, "Newton converged" if newton else "default",
                                                " / ".join("%.4g" % e for e in errs),
                                                "falls steadily" if steady else "does NOT fall steadily"),
                  file=sys.stderr, flush=True)
    print("| body (scene:tris:frames) | solver | " + " | ".join("%d substep%s" % (s, "s" if s > 1 else "") for s in subs) + " |")
    print("|---|---|" + "---|" * len(subs))
    keys = []
    for r in rows:
        if (r[0], r[1]) not in keys:
            keys.append((r[0], r[1]))
    for k in keys:
        errs = [r[3] for r in rows if (r[0], r[1]) == k]
        print("| %s | %s | %s |" % (k[0], k[1], " | ".join("%.4g" % e for e in errs)))
    if a.csv:
        with open(a.csv, "w") as f:
            f.write("body,solver,substeps,error_vs_truth,ms_per_frame_median,snags,failures,seconds,command\n")
            for r in rows:
                f.write('%s,%s,%d,%.6g,%.4g,%d,%d,%.1f,"%s"\n' % r)


if __name__ == "__main__":
    sys.exit(main())
