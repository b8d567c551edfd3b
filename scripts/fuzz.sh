#!/usr/bin/env bash
# The long fuzz run of docs/guide/refusals.md: MUTANTS mutants of the shipped pipelines through
# `stickslip check` and RUNS of the accepted ones through a `stickslip run` bounded to 30 s, on
# up to 4 workers; it prints the figures (mutants, refused, accepted, runs, panics, hangs,
# refusals without a field, 25-digit numbers, non-finite values in tables) and fails on any
# defect, with examples. The suite's own fuzz test is the same code at a few hundred mutants.
#   scripts/fuzz.sh [mutants, default 10000] [runs, default 500] [seed, default 2026]
set -euo pipefail
case ${1:-} in
    -h | --help) sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
esac
mutants=${1:-10000} runs=${2:-500} seed=${3:-2026}
for v in "$mutants" "$runs" "$seed"; do
    [[ $v =~ ^[0-9]+$ ]] || { echo "usage: scripts/fuzz.sh [mutants] [runs] [seed] (whole numbers)" >&2; exit 2; }
done
cd "$(dirname "$0")/.."
STICKSLIP_FUZZ_MUTANTS=$mutants STICKSLIP_FUZZ_RUNS=$runs STICKSLIP_FUZZ_SEED=$seed \
    exec cargo test --release -p stickslip --test fuzz -- --ignored --nocapture --exact fuzz_long
