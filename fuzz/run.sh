#!/usr/bin/env bash
# Fuzz one target for a while, starting from the seeds and the committed
# corpus; new inputs go to corpus-raw/<target> (not committed; see
# minimize.sh). Usage: fuzz/run.sh TARGET [SECONDS] [extra libFuzzer flags]
set -euo pipefail
cd "$(dirname "$0")"
target=$1
secs=${2:-600}
shift $(( $# >= 2 ? 2 : 1 ))
mkdir -p "corpus-raw/$target" "corpus/$target"
cp -n seeds/"$target"/* "corpus-raw/$target/" 2>/dev/null || true
cp -n corpus/"$target"/* "corpus-raw/$target/" 2>/dev/null || true
# Stable toolchain: RUSTC_BOOTSTRAP=1 unlocks the -Z sanitizer flags cargo-fuzz passes.
RUSTC_BOOTSTRAP=1 cargo fuzz run -O "$target" "corpus-raw/$target" -- \
    -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
    -print_final_stats=1 "$@"
