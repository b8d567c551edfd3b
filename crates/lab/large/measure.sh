#!/usr/bin/env bash
# Memory and speed of one seed at size (BENCHMARKS.md §8): `pipelines/large-block.toml` at three
# sizes, each run as a whole (`stickslip pipeline --seeds 1`: set-up, steps, analysis, tables)
# under /usr/bin/time -v on 1 and 2 threads, peak resident memory and wall time read from it,
# the steps and Δt from the runs table. BEFORE names another build's `stickslip` to run the same
# files side by side (alternating, the same sizes and threads).
#   crates/lab/large/measure.sh [sizes...]   sizes as NXxNYxNZ:DURATION_S, default
#                                             200x50x20:0.02 400x100x36:0.0095 500x150x48:0.0095
# Prints one line per size, binary and thread count: bars, nodes, steps, wall s, peak RSS MB,
# bytes per bar, bytes per node, bar-updates/s of the whole run.
set -euo pipefail
cd "$(dirname "$0")/../../.."
. crates/lab/large/scene.sh
stickslip_binary
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(200x50x20:0.02 400x100x36:0.0095 500x150x48:0.0095)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bins=("after=$STICKSLIP")
[ -n "${BEFORE:-}" ] && bins+=("before=$BEFORE")
printf '%-12s %-7s %3s %11s %10s %6s %9s %9s %8s %8s %11s\n' \
    block build thr bars nodes steps wall_s peak_MB B/bar B/node updates/s
for size in "${sizes[@]}"; do
    dims=${size%%:*}; duration=${size#*:}
    IFS=x read -r nx ny nz <<<"$dims"
    toml=$work/large-$dims.toml
    large_block "$dims" "$duration" "$toml"
    # Closed forms of docs/model.md §1.
    bars=$(( nx*(ny+1)*(nz+1) + (nx+1)*ny*(nz+1) + (nx+1)*(ny+1)*nz + 8*nx*ny*nz + (nx-1)*ny*nz + nx*(ny-1)*nz + nx*ny*(nz-1) ))
    nodes=$(( (nx+1)*(ny+1)*(nz+1) + nx*ny*nz ))
    for threads in 1 2; do
        for entry in "${bins[@]}"; do
            name=${entry%%=*}; bin=${entry#*=}
            out=$work/out-$name-$dims-$threads
            /usr/bin/time -v "$bin" pipeline "$toml" --seeds 1 --threads "$threads" --out "$out" --fresh -q \
                >"$work/log" 2>"$work/time" || { cat "$work/log" "$work/time" >&2; exit 1; }
            wall=$(awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; print s }' "$work/time")
            rss=$(awk -F': ' '/Maximum resident set size/ { print $2 }' "$work/time")
            steps=$(python3 -c "import pyarrow.parquet as pq, glob; t = pq.read_table(glob.glob('$out/tables/runs*.parquet')[0] if glob.glob('$out/tables/runs*.parquet') else glob.glob('$out/parts/**/runs*.parquet', recursive=True)[0]); print(t.column('steps')[0].as_py())")
            awk -v d="$dims" -v n="$name" -v t="$threads" -v b="$bars" -v nn="$nodes" -v s="$steps" -v w="$wall" -v r="$rss" \
                'BEGIN { printf "%-12s %-7s %3d %11d %10d %6d %9.1f %9.0f %8.1f %8.1f %11.3e\n", d, n, t, b, nn, s, w, r / 1024, r * 1024 / b, r * 1024 / nn, b * s / w }'
            rm -rf "$out"
        done
    done
done
