#!/usr/bin/env bash
# The MPI part of the README's test command: builds the solver's `split_step` example with the
# `mpi` feature and runs it under mpirun on 2 and 3 ranks of this machine (oversubscribed),
# each run comparing every node's three time levels with one process, bit for bit
# (docs/model.md §19). Needs an MPI implementation and libclang (Debian: openmpi-bin
# libopenmpi-dev libclang-dev; .ci/run installs them).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v mpirun >/dev/null; then
    echo "mpirun not found: install Open MPI or MPICH (Debian: openmpi-bin libopenmpi-dev libclang-dev)" >&2
    exit 1
fi
cargo build --release -p stickslip-solver --features mpi --example split_step
bin="${CARGO_TARGET_DIR:-target}/release/examples/split_step"

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
echo "MPI tests: every split run gave one process's bits"
