#!/bin/sh
# Records LinuxCNC's execution time of the planner reference programs as test fixtures.
#
# Each program in crates/vcnc/tests/data/plan/lcnc/*.ngc names the machine limits it is timed
# with in its first line, `(limits: --vel V --acc A)`; LinuxCNC's real trajectory planner runs it
# through lcnc-time (../shared/tools/lcnc-time, see its README) and the JSON report is stored
# beside the program as <stem>.json. tests/it/plan_reference.rs reads those files: the test suite
# never needs LinuxCNC.
#
# Usage: tools/record-lcnc-time.sh [STEM ...]      (no stem: every program)
# LCNC_TIME overrides the path of the lcnc-time harness.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
dir="$root/crates/vcnc/tests/data/plan/lcnc"
lcnc_time=${LCNC_TIME:-"$root/../shared/tools/lcnc-time/lcnc-time"}
if [ ! -x "$lcnc_time" ]; then
    echo "lcnc-time not found at $lcnc_time (set LCNC_TIME)" >&2
    exit 2
fi
if [ $# -eq 0 ]; then
    set -- $(cd "$dir" && ls *.ngc | sed 's/\.ngc$//')
fi
for stem in "$@"; do
    program="$dir/$stem.ngc"
    limits=$(sed -n '1s/^(limits: \(.*\))$/\1/p' "$program")
    if [ -z "$limits" ]; then
        echo "$program: first line must be (limits: --vel V --acc A)" >&2
        exit 2
    fi
    # The limits are word-split on purpose: they are options.
    # shellcheck disable=SC2086
    # The program's path is stored without this machine's directories.
    "$lcnc_time" "$program" $limits --json -q |
        sed 's|"program": ".*/\([^/]*\)"|"program": "\1"|' > "$dir/$stem.json.tmp"
    mv "$dir/$stem.json.tmp" "$dir/$stem.json"
    printf '%s %s\n' "$stem" "$(sed -n 's/^ *"seconds": \([0-9.]*\),*$/\1/p' "$dir/$stem.json")"
done
