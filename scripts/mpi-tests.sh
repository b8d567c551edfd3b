#!/usr/bin/env bash
# The MPI part of the README's test command: builds the solver's `split_step` example and the
# command line with the `mpi` feature, then under mpirun on 2 and 3 ranks of this machine
# (oversubscribed): every node's three time levels against one process, bit for bit
# (docs/model.md §19), and `stickslip pipeline`'s folder against one process's, table by table. Needs an MPI implementation and libclang (Debian: openmpi-bin
# libopenmpi-dev libclang-dev; .ci/run installs them).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v mpirun >/dev/null; then
    echo "mpirun not found: install Open MPI or MPICH (Debian: openmpi-bin libopenmpi-dev libclang-dev)" >&2
    exit 1
fi
cargo build --release -p stickslip-solver --features mpi --example split_step
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
pipeline() {
    local name="$1"; shift
    echo "== stickslip pipeline pipelines/$name.toml, one process and mpirun -n $*"
    "$cli" pipeline "pipelines/$name.toml" --out "$out/$name-1" --quiet >/dev/null
    for n in "$@"; do
        mpirun "${flags[@]}" -n "$n" "$cli" pipeline "pipelines/$name.toml" --out "$out/$name-$n" --quiet >/dev/null
        "$cli" compare "$out/$name-1" "$out/$name-$n"
    done
}
pipeline tpv5-500m 2 3
pipeline large-block 2
echo "MPI tests: every split run gave one process's bits and tables"
