#!/usr/bin/env bash
# Writes the manual's generated tables: in every doc/*.md, the lines between
#   <!-- generated: skinsim settings --markdown (bash scripts/doc_tables.sh) -->
#   <!-- end of generated table -->
# become the output of `skinsim settings --markdown` (the one settings table,
# src/core/settings.c), and those between
#   <!-- generated: skin_sim_node --params-markdown (bash scripts/doc_tables.sh) -->
#   <!-- end of generated table -->
# the node's own parameter table (src/nodes/skin_params.c; where the build has the
# node, i.e. ROS). Run it after changing a setting or a parameter;
# tests/tool/test_doc_tables.sh fails while a page and a table disagree.
#
#   bash scripts/doc_tables.sh [BUILD_DIR]           # rewrite the pages (default build/release)
#   bash scripts/doc_tables.sh --check [BUILD_DIR]   # exit 1, showing the difference, if any
#                                                    # page is out of date; change nothing
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
src="$(cd "$(dirname "$0")/.." && pwd)"
check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
bld="${1:-$src/build/release}"
exe=$(find -L "$bld" -type f -name skinsim -perm -u+x 2> /dev/null | head -n 1)
[ -n "$exe" ] || { echo "doc_tables.sh: no skinsim under $bld (build first: bash scripts/build.sh $bld)" >&2; exit 2; }
node=$(find -L "$bld" -type f -name skin_sim_node -perm -u+x 2> /dev/null | head -n 1)
table=$(mktemp)
ntable=$(mktemp)
trap 'rm -f "$table" "$ntable"' EXIT
"$exe" settings --markdown > "$table"
if [ -n "$node" ]; then "$node" --params-markdown > "$ntable"; else : > "$ntable"; fi
/usr/bin/python3 - "$table" "$check" "$ntable" "$src"/doc/*.md <<'PY'
import difflib, re, sys
tables = [("<!-- generated: skinsim settings --markdown (bash scripts/doc_tables.sh) -->",
           open(sys.argv[1]).read())]
node_table = open(sys.argv[3]).read()
if node_table:  # a build without ROS has no node: its block is left as it is
    tables.append(("<!-- generated: skin_sim_node --params-markdown (bash scripts/doc_tables.sh) -->",
                   node_table))
check = sys.argv[2] == "1"
end = "<!-- end of generated table -->"
stale = 0
found = 0
for page in sys.argv[4:]:
    text = open(page).read()
    new = text
    for begin, table in tables:
        block = re.compile(re.escape(begin) + r"\n.*?" + re.escape(end), re.S)
        new, n = block.subn(lambda m: begin + "\n" + table + end, new)
        found += n
    if new == text:
        continue
    stale += 1
    if check:
        sys.stdout.writelines(difflib.unified_diff(text.splitlines(True), new.splitlines(True),
                                                   page, page + " (from skinsim settings --markdown)"))
    else:
        open(page, "w").write(new)
        print("doc_tables.sh: wrote %s" % page)
if found == 0:
    print("doc_tables.sh: no generated table in doc/*.md")
    sys.exit(1)
if check and stale:
    print("doc_tables.sh: %d page(s) disagree with the settings table: run bash scripts/doc_tables.sh" % stale)
    sys.exit(1)
print("doc_tables.sh: %d table(s) in doc/ %s" % (found, "agree with the settings table" if check else "up to date"))
PY
