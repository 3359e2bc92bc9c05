#!/usr/bin/env bash
# Merge corpus-raw/<target> into a minimal corpus/<target> (the committed
# one): only inputs that add coverage are kept. Usage: fuzz/minimize.sh TARGET
set -euo pipefail
cd "$(dirname "$0")"
target=$1
mkdir -p "corpus/$target" "corpus-min/$target"
RUSTC_BOOTSTRAP=1 cargo fuzz run -O "$target" -- -merge=1 -max_len=4096 -timeout=10 \
    "corpus-min/$target" "corpus/$target" "corpus-raw/$target"
rm -rf "corpus/$target"
mv "corpus-min/$target" "corpus/$target"
rmdir corpus-min 2>/dev/null || true
echo "corpus/$target: $(ls "corpus/$target" | wc -l) inputs"
