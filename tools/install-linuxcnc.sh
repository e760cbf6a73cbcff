#!/bin/sh
# Installs LinuxCNC 2.9 from Debian's packages: `rs274` for `cargo xtask record-lcnc` and the
# trajectory planner that ../shared/tools/lcnc-time runs for tools/record-lcnc-time.sh. Only
# recording needs it; the tests read what was recorded. Run as root.
set -eu
if command -v rs274 >/dev/null 2>&1 && command -v milltask >/dev/null 2>&1; then
    echo "LinuxCNC is installed: $(command -v rs274)"
    exit 0
fi
apt-get update
DEBIAN_FRONTEND=noninteractive apt-get install -y linuxcnc-uspace
