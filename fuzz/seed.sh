#!/bin/sh
# Fills fuzz/corpus/<target>/ with seed inputs from the shared reference material: every seed
# example (../shared/spec/examples) and every real program (../shared/corpus). Files over 64 KiB
# are cut to their first 16 KiB so that libFuzzer's input size stays small. The corpus is
# gitignored: what this copies stays on this machine.
#
# Usage: fuzz/seed.sh [target ...]   (default: interpret parse_iso)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
shared=${VCNC_SHARED:-$here/../../shared}
if [ ! -d "$shared/spec/examples" ]; then
    echo "seed.sh: no reference material at $shared (set VCNC_SHARED)" >&2
    exit 1
fi
[ $# -gt 0 ] || set -- interpret parse_iso
for target in "$@"; do
    dir=$here/corpus/$target
    mkdir -p "$dir"
    find "$shared/spec/examples" "$shared/corpus" -type f ! -name '*.md' | while read -r file; do
        name=$(echo "${file#"$shared"/}" | tr '/' '_')
        if [ "$(wc -c < "$file")" -gt 65536 ]; then
            head -c 16384 "$file" > "$dir/$name"
        else
            cp "$file" "$dir/$name"
        fi
    done
    echo "seed.sh: $(ls "$dir" | wc -l) inputs in $dir"
done
