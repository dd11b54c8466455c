#!/usr/bin/env bash
# skinsim run --reference: the reference is cached (the second run reads it:
# reference_cache_hit), a corrupted or truncated cache file is detected and
# recomputed (never trusted), the reference configuration itself has error 0,
# a coarser run has error > 0, an unusable cache folder is one clear error, and
# the key's code digest (cmake/code_digest.cmake) follows the code: another
# source text, another digest; the build's digest is that of its sources now.
# Usage: test_skinsim_reference.sh BUILD_DIR [SOURCE_DIR]
set -u
. "$(dirname "$0")/lib.sh"   # bld, src, exe, tmp, py, check
field() { /usr/bin/python3 -c "import json,sys; v=json.load(open(sys.argv[1]))[sys.argv[2]]; print(v)" "$1" "$2"; }
export OPENBLAS_NUM_THREADS=1
run=(run --scene elbow --tris 300 --frames 8 --reference --cache "$tmp/cache")

"$exe" "${run[@]}" --json "$tmp/a.json" > /dev/null; rc=$?
check "first run exits 0" "[ $rc -eq 0 ]"
check "first run computes the reference" "[ \"\$(field $tmp/a.json reference_cache_hit)\" = 0 ]"
check "one cache file" "[ \$(ls '$tmp/cache' | wc -l) -eq 1 ]"
e1=$(field "$tmp/a.json" error_vs_reference)
check "error of the default run is > 0 ($e1)" \
  "/usr/bin/python3 -c 'import sys; sys.exit(0 if 0 < $e1 < 10 else 1)'"

"$exe" "${run[@]}" --json "$tmp/b.json" > /dev/null
check "second run hits the cache" "[ \"\$(field $tmp/b.json reference_cache_hit)\" = 1 ]"
check "same error from the cache" "[ \"\$(field $tmp/b.json error_vs_reference)\" = '$e1' ]"

file=$(ls "$tmp/cache"/ref_*.bin)
size=$(stat -c %s "$file")
printf '\x7f' | dd of="$file" bs=1 seek=$(( size / 2 )) conv=notrunc 2> /dev/null
"$exe" "${run[@]}" --json "$tmp/c.json" > /dev/null
check "a corrupted cache file is rejected" \
  "[ \"\$(field $tmp/c.json reference_cache_rejected)\" = 1 ] && [ \"\$(field $tmp/c.json reference_cache_hit)\" = 0 ]"
check "... recomputed to the same error" "[ \"\$(field $tmp/c.json error_vs_reference)\" = '$e1' ]"
"$exe" "${run[@]}" --json "$tmp/d.json" > /dev/null
check "... and rewritten (next run hits)" "[ \"\$(field $tmp/d.json reference_cache_hit)\" = 1 ]"
head -c 1000 "$file" > "$tmp/short" && cp "$tmp/short" "$file"
"$exe" "${run[@]}" --json "$tmp/e.json" > /dev/null
check "a truncated cache file is rejected" "[ \"\$(field $tmp/e.json reference_cache_rejected)\" = 1 ]"
key=$(basename "$file")
"$exe" run --scene elbow --tris 300 --frames 9 --reference --cache "$tmp/cache" --json "$tmp/f.json" > /dev/null
cp "$tmp/cache/ref_$(field $tmp/f.json reference_key).bin" "$file"
"$exe" "${run[@]}" --json "$tmp/g.json" > /dev/null
check "another configuration's file under this key is rejected" \
  "[ \"\$(field $tmp/g.json reference_cache_rejected)\" = 1 ] && [ \"\$(field $tmp/g.json error_vs_reference)\" = '$e1' ]"

"$exe" run --scene elbow --tris 300 --frames 8 --reference --cache "$tmp/cache" --solver newton \
  --substeps 16 --iterations 100 --tol 1e-6 --json "$tmp/r.json" > /dev/null; rc=$?
check "the reference configuration runs" "[ $rc -eq 0 ]"
check "the reference configuration has error 0" "[ \"\$(field $tmp/r.json error_vs_reference)\" = 0 ]"
"$exe" run --scene elbow --tris 300 --frames 8 --reference --cache "$tmp/cache" --substeps 4 \
  --json "$tmp/s.json" > /dev/null
check "more substeps: the same reference (slide is a rate per second)" \
  "[ \"\$(field $tmp/s.json reference_key)\" = \"\$(field $tmp/a.json reference_key)\" ]"
"$exe" run --scene elbow --tris 300 --frames 8 --json "$tmp/n.json" > /dev/null
check "without --reference no error field" "! grep -q error_vs_reference '$tmp/n.json'"

# the code digest: the same files give the same header (not rewritten), a changed
# file another digest; the built header is the digest of the build's sources
digest() { cmake -DLIST="$1" -DROOT="$tmp" -DOUT="$2" -P "$src/cmake/code_digest.cmake"; }
printf 'int a;\n' > "$tmp/d1.c"; printf 'int b;\n' > "$tmp/d2.c"
printf '%s\n' "$tmp/d1.c" "$tmp/d2.c" > "$tmp/dlist"
digest "$tmp/dlist" "$tmp/dig.h"; cp "$tmp/dig.h" "$tmp/dig0.h"; touch -d @1 "$tmp/dig.h"
digest "$tmp/dlist" "$tmp/dig.h"
check "code digest: same sources, same header, left untouched" \
  "cmp -s '$tmp/dig.h' '$tmp/dig0.h' && [ \$(stat -c %Y '$tmp/dig.h') -eq 1 ]"
printf 'int a; /* changed */\n' > "$tmp/d1.c"
digest "$tmp/dlist" "$tmp/dig.h"
check "code digest: a changed source, another digest" "! cmp -s '$tmp/dig.h' '$tmp/dig0.h'"
gen=$(find -L "$bld" -name ss_code_digest.h -path '*generated*' 2> /dev/null | head -n 1)
lst="$(dirname "$gen")/code_digest_files.txt"
if [ -f "$gen" ] && [ -f "$lst" ]; then
  cmake -DLIST="$lst" -DROOT="$src" -DOUT="$tmp/now.h" -P "$src/cmake/code_digest.cmake"
  check "the built code digest is that of the sources" "cmp -s '$gen' '$tmp/now.h'"
else
  check "the build has its code digest header" false
fi

touch "$tmp/notadir"
"$exe" "${run[@]:0:7}" --reference --cache "$tmp/notadir/sub" > /dev/null 2> "$tmp/err"; rc=$?
check "unusable cache folder: exit 2, one message" "[ $rc -eq 2 ] && [ \$(wc -l < '$tmp/err') -eq 1 ]"
exit $fail
