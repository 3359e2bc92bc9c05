#!/usr/bin/env bash
# CHOLMOD vs ecc's factorisation on the same matrices (issue #11).
#
#   bash benches/cholmod/run.sh [OUT_DIR] [ROUNDS] [REPEATS] [MATRIX…]
#
# Export the first projected Newton matrices (export_hessians; also the
# uniform Tutte system of the disk, `disk_tutte`, when named), then time
# CHOLMOD (cholmod_bench: METIS and AMD, supernodal, OpenBLAS) and ecc
# (factor_bench: every ordering and thread policy) on them. Each round runs
# the configurations one after the other (CHOLMOD 1T, CHOLMOD 2T, ecc), each
# process doing REPEATS timed factorisations, so the load of a shared machine
# hits them alike; the table takes the best over all rounds. Needs Debian's
# libsuitesparse-dev and libopenblas-dev. Not part of CI.
#
# OUT_DIR (default target/cholmod) receives the .mtx files (large: ~0.3 GB
# for the 1M-triangle disk), runs.jsonl (every JSON line, with the commit
# and `uptime`) and table.md.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-$root/target/cholmod}
rounds=${2:-5}
repeats=${3:-1}
shift $(( $# < 3 ? $# : 3 ))
matrices=("$@")
[ ${#matrices[@]} -gt 0 ] || matrices=(camelhead armadillo_cut_low hand_1_i_f5000 disk hand_arap hand_snh)
mkdir -p "$out"
out=$(cd "$out" && pwd)  # absolute: make -C below changes directory

cd "$root"
# BIN_DIR=…: use export_hessians/factor_bench already built there (e.g. from a clean worktree)
if [ -z "${BIN_DIR:-}" ]; then
  cargo build --release -q -p ecc-benches --features metis --bin export_hessians --bin factor_bench
fi
bin=${BIN_DIR:-$root/target/release}
make -s -C benches/cholmod OUT="$out"

for m in "${matrices[@]}"; do
  [ -f "$out/$m.mtx" ] || "$bin/export_hessians" --out "$out" "$m" >> "$out/export.jsonl"
done

runs=$out/runs.jsonl
commit=${COMMIT:-$(git rev-parse --short HEAD)}  # COMMIT=…: the sources BIN_DIR was built from
for ((r = 1; r <= rounds; r++)); do
  for m in "${matrices[@]}"; do
    f=$out/$m.mtx
    for t in 1 2; do
      echo "{\"round\":$r,\"commit\":\"$commit\",\"uptime\":\"$(uptime | sed 's/.*load/load/')\"}" >> "$runs"
      OMP_WAIT_POLICY=passive OMP_THREAD_LIMIT=$t OMP_NUM_THREADS=$t OPENBLAS_NUM_THREADS=$t \
        "$out/cholmod_bench" "$f" --repeats "$repeats" --threads "$t" >> "$runs"
    done
    echo "{\"round\":$r,\"commit\":\"$commit\",\"uptime\":\"$(uptime | sed 's/.*load/load/')\"}" >> "$runs"
    "$bin/factor_bench" "$f" --repeats "$repeats" --pool 2 >> "$runs"
  done
done
python3 "$root/benches/cholmod/table.py" "$runs" "$out/export.jsonl" > "$out/table.md"
cat "$out/table.md"
