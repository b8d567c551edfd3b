#!/usr/bin/env bash
# Throughput side by side with LAMMPS (Debian's `lammps`, binary `lmp`, serial) on the same
# lattices: atoms at our nodes with our masses, harmonic bonds with our stiffnesses and rest
# lengths (LAMMPS's K = EA/(2L)), pair_style none, a neighbour list that never rebuilds,
# fix nve + fix viscous (γ = D·m per type), the same Δt and number of steps, one core each.
#   crates/lab/lammps/compare.sh [steps scale, default 1]
# SIZES replaces the lattices and their steps, e.g. SIZES="200x50x20x100" (2.8 M bars, 100 steps).
# Prints bond-updates per second of LAMMPS, ours with one seed and ours with 8 seeds side by side,
# and the ratios. BENCH names another build's benchmark command (e.g. an older commit's binary),
# to compare two builds against the same LAMMPS runs.
set -euo pipefail
cd "$(dirname "$0")/../../.."
command -v lmp >/dev/null || { echo "LAMMPS (lmp) not found: install Debian's lammps package (apt-get install lammps)" >&2; exit 1; }
if [ -z "${BENCH:-}" ]; then
    cargo build --release -q -p stickslip-lab --bin stickslip-bench
    BENCH="${CARGO_TARGET_DIR:-target}/release/stickslip-bench"
fi
scale=${1:-1}
work=$(mktemp -d)
printf '%-12s %10s %8s %14s %14s %14s %9s %9s\n' lattice bars steps lammps ours_1seed ours_8seeds ratio_1 ratio_8
sizes=${SIZES:-"10x1x5x40000 40x20x4x1000 100x50x10x100"}
for size in $sizes; do
    set -- ${size//x/ }
    steps=$(( $4 * scale ))
    dir=$work/$1x$2x$3
    # Best of three runs for each side, alternating, both pinned to core 0.
    ours1=0; ours8=0; lmp_rate=0
    for _ in 1 2 3; do
        out=$(taskset -c 0 $BENCH peer "$1" "$2" "$3" "$steps" "$dir")
        bars=$(awk '/^bars/ { print $2 }' <<<"$out")
        ours1=$(awk -v a="$ours1" '/^ours_1 / { print ($2 > a ? $2 : a) }' <<<"$out")
        ours8=$(awk -v a="$ours8" '/^ours_8 / { print ($2 > a ? $2 : a) }' <<<"$out")
        (cd "$dir" && OMP_NUM_THREADS=1 taskset -c 0 lmp -in in.lattice -log log.lammps -screen none)
        loop=$(awk '/^Loop time of/ { print $4 }' "$dir/log.lammps")
        lmp_rate=$(awk -v b="$bars" -v s="$steps" -v t="$loop" -v a="$lmp_rate" 'BEGIN { r = b * s / t; printf "%.4e", (r > a ? r : a) }')
    done
    awk -v n="$1x$2x$3" -v b="$bars" -v s="$steps" -v l="$lmp_rate" -v o1="$ours1" -v o8="$ours8" \
        'BEGIN { printf "%-12s %10d %8d %14.3e %14.3e %14.3e %8.2fx %8.2fx\n", n, b, s, l, o1, o8, o1 / l, o8 / l }'
done
rm -rf "$work"
