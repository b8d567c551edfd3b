#!/usr/bin/env bash
# The Python side of the README's test command: builds the package `stickslip` from this clone
# into a virtual environment under the Cargo target folder (`pip install '.[test]'`: maturin
# compiles crates/python with the release profile, reusing what `cargo test --release` built),
# then runs its tests (python/tests: the API, refusals, the CLI's tables from Python, ObsPy
# reading the MiniSEED, StationXML and QuakeML, the examples).
#
# Needs Python 3.9+ with venv and pip, and the package index (or wheels in PIP_FIND_LINKS) for
# maturin, numpy, polars, pyarrow, obspy, matplotlib and pytest. STICKSLIP_PYTHON picks the
# interpreter (default python3).
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-target}"
venv="$target/python-venv"
python="${STICKSLIP_PYTHON:-python3}"
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --upgrade pip
# The CLI the tests compare with is the one `cargo test --release --workspace` built.
export CARGO_TARGET_DIR="$(cd "$target" && pwd)"
"$venv/bin/python" -m pip install --quiet '.[test]'
"$venv/bin/python" -m pytest -q python/tests "$@"
