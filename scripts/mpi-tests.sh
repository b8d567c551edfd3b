#!/usr/bin/env bash
# The MPI part of the README's test command: builds the command line's `split_step` example and the
# command line with the `mpi` feature, then under mpirun on 2, 3 and 4 ranks of this machine
# (oversubscribed): every node's three time levels against one process, bit for bit
# (docs/model.md §19), and `stickslip pipeline`'s folder against one process's, table by table,
# also for a split run stopped and resumed from its checkpoints. Needs an MPI implementation and
# libclang (Debian: openmpi-bin libopenmpi-dev libclang-dev; .ci/run installs them).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v mpirun >/dev/null; then
    echo "mpirun not found: install Open MPI or MPICH (Debian: openmpi-bin libopenmpi-dev libclang-dev)" >&2
    exit 1
fi
cargo build --release -p stickslip --features mpi --example split_step
cargo build --release -p stickslip --features mpi
target="${CARGO_TARGET_DIR:-target}"
bin="$target/release/examples/split_step"
cli="$target/release/stickslip"

# Open MPI refuses root and more ranks than cores unless told.
flags=()
if mpirun --version 2>&1 | grep -q "Open MPI"; then
    flags+=(--oversubscribe)
    [ "$(id -u)" = 0 ] && flags+=(--allow-run-as-root)
fi

run() {
    echo "== mpirun -n $1 split_step $2 --steps $3 --check"
    mpirun "${flags[@]}" -n "$1" "$bin" "$2" --steps "$3" --check
}
run 2 pipelines/tpv5-500m.toml 120
run 3 pipelines/tpv5-500m.toml 120
run 2 pipelines/paper.toml 2000

# `stickslip pipeline` under mpirun: the same folder as one process (every table, wall times aside).
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
# SEEDS (when set) runs those seeds only.
pipeline() {
    local name="$1"; shift
    local seeds=()
    [ -n "${SEEDS:-}" ] && seeds=(--seeds "$SEEDS")
    echo "== stickslip pipeline pipelines/$name.toml${SEEDS:+ --seeds $SEEDS}, one process and mpirun -n $*"
    "$cli" pipeline "pipelines/$name.toml" "${seeds[@]}" --out "$out/$name-1" --quiet >/dev/null
    for n in "$@"; do
        mpirun "${flags[@]}" -n "$n" "$cli" pipeline "pipelines/$name.toml" "${seeds[@]}" --out "$out/$name-$n" \
            --quiet >/dev/null
        "$cli" compare "$out/$name-1" "$out/$name-$n"
    done
}
pipeline tpv5-500m 2 3
pipeline large-block 2
# The paper's scene (its 781 bars listed, its energy ledger), one seed, on 2, 3 and 4 ranks.
SEEDS=123 pipeline paper 2 3 4

# Stopped and resumed: mpirun interrupted (it passes the signal on) once every rank has written a
# checkpoint, then the same command again: the seed resumes, and the folder is one process's.
echo "== stickslip pipeline pipelines/tpv5-500m.toml --checkpoint-every, mpirun -n 2 stopped and resumed"
dir="$out/tpv5-500m-stopped"
mpirun "${flags[@]}" -n 2 "$cli" pipeline pipelines/tpv5-500m.toml --out "$dir" --quiet --checkpoint-every 0.001 \
    >/dev/null 2>&1 &
launcher=$!
for _ in $(seq 600); do
    compgen -G "$dir/checkpoints/*.rank-1-of-2.ckpt" >/dev/null && break
    sleep 0.05
done
kill -INT "$launcher"
wait "$launcher" && { echo "the run was not stopped" >&2; exit 1; }
compgen -G "$dir/checkpoints/*.rank-0-of-2.ckpt" >/dev/null || { echo "no checkpoint of rank 0" >&2; exit 1; }
mpirun "${flags[@]}" -n 2 "$cli" pipeline pipelines/tpv5-500m.toml --out "$dir" --quiet --checkpoint-every 0.001 \
    | grep "resumes from its checkpoint"
"$cli" compare "$out/tpv5-500m-1" "$dir"
if compgen -G "$dir/checkpoints/*.ckpt" >/dev/null; then
    echo "checkpoints left after the seed was written" >&2
    exit 1
fi
echo "MPI tests: every split run gave one process's bits and tables, stopped and resumed too"
