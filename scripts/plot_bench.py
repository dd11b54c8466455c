#!/usr/bin/python3
"""Charts of `skinsim bench`: reads DIR/results.csv, writes into DIR
pareto.png (ms per frame against error_vs_truth: every method against one truth),
pareto_reference.png (the same against each method's own reference),
stability.png + stability.md, scaling.png, breakdown.png, options.png + options.md,
rest_return.png, accuracy.png + accuracy.md (every method
against the truth, with the commands) (matplotlib, Agg backend, no display).

usage: /usr/bin/python3 scripts/plot_bench.py DIR
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DPI = 80
METHODS = ["walk", "project", "nring1", "nring2", "nring4"]
MARKERS = {"walk": "o", "project": "s", "nring1": "^", "nring2": "v", "nring4": "D"}
COLORS = {"walk": "tab:green", "project": "tab:red", "nring1": "tab:orange",
          "nring2": "tab:purple", "nring4": "tab:brown"}


def num(row, key):
    try:
        v = float(row.get(key, ""))
        return v if math.isfinite(v) else None
    except ValueError:
        return None


def base_config(rows):
    """The sweep's base configuration as its methods rows ran it (the defaults)."""
    for r in rows:
        if r.get("sweep") == "methods" and r.get("method") == "walk":
            return "%s, %s substep%s x %s iterations" % (
                r.get("solver", "quasi-newton"), r["substeps"], "" if r["substeps"] == "1" else "s",
                r["iterations"])
    return "the defaults"


def inverted_cell(r):
    """inverted faces, + those over body folds / folded body faces (older CSVs: the count)."""
    inv = r.get("inverted_faces_max", "-")
    if r.get("inverted_over_folds_max") in (None, ""):
        return inv
    return "%s (+%s / %s)" % (inv, r["inverted_over_folds_max"], r.get("body_folds_max", "-"))


def method_label(row):
    m = row["method"]
    return "nring" + row["nring_rings"] if m == "nring" else m


def load(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save(fig, out, name):
    fig.savefig(os.path.join(out, name), dpi=DPI, bbox_inches="tight")
    plt.close(fig)


def pareto_front(points):
    """Points (x, y) not dominated by another (lower x and lower y)."""
    front, best = [], math.inf
    for x, y in sorted(points):
        if y < best:
            front.append((x, y))
            best = y
    return front


def config_label(row):
    return "%s %s it %s sub %s" % (method_label(row), row["solver"], row["iterations"],
                                   row["substeps"])


def plot_pareto(rows, out, field="error_vs_truth", name="pareto.png"):
    """ms per frame against error (field), per scene with the solver/substeps sweep."""
    scenes = []
    for r in rows:
        if r["sweep"] in ("solvers", "substeps") and r["scene"] not in scenes:
            scenes.append(r["scene"])
    if not scenes:
        scenes = sorted({r["scene"] for r in rows if num(r, field) is not None})[:3]
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.2 * len(scenes), 4.4), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        pts = [r for r in rows if r["scene"] == scene and r["sweep"] in
               ("methods", "solvers", "substeps")
               and num(r, field) is not None]
        seen = set()
        for r in pts:
            ms, err = num(r, "ms_per_frame_median"), num(r, field)
            m, solver = method_label(r), r["solver"]
            key = (m, solver)
            face = COLORS.get(m, "gray") if solver == "quasi-newton" else "none"
            ax.scatter([ms], [max(err, 1e-6)], marker=MARKERS.get(m, "x"),
                       facecolors=face, edgecolors=COLORS.get(m, "gray"), s=46,
                       label=("%s, %s" % (m, solver)) if key not in seen else None)
            seen.add(key)
            if r["sweep"] in ("solvers", "substeps"):
                tag = ("it %s" % r["variant"]) if r["sweep"] == "solvers" else ("sub %s" % r["variant"])
                ax.annotate(tag, (ms, max(err, 1e-6)), fontsize=6, xytext=(3, 3),
                            textcoords="offset points")
        front = pareto_front([(num(r, "ms_per_frame_median"), max(num(r, field), 1e-6))
                              for r in pts])
        if front:
            ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="k",
                    lw=1, ls="--", label="Pareto front")
        ax.set_xscale("log")
        ax.set_yscale("log")
        tri = pts[0]["triangles"] if pts else "?"
        ax.set_title("%s (%s triangles)" % (scene, tri), fontsize=10)
        ax.set_xlabel("ms per frame (median)")
        ax.set_ylabel(("error vs truth" if field == "error_vs_truth" else
                       "error vs its own method's reference") + " (mean edge lengths)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6, loc="best")
    what = ("against ONE truth (walk, Newton to 1e-6, 16 substeps): snags count"
            if field == "error_vs_truth" else
            "against each method's OWN reference (a snagging method's reference snags too)")
    fig.suptitle("Speed against accuracy, %s\n(filled: quasi-Newton, hollow: Newton; "
                 "labels: iterations / substeps)" % what, fontsize=9)
    save(fig, out, name)


def plot_stability(rows, out):
    mrows = [r for r in rows if r["sweep"] == "methods"]
    scenes = []
    for r in mrows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    cell = {(r["scene"], method_label(r)): r for r in mrows}
    lines = ["# Stability: where each method breaks", "",
             "Per scene and anchor method (" + base_config(rows) + "): snags "
             "(anchor jumps across a gap), failures (frames with NaN/Inf, an area ratio "
             "outside [0.05, 20] or a failed step), hug RMS / max (skin to body distance, "
             "mean edge lengths), inverted faces (the most skin faces in one frame turned "
             "against the body where anchored; + those over a body fold, where the pose turned "
             "a body face against a neighbour it faced the same way as at rest, counted apart; "
             "/ the body faces so folded), inside (deepest skin vertex under the body, "
             "mean edge lengths), error vs truth (one truth for every method: walk, Newton "
             "to 1e-6, 16 substeps) and vs the method's own reference (mean edge lengths).", "",
             "| scene | triangles | frames | method | snags | failures | hug rms | hug max "
             "| inverted | inside | error vs truth | error vs own ref | ms/frame |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in scenes:
        for m in METHODS:
            r = cell.get((s, m))
            if not r:
                continue
            e = num(r, "error_vs_reference")
            t = num(r, "error_vs_truth")
            lines.append("| %s | %s | %s | %s | %s | %s | %.3f | %.3f | %s | %.3f | %s | %s "
                         "| %.2f |" % (
                s, r["triangles"], r["frames"], m, r["snags"], r["failures"],
                num(r, "hug_rms") or 0.0, num(r, "hug_max") or 0.0,
                inverted_cell(r), num(r, "inside_max") or 0.0,
                "%.3g" % t if t is not None else "-",
                "%.3g" % e if e is not None else "-", num(r, "ms_per_frame_median") or 0.0))
    with open(os.path.join(out, "stability.md"), "w") as f:
        f.write("\n".join(lines) + "\n")

    fig, axes = plt.subplots(1, 9, figsize=(40, 0.42 * len(scenes) + 1.8))
    keys = [("snags", "snags (count)"), ("failures", "failed frames"),
            ("inverted_faces_max", "inverted faces (most in a frame)"),
            ("faces_turned_max", "faces turned, plain count (most in a frame)"),
            ("hug_far_max", "vertices over an edge off (most in a frame)"),
            ("inside_max", "inside the body (edge lengths)"),
            ("inside_clean_max", "inside the clean body, winding number (edge lengths)"),
            ("hug_rms", "hug RMS (edge lengths)"),
            ("error_vs_truth", "error vs truth (edge lengths)")]
    for ax, (key, title) in zip(axes, keys):
        data = [[num(cell[(s, m)], key) if (s, m) in cell else float("nan") for m in METHODS]
                for s in scenes]
        vals = [v for row in data for v in row if v is not None and not math.isnan(v)]
        vmax = max(vals) if vals else 1.0
        img = [[(v if v is not None else float("nan")) for v in row] for row in data]
        ax.imshow(img, cmap="Reds", vmin=0, vmax=vmax if vmax > 0 else 1.0, aspect="auto")
        for i, row in enumerate(data):
            for j, v in enumerate(row):
                if v is None or math.isnan(v):
                    continue
                txt = ("%d" % v) if key in ("snags", "failures", "inverted_faces_max", "faces_turned_max",
                                            "hug_far_max") else ("%.3f" % v)
                ax.text(j, i, txt, ha="center", va="center", fontsize=7,
                        color="white" if vmax > 0 and v > 0.6 * vmax else "black")
        ax.set_xticks(range(len(METHODS)))
        ax.set_xticklabels(METHODS, fontsize=8)
        ax.set_yticks(range(len(scenes)))
        ax.set_yticklabels(scenes, fontsize=8)
        ax.set_title(title, fontsize=10)
    fig.suptitle("Where methods break: per scene and anchor method", fontsize=11)
    save(fig, out, "stability.png")


def fit_exponent(xs, ys):
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    n = len(lx)
    mx, my = sum(lx) / n, sum(ly) / n
    sxx = sum((a - mx) ** 2 for a in lx)
    if n < 2 or sxx == 0:
        return None, None
    k = sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx
    return k, math.exp(my - k * mx)


def plot_scaling(rows, out):
    srows = [r for r in rows if r["sweep"] == "scaling"]
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    summary = []
    for m, key, style, what in [("walk", "ms_per_frame_median", "o-", "frame, walk"),
                                ("project", "ms_per_frame_median", "s-", "frame, project"),
                                ("walk", "walk_ms_per_frame_median", "o:", "anchor walk only"),
                                ("project", "walk_ms_per_frame_median", "s:",
                                 "anchor projection only")]:
        pts = sorted((int(r["triangles"]), num(r, key)) for r in srows
                     if method_label(r) == m and num(r, key))
        if len(pts) < 2:
            continue
        k, c = fit_exponent([p[0] for p in pts], [p[1] for p in pts])
        ax.plot([p[0] for p in pts], [p[1] for p in pts], style, color=COLORS[m],
                label="%s: ms ~ tris^%.2f" % (what, k))
        summary.append("%s: exponent %.2f" % (what, k))
    ax.axhline(33.0, color="gray", ls="--", lw=1)
    ax.text(0.01, 35, "33 ms budget (30 Hz)", fontsize=7, color="gray",
            transform=ax.get_yaxis_transform())
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("body triangles (quadruped)")
    ax.set_ylabel("ms per frame (median)")
    ax.set_title("Scaling: " + base_config(rows), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, out, "scaling.png")
    with open(os.path.join(out, "scaling.txt"), "w") as f:
        f.write("\n".join(summary) + "\n")


def plot_breakdown(rows, out):
    bars = []
    for r in rows:
        if r["sweep"] == "methods" and method_label(r) == "walk":
            bars.append(("%s qn" % r["scene"], r))
    for r in rows:
        if r["sweep"] == "solvers" and r["solver"] == "newton" and r["variant"] == "8":
            bars.append(("%s newton" % r["scene"], r))
    for r in rows:
        if r["sweep"] == "scaling" and method_label(r) == "walk":
            bars.append(("quadruped %s" % r["triangles"], r))
    parts = [("assemble_ms_per_frame_median", "assemble", "tab:blue"),
             ("factor_ms_per_frame_median", "factorise", "tab:red"),
             ("solve_ms_per_frame_median", "solve", "tab:orange"),
             ("walk_ms_per_frame_median", "walk (anchor update)", "tab:green")]
    fig, ax = plt.subplots(figsize=(max(7.0, 0.42 * len(bars) + 4), 4.8))
    xs = range(len(bars))
    for i, (label, r) in enumerate(bars):
        total = num(r, "ms_per_frame_median") or 0.0
        bottom = 0.0
        fracs = []
        for key, name, color in parts:
            v = num(r, key) or 0.0
            fracs.append(v)
        # medians of the parts need not add up to the median total: scale shares
        s = sum(fracs)
        other = max(total - s, 0.0)
        scale = total / s if s > total and s > 0 else 1.0
        for (key, name, color), v in zip(parts, fracs):
            ax.bar(i, 100.0 * v * scale / total if total else 0, bottom=bottom, color=color,
                   label=name if i == 0 else None)
            bottom += 100.0 * v * scale / total if total else 0
        ax.bar(i, 100.0 * other / total if total else 0, bottom=bottom, color="lightgray",
               label="other (pose, line search, bookkeeping)" if i == 0 else None)
        ax.text(i, 101, "%.1f" % total, ha="center", fontsize=6, rotation=90)
    ax.set_xticks(list(xs))
    ax.set_xticklabels([b[0] for b in bars], rotation=70, fontsize=7)
    ax.set_ylabel("% of a frame's time (median; ms on top)")
    ax.set_ylim(0, 118)
    ax.set_title("Where a frame's time goes", fontsize=10)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    save(fig, out, "breakdown.png")


def plot_options(rows, out):
    orows = [r for r in rows if r["sweep"] == "options"]
    scenes = []
    for r in orows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    options = []
    for r in orows:
        if r["option"] not in options:
            options.append(r["option"])
    cell = {(r["scene"], r["option"]): r for r in orows}
    lines = ["# What each optional part costs and buys", "",
             "Per scene (walk, " + base_config(rows) + "): ms per frame; "
             "error = RMS distance to the reference of the same model (what the fast "
             "solve costs); vs default = RMS distance to the reference of the default model "
             "(what the option changes: for a simplification its cost in accuracy, for an "
             "added term how much the scene needs it). Both in mean edge lengths; the coarse "
             "skin is compared with the fine skin's reference through closest points at "
             "rest. bending: hinge k = 1e-3 N m; gravity: 9.81 m/s^2 along -z; region: only "
             "the faces whose rest centroid has x >= the median simulated, the rest follows "
             "the body; coarse-skin: the same scene at a quarter of the triangles as skin; "
             "stiff-compression: compression 1, the Stable Neo-Hookean membrane, as stiff "
             "pushed together as pulled apart (the default skin is 0.1 as stiff in "
             "compression). collide: the skin moved out of the clean body (contact). hug rms: "
             "distance of the skin to the body (silhouette); inverted: most skin faces turned "
             "against the body in a frame; clean depth: the deepest skin vertex inside the "
             "body where the body is clean (winding number, every 10th frame).", "",
             "| scene | option | skin triangles | ms/frame | x base | error | vs default "
             "| snags | hug rms | inverted | clean depth |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in scenes:
        base = num(cell[(s, "base")], "ms_per_frame_median") if (s, "base") in cell else None
        for o in options:
            r = cell.get((s, o))
            if not r:
                continue
            ms = num(r, "ms_per_frame_median") or 0.0
            e = num(r, "error_vs_reference")
            d = num(r, "error_vs_base_reference")
            lines.append("| %s | %s | %s | %.2f | %s | %s | %s | %s | %.3f | %s | %.3f |" % (
                s, o, r["skin_triangles"], ms, "%.2f" % (ms / base) if base else "-",
                "%.3g" % e if e is not None else "-", "%.3g" % d if d is not None else "-",
                r["snags"], num(r, "hug_rms") or 0.0, inverted_cell(r),
                num(r, "inside_clean_max") or 0.0))
    with open(os.path.join(out, "options.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    fig, axes = plt.subplots(1, 4, figsize=(20, 4.2))
    width = 0.8 / max(1, len(scenes))
    for k, (key, title) in enumerate([
            ("ms_per_frame_median", "ms per frame (median)"),
            ("error_vs_reference", "error vs the same model's reference"),
            ("error_vs_base_reference", "distance to the default model's reference"),
            ("inside_clean_max", "deepest inside the clean body (edge lengths)")]):
        ax = axes[k]
        for i, s in enumerate(scenes):
            vals = [num(cell[(s, o)], key) if (s, o) in cell else 0 for o in options]
            ax.bar([j + i * width for j in range(len(options))], [v or 0 for v in vals], width,
                   label="%s (%s tris)" % (s, cell[(s, options[0])]["triangles"])
                   if (s, options[0]) in cell else s)
        ax.set_xticks([j + 0.4 - width / 2 for j in range(len(options))])
        ax.set_xticklabels(options, rotation=30, fontsize=8)
        ax.set_title(title, fontsize=10)
        ax.set_yscale("log")
        ax.grid(True, axis="y", which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("What each optional part of the model costs (time) and changes (edge lengths)",
                 fontsize=10)
    save(fig, out, "options.png")


def plot_rest_return(rows, out):
    """Rest error after settling against the tether, per body, walk and project."""
    rrows = [r for r in rows if r["sweep"] == "rest" and num(r, "rest_error_max") is not None]
    if not rrows:
        return
    bodies = []
    for r in rrows:
        if r["scene"] not in bodies:
            bodies.append(r["scene"])
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.6))
    keys = [("rest_error_rms", "rest error RMS (edge lengths)"),
            ("rest_error_max", "rest error max (edge lengths)"),
            ("slide_max", "max slide during the motion (edge lengths)")]
    cmap = plt.get_cmap("tab10")
    for ax, (key, title) in zip(axes, keys):
        for i, b in enumerate(bodies):
            for m, ls in (("walk", "-"), ("project", ":")):
                pts = sorted((num(r, "tether"), num(r, key)) for r in rrows
                             if r["scene"] == b and r["method"] == m
                             and num(r, "tether") is not None and num(r, key) is not None)
                if not pts:
                    continue
                xs = [max(x, 0.03) for x, _ in pts]  # tether 0 drawn at the left edge
                ax.plot(xs, [max(y, 1e-4) for _, y in pts], ls=ls, marker="o", ms=3,
                        color=cmap(i % 10), label="%s, %s" % (os.path.basename(b), m))
        if key != "slide_max":
            ax.axhline(0.1 if key == "rest_error_max" else 0.02, color="k", lw=0.8, ls="--")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("tether (1/s; 0 drawn at 0.03)")
        ax.set_title(title, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=6, loc="best")
    fig.suptitle("Rest return: after the motion the body goes back to rest over 1 s (in its joint angles) and "
                 "holds still (settle); solid walk, dotted project; dashed: the goals 0.02 rms, "
                 "0.1 max", fontsize=9)
    save(fig, out, "rest_return.png")


ACC_METHODS = ["walk", "project", "nring2"]


def run_command(r):
    """The `skinsim run` command that reproduces a methods-sweep row (error vs truth)."""
    m = method_label(r)
    if r["body_kind"] == "scene":
        # the sweep asks 1000 triangles (--quick: 300); the scene builds about that many
        body = "--scene %s --tris %s" % (r["scene"], "1000" if r["frames"] == "40" else "300")
    elif r["scene"] == "demo":
        body = "--avatar demo"
    else:
        body = "--asset /usr/share/assimp/models/X/%s" % r["scene"]
    meth = {"walk": "", "project": " --method project", "nring2": " --method nring --rings 2"}.get(m, "")
    return "skinsim run %s --frames %s%s --truth --json -" % (body, r["frames"], meth)


def plot_accuracy(rows, out):
    """Per body: error_vs_truth of walk, project and n-ring 2 at the default solver
    settings (the methods sweep), with the error against each method's own reference,
    snags and inverted faces beside them: accuracy.md and accuracy.png."""
    mrows = [r for r in rows if r["sweep"] == "methods" and method_label(r) in ACC_METHODS]
    bodies = []
    for r in mrows:
        if r["scene"] not in bodies:
            bodies.append(r["scene"])
    if not bodies:
        return
    cell = {(r["scene"], method_label(r)): r for r in mrows}
    # the truth's own uncertainty: `skinsim bench --truth-doubling 32` (16 vs 32 substeps)
    unc = {}
    upath = os.path.join(out, "truth_doubling.csv")
    if os.path.exists(upath):
        for r in load(upath):
            if num(r, "diff_16_32") is not None:
                unc[r["body"]] = num(r, "diff_16_32")
    lines = ["# Every method against one truth", "",
             "Per body: the error of each anchor method at the default solver settings "
             "(" + base_config(rows) + ") against the TRUTH (walk, Newton to 1e-6, "
             "16 substeps: one run per body, motion and physical settings), and against the "
             "method's OWN reference (the same method, Newton to 1e-6, 16 substeps), both as RMS "
             "over frames and skin vertices in mean rest edge lengths; x walk = error vs truth "
             "divided by walk's. Snags (anchor jumps across a gap) and inverted faces (most in a "
             "frame) beside them. Scenes: 1000 triangles requested, 40 frames; avatars 15 frames. "
             "Each row's command (the avatar's with --avatar-tris 3000 for the demo) prints the "
             "same figures. truth 16 vs 32: how far the truth itself moves when its substeps are "
             "doubled (`skinsim bench --truth-doubling 32`, truth_doubling.md): differences "
             "between methods smaller than it are not resolved by this truth.", "",
             "| body | method | error vs truth | x walk | truth 16 vs 32 | error vs own ref | snags | inverted | ms/frame | command |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for b in bodies:
        w = num(cell[(b, "walk")], "error_vs_truth") if (b, "walk") in cell else None
        for m in ACC_METHODS:
            r = cell.get((b, m))
            if not r:
                continue
            t, e = num(r, "error_vs_truth"), num(r, "error_vs_reference")
            cmd = run_command(r)
            if b == "demo":
                cmd = cmd.replace("--avatar demo", "--avatar demo --avatar-tris 3000")
            u = unc.get(os.path.basename(b))
            lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %.2f | `%s` |" % (
                os.path.basename(b), m, "%.4g" % t if t is not None else "-",
                "%.2f" % (t / w) if t is not None and w else "-",
                "%.3g" % u if u is not None else "-",
                "%.4g" % e if e is not None else "-", r["snags"], inverted_cell(r),
                num(r, "ms_per_frame_median") or 0.0, cmd))
    with open(os.path.join(out, "accuracy.md"), "w") as f:
        f.write("\n".join(lines) + "\n")

    fig, axes = plt.subplots(1, 2, figsize=(14, 4.6))
    width = 0.8 / len(ACC_METHODS)
    xs = range(len(bodies))
    for k, m in enumerate(ACC_METHODS):
        for ax, field, hatch in ((axes[0], "error_vs_truth", None), (axes[1], "error_vs_reference", None)):
            vals = []
            for b in bodies:
                r = cell.get((b, m))
                v = num(r, field) if r else None
                w = num(cell[(b, "walk")], "error_vs_truth") if (b, "walk") in cell else None
                vals.append(v / w if v is not None and w else float("nan"))
            bars = ax.bar([x + (k - 1) * width for x in xs], vals, width, color=COLORS[m], label=m,
                          hatch=hatch)
            if field == "error_vs_truth":
                for x, b in zip(xs, bodies):
                    r = cell.get((b, m))
                    v = vals[list(xs).index(x)]
                    if r and int(float(r["snags"] or 0)) > 0 and v == v:
                        ax.annotate("%s snags" % r["snags"], (x + (k - 1) * width, v), fontsize=6,
                                    rotation=90, xytext=(0, 3), textcoords="offset points",
                                    ha="center", va="bottom")
    for x, b in zip(xs, bodies):  # the truth's own uncertainty around walk's error
        u = unc.get(os.path.basename(b))
        w = num(cell[(b, "walk")], "error_vs_truth") if (b, "walk") in cell else None
        if u is not None and w:
            axes[0].add_patch(plt.Rectangle((x - 0.45, 1.0 - u / w), 0.9, 2 * u / w, color="0.85",
                                            zorder=0, label="truth 16 vs 32 substeps" if x == 0 else None))
    for ax, title in ((axes[0], "error vs the TRUTH, relative to walk's (grey: +- the truth's own "
                                "16 vs 32 difference)"),
                      (axes[1], "error vs each method's OWN reference, relative to walk's error vs truth")):
        ax.axhline(1.0, color="k", lw=0.8, ls="--")
        ax.set_ylim(0.6, ax.get_ylim()[1] * 1.3)
        ax.set_xticks(list(xs))
        ax.set_xticklabels([os.path.basename(b) + "\n(walk %.3g)" % (num(cell[(b, "walk")], "error_vs_truth") or 0)
                            if (b, "walk") in cell else os.path.basename(b) for b in bodies], fontsize=7,
                           rotation=30)
        ax.set_title(title, fontsize=10)
        ax.set_ylabel("error / walk's error vs truth")
        ax.grid(True, axis="y", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Where each method stands (" + base_config(rows) + "); under each body "
                 "walk's error vs truth in mean edge lengths", fontsize=10)
    save(fig, out, "accuracy.png")


def main():
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    out = sys.argv[1]
    rows = load(os.path.join(out, "results.csv"))
    if not rows:
        sys.stderr.write("plot_bench: %s/results.csv has no rows\n" % out)
        return 1
    # each chart from the sweeps it reads; a results.csv of some sweeps only
    # (skinsim bench --sweeps) gets those charts only
    have = set(r["sweep"] for r in rows)
    charts = [
        ({"solvers"}, lambda: plot_pareto(rows, out)),
        ({"solvers"},
         lambda: plot_pareto(rows, out, "error_vs_reference", "pareto_reference.png")),
        ({"rest"}, lambda: plot_rest_return(rows, out)),
        ({"methods"}, lambda: plot_accuracy(rows, out)),
        ({"methods"}, lambda: plot_stability(rows, out)),
        ({"scaling"}, lambda: plot_scaling(rows, out)),
        ({"methods", "solvers", "scaling"}, lambda: plot_breakdown(rows, out)),
        ({"options"}, lambda: plot_options(rows, out)),
    ]
    drawn = 0
    for needs, draw in charts:
        if needs & have == needs:
            draw()
            drawn += 1
    print("plot_bench: %d charts written to %s" % (drawn, out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
