#!/bin/sh
# Records LinuxCNC's execution time of the planner reference programs as test fixtures.
#
# Each program in crates/vcnc/tests/data/plan/lcnc/*.ngc names the machine limits it is timed
# with in its first line, `(limits: --vel V --acc A)`; LinuxCNC's real trajectory planner runs it
# through lcnc-time (../shared/tools/lcnc-time, see its README) and the JSON report is stored
# beside the program as <stem>.json. tests/it/plan_reference.rs reads those files: the test suite
# never needs LinuxCNC.
#
# A blend tolerance goes in the program (`G64 P0.02 Q0`), never through lcnc-time's --blend-tol:
# that option writes G64 P into the start-up code, which does not reach LinuxCNC's motion planner
# (a square at F6000: 3.768 s plain and with --blend-tol 0.001, 4.897 s with G64 P0.001 in the
# program).
#
# The random programs of `cargo xtask gen-plan-programs` are in random/: name them as
# `random/arcs_01`. Already recorded programs are skipped unless named or FORCE=1 is set.
#
# Usage: tools/record-lcnc-time.sh [STEM ...]      (no stem: every program not yet recorded)
# LCNC_TIME overrides the path of the lcnc-time harness; tools/install-linuxcnc.sh installs LinuxCNC.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
dir="$root/crates/vcnc/tests/data/plan/lcnc"
lcnc_time=${LCNC_TIME:-"$root/../shared/tools/lcnc-time/lcnc-time"}
if [ ! -x "$lcnc_time" ]; then
    echo "lcnc-time not found at $lcnc_time (set LCNC_TIME)" >&2
    exit 2
fi
named=$#
failed=0
if [ $# -eq 0 ]; then
    set -- $(cd "$dir" && ls *.ngc random/*.ngc 2>/dev/null | sed 's/\.ngc$//')
fi
for stem in "$@"; do
    if [ "$named" -eq 0 ] && [ -z "${FORCE:-}" ] && [ -s "$dir/$stem.json" ]; then
        continue
    fi
    program="$dir/$stem.ngc"
    limits=$(sed -n '1s/^(limits: \(.*\))$/\1/p' "$program")
    if [ -z "$limits" ]; then
        echo "$program: first line must be (limits: --vel V --acc A)" >&2
        exit 2
    fi
    # The limits are word-split on purpose: they are options. LinuxCNC's start fails now and
    # then on a loaded machine (rtapi_app not ready): up to three tries, and a run that gives
    # no time leaves no file behind.
    # shellcheck disable=SC2086
    tries=0
    while :; do
        tries=$((tries + 1))
        # The program's path is stored without this machine's directories.
        if "$lcnc_time" "$program" $limits --json -q > "$dir/$stem.json.tmp" &&
            grep -q '"seconds"' "$dir/$stem.json.tmp"; then
            break
        fi
        if [ "$tries" -ge 3 ]; then
            rm -f "$dir/$stem.json.tmp"
            echo "$stem: lcnc-time failed $tries times" >&2
            failed=$((failed + 1))
            continue 2
        fi
    done
    sed 's|"program": ".*/\([^/]*\)"|"program": "\1"|' "$dir/$stem.json.tmp" > "$dir/$stem.json"
    rm -f "$dir/$stem.json.tmp"
    printf '%s %s\n' "$stem" "$(sed -n 's/^ *"seconds": \([0-9.]*\),*$/\1/p' "$dir/$stem.json")"
done
[ "$failed" -eq 0 ] || { echo "$failed program(s) not recorded" >&2; exit 1; }
