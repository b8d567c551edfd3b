#!/usr/bin/env bash
# What two threads can give on this machine (BENCHMARKS.md §8): one seed of
# `pipelines/large-block.toml` at SIZE (default 200x50x20:0.02, 2.8 M bars) run
#   (a) alone on 1 thread, (b) alone on 2 threads, (c) as two independent 1-thread processes at once.
# (c) shares nothing but the machine (cores, caches, memory bandwidth), so 2·(a)/(c) is the most any
# two-thread run can gain here; (a)/(b) is what the solver's threads gain. REPEATS rounds (default 2),
# alternating; prints each round's walls and the ratios of the best of each.
#   crates/lab/large/ceiling.sh [NXxNYxNZ:DURATION_S]
set -euo pipefail
cd "$(dirname "$0")/../../.."
. crates/lab/large/scene.sh
stickslip_binary
size=${1:-200x50x20:0.02}
dims=${size%%:*}; duration=${size#*:}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
toml=$work/large-$dims.toml
large_block "$dims" "$duration" "$toml"
wall() { # threads out -> seconds
    local start end
    start=$(date +%s.%N)
    "$STICKSLIP" pipeline "$toml" --seeds 1 --threads "$1" --out "$2" --fresh -q >/dev/null
    end=$(date +%s.%N)
    rm -rf "$2"
    awk -v a="$start" -v b="$end" 'BEGIN { print b - a }'
}
best1=1e9; best2=1e9; bestc=1e9
for round in $(seq "${REPEATS:-2}"); do
    t1=$(wall 1 "$work/a"); t2=$(wall 2 "$work/b")
    wall 1 "$work/c1" >"$work/c1.t" & wall 1 "$work/c2" >"$work/c2.t" & wait
    c1=$(cat "$work/c1.t"); c2=$(cat "$work/c2.t")
    tc=$(awk -v a="$c1" -v b="$c2" 'BEGIN { print (a > b ? a : b) }')
    printf 'round %d: 1 thread %.2f s, 2 threads %.2f s, two 1-thread processes together %.2f s and %.2f s\n' \
        "$round" "$t1" "$t2" "$c1" "$c2"
    best1=$(awk -v a="$t1" -v b="$best1" 'BEGIN { print (a < b ? a : b) }')
    best2=$(awk -v a="$t2" -v b="$best2" 'BEGIN { print (a < b ? a : b) }')
    bestc=$(awk -v a="$tc" -v b="$bestc" 'BEGIN { print (a < b ? a : b) }')
done
printf 'best: 1 thread %.2f s, 2 threads %.2f s (%.2fx), two processes %.2f s (%.2fx the work of one in that time)\n' \
    "$best1" "$best2" "$(awk -v a="$best1" -v b="$best2" 'BEGIN { print a / b }')" \
    "$bestc" "$(awk -v a="$best1" -v b="$bestc" 'BEGIN { print 2 * a / b }')"
