#!/usr/bin/env bash
# The manual's settings tables (doc/ros.md, doc/cli.md) are the settings table itself:
# every block between the "generated" markers in doc/*.md must be exactly what
# `skinsim settings --markdown` prints now. After a setting is added or changed,
# regenerate them with one command:
#   bash scripts/doc_tables.sh [BUILD_DIR]
# Also checks that the check can fail: a page with a stale row is caught.
# Usage: test_doc_tables.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
. "$src/tests/check.sh"
bash "$src/scripts/doc_tables.sh" --check "$bld" > /tmp/doc_tables.$$ 2>&1; rc=$?
cat /tmp/doc_tables.$$
check "doc/*.md's generated tables agree with skinsim settings --markdown" "[ $rc -eq 0 ]"
check "doc/ros.md and doc/cli.md each hold one" \
  "! grep -c 'generated: skinsim settings' '$src/doc/ros.md' '$src/doc/cli.md' | grep -q ':0$'"
# a copy of the tree with one row changed must fail the check
tmp=$(mktemp -d)
mkdir -p "$tmp/scripts" "$tmp/doc"
cp "$src/scripts/doc_tables.sh" "$tmp/scripts/"
cp "$src"/doc/*.md "$tmp/doc/"
sed -i 's/^| `~poisson` | \(.*\) 0\.3 |/| `~poisson` | \1 0.35 |/; s/^\(| `~poisson` |[^|]*| double, \)0\.3/\10.35/' "$tmp/doc/ros.md"
bash "$tmp/scripts/doc_tables.sh" --check "$bld" > /tmp/doc_tables.$$ 2>&1; rc=$?
check "a page whose ~poisson row says 0.35 is caught (exit $rc)" "[ $rc -eq 1 ] && grep -q 'poisson' /tmp/doc_tables.$$"
rm -rf "$tmp" /tmp/doc_tables.$$
exit $fail
