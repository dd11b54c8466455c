# shellcheck shell=bash
# tests/check.sh: the test scripts' one check, sourced by tests/ros/ros_env.sh,
# tests/tool/lib.sh and the scripts that need nothing else:
#
#   check NAME EXPR   evals EXPR; prints "ok: NAME", or "FAIL: NAME", sets fail=1
#                     (the status the script exits with: `exit $fail`) and returns 1,
#                     so that `check ... || tail LOG` shows a log on failure only.
fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; return 1; fi; }
