#!/usr/bin/env bash
# A/B timing of builds of bench_sim on a shared machine: runs the binaries
# alternately ROUNDS times with the same arguments and prints, per binary,
# the median over the rounds of each per-frame median bench_sim reports
# (total, cpu, pose, walk, assemble, factor, solve, linesearch, orient,
# other: total less the stages; where a build reports no linesearch and orient
# they are in its other), the iterations, the
# energy evaluations per iteration (where the build reports them), the hash,
# and the ratio of each time to the first binary's.
#
#   bash bench/ab.sh A_BENCH_SIM B_BENCH_SIM ROUNDS [bench_sim arguments...]
#   bash bench/ab.sh --bins A,B,C ROUNDS [bench_sim arguments...]   (any number of builds)
#   e.g. OPENBLAS_NUM_THREADS=1 bash bench/ab.sh /tmp/base/devel/lib/skin_sim/bench_sim \
#          build/release/devel/lib/skin_sim/bench_sim 5 quadruped 19000 60 quasi-newton 1 8 1e-4 walk 1
#
# OPENBLAS_NUM_THREADS=1: otherwise OpenBLAS starts a thread pool whose threads
# spin for about 0.1 s after each call and take a core from the timed run.
#
# Read "cpu" (process CPU time per step, all threads) for one thread on a
# loaded machine: wall-clock times there mostly measure the other jobs. After
# the medians (and their ratios to the first binary) it prints the fastest
# round of each, which a noisy neighbour disturbs least.
set -euo pipefail
if [[ "${1:-}" == "--bins" ]]; then
  IFS=, read -r -a bins <<<"${2:?usage: ab.sh --bins A,B[,C...] ROUNDS [bench_sim args]}"
  shift 2
else
  bins=("${1:?usage: ab.sh A B ROUNDS [bench_sim args]}" "${2:?usage: ab.sh A B ROUNDS [bench_sim args]}")
  shift 2
fi
rounds="${1:?usage: ab.sh A B ROUNDS [bench_sim args]}"
shift 1
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
tags=(A B C D E F G H)
for ((r = 0; r < rounds; r++)); do
  for ((i = 0; i < ${#bins[@]}; i++)); do
    echo "${tags[$i]} $("${bins[$i]}" "$@")" >>"$out"
  done
done
for ((i = 0; i < ${#bins[@]}; i++)); do echo "${tags[$i]} = ${bins[$i]}"; done
/usr/bin/python3 - "$out" <<'PYEOF'
import re, statistics, sys
keys = ["total", "cpu", "pose", "walk", "assemble", "factor", "solve", "linesearch", "orient", "other"]
rows = {}
for line in open(sys.argv[1]):
    tag, rest = line.split(" ", 1)
    d = {k: float(re.search(r"\b%s ([0-9.]+)" % k, rest).group(1)) for k in keys if re.search(r"\b%s ([0-9.]+)" % k, rest)}
    if "other" not in d:  # a build without the linesearch and orient timers: the rest is "other"
        d["other"] = d["total"] - sum(d.get(k, 0.0) for k in keys[2:-1])
    d["iterations"] = float(re.search(r"iterations ([0-9.]+)", rest).group(1))
    m = re.search(r"energy evaluations ([0-9.]+)", rest)
    if m: d["evals/it"] = float(m.group(1))
    d["hash"] = re.search(r"hash ([0-9a-f]+)", rest).group(1)
    rows.setdefault(tag, []).append(d)
cols = keys + ["iterations", "evals/it"]
med = {t: {k: statistics.median(r[k] for r in rows[t]) for k in cols if k in rows[t][0]} for t in rows}
tags = sorted(rows)
print("%-6s" % "" + "".join("%11s" % k for k in cols) + "  hash")
for t in tags:
    print("%-6s" % t + "".join("%11.2f" % med[t].get(k, float("nan")) for k in cols) +
          "  " + ",".join(sorted(set(r["hash"] for r in rows[t]))))
for t in tags[1:]:
    print("%-6s" % (t + "/" + tags[0]) + "".join("%11.2f" % (med[t][k] / med[tags[0]][k] if med[tags[0]].get(k) else float("nan")) for k in keys))
# The fastest round of each: the run a busy neighbour disturbed least (the
# times are CPU-bound and deterministic, so noise only adds); read beside the
# medians when they disagree.
low = {t: {k: min(r[k] for r in rows[t]) for k in keys if k in rows[t][0]} for t in rows}
print("fastest round of each:")
for t in tags:
    print("%-6s" % t + "".join("%11.2f" % low[t].get(k, float("nan")) for k in keys))
for t in tags[1:]:
    print("%-6s" % (t + "/" + tags[0]) + "".join("%11.2f" % (low[t][k] / low[tags[0]][k] if low[tags[0]].get(k) else float("nan")) for k in keys))
PYEOF
