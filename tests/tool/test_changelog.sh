#!/usr/bin/env bash
# CHANGELOG.rst is in catkin's format (catkin_pkg reads it as catkin_generate_changelog
# and bloom do) and its newest version is package.xml's: the version moves with the
# changelog. Skipped (77) without python3-catkin-pkg.
# Usage: test_changelog.sh BUILD_DIR [SOURCE_DIR].
set -u
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
/usr/bin/python3 -c 'import catkin_pkg.changelog' 2> /dev/null || { echo "skipped: python3-catkin-pkg absent"; exit 77; }
/usr/bin/python3 - "$src" <<'PY'
import sys
from catkin_pkg.changelog import get_changelog_from_path
from catkin_pkg.package import parse_package
src = sys.argv[1]
log = get_changelog_from_path(src + "/CHANGELOG.rst", "skin_sim")
pkg = parse_package(src + "/package.xml")
versions = sorted((v for v, _, _ in log.foreach_version()),
                  key=lambda v: tuple(int(x) for x in v.split(".")), reverse=True)
first = open(src + "/CHANGELOG.rst").read().split("(", 1)[0].split()[-1]
fail = 0
def check(name, ok):
    global fail
    print(("ok: " if ok else "FAIL: ") + name)
    fail |= not ok
check("CHANGELOG.rst parses, with versions %s" % ", ".join(versions), len(versions) > 0)
check("its newest version %s is package.xml's %s" % (versions[0] if versions else "-", pkg.version),
      bool(versions) and versions[0] == pkg.version)
check("the newest version comes first in the file (%s)" % first, bool(versions) and first == versions[0])
check("every version has entries", all(len(list(log.get_content_of_version(v))) > 0 for v in versions))
sys.exit(fail)
PY
