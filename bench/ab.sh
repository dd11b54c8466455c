#!/usr/bin/env bash
# A/B timing of two builds of bench_sim on a shared machine: runs the two
# binaries alternately ROUNDS times with the same arguments and prints, per
# binary, the median over the rounds of each per-frame median bench_sim
# reports (total, cpu, pose, walk, assemble, factor, solve), the iterations,
# the hash, and the ratio B/A of each time.
#
#   bash bench/ab.sh A_BENCH_SIM B_BENCH_SIM ROUNDS [bench_sim arguments...]
#   e.g. bash bench/ab.sh /tmp/base/devel/lib/skin_sim/bench_sim \
#          build/release/devel/lib/skin_sim/bench_sim 5 quadruped 19000 60 quasi-newton 1 8 1e-4 walk 1
#
# Read "cpu" (process CPU time per step) for one thread on a loaded machine:
# wall-clock times there mostly measure the other jobs.
set -euo pipefail
a="${1:?usage: ab.sh A B ROUNDS [bench_sim args]}"
b="${2:?usage: ab.sh A B ROUNDS [bench_sim args]}"
rounds="${3:?usage: ab.sh A B ROUNDS [bench_sim args]}"
shift 3
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
for ((r = 0; r < rounds; r++)); do
  echo "A $("$a" "$@")" >>"$out"
  echo "B $("$b" "$@")" >>"$out"
done
/usr/bin/python3 - "$out" <<'EOF'
import re, statistics, sys
keys = ["total", "cpu", "pose", "walk", "assemble", "factor", "solve"]
rows = {"A": [], "B": []}
for line in open(sys.argv[1]):
    tag, rest = line.split(" ", 1)
    d = {k: float(re.search(r"\b%s ([0-9.]+)" % k, rest).group(1)) for k in keys if re.search(r"\b%s ([0-9.]+)" % k, rest)}
    d["iterations"] = float(re.search(r"iterations ([0-9.]+)", rest).group(1))
    d["hash"] = re.search(r"hash ([0-9a-f]+)", rest).group(1)
    rows[tag].append(d)
med = {t: {k: statistics.median(r[k] for r in rows[t]) for k in keys + ["iterations"] if k in rows[t][0]} for t in rows}
print("%-4s" % "" + "".join("%10s" % k for k in keys + ["iterations"]) + "  hash")
for t in "AB":
    print("%-4s" % t + "".join("%10.2f" % med[t].get(k, float("nan")) for k in keys + ["iterations"]) +
          "  " + ",".join(sorted(set(r["hash"] for r in rows[t]))))
print("%-4s" % "B/A" + "".join("%10.2f" % (med["B"][k] / med["A"][k] if med["A"].get(k) else float("nan")) for k in keys))
EOF
