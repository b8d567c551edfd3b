"""Shared fixtures: the command-line program (built by `cargo test --release --workspace`, which
the README's test command runs first) and runs of the paper pipeline by the CLI and by Python."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def cli_path() -> Path:
    """The `stickslip` program of this checkout."""
    if os.environ.get("STICKSLIP_BIN"):
        return Path(os.environ["STICKSLIP_BIN"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    if not target.is_absolute():
        target = REPO / target
    path = target / "release" / "stickslip"
    if not path.exists():
        pytest.fail(f"{path} not found: build it first (cargo build --release -p stickslip) or set STICKSLIP_BIN")
    return path


def run_cli(*args: str, cwd: Path = REPO) -> subprocess.CompletedProcess:
    """Runs the CLI, failing the test with its stderr when it fails."""
    r = subprocess.run([str(cli_path()), *args], cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0:
        pytest.fail(f"stickslip {' '.join(args)} failed ({r.returncode}):\n{r.stderr}")
    return r


PAPER_SEEDS = [7, 123]


@pytest.fixture(scope="session")
def paper_runs(tmp_path_factory):
    """The paper pipeline for two seeds, run by the CLI and by `stickslip.run` into two folders."""
    import stickslip

    root = tmp_path_factory.mktemp("paper")
    cli_out, py_out = root / "cli", root / "python"
    run_cli("pipeline", "pipelines/paper.toml", "--seeds", ",".join(map(str, PAPER_SEEDS)), "--out", str(cli_out), "--quiet")
    result = stickslip.run(REPO / "pipelines/paper.toml", seeds=PAPER_SEEDS, out=py_out, progress=False)
    return cli_out, result


@pytest.fixture(scope="session")
def fault_run(tmp_path_factory):
    """TPV5 at 500 m for its first 3 s, one seed: a fault scenario's station records, inventory
    and catalogue."""
    import stickslip

    root = tmp_path_factory.mktemp("tpv5")
    p = stickslip.Pipeline.from_toml(REPO / "pipelines/tpv5-500m.toml")
    p["shear.duration_s"] = 3.0
    p["report.enabled"] = False
    # Placed near Landers, California.
    p["exchange"] = {"origin_lat_deg": 34.2, "origin_lon_deg": -116.4}
    return stickslip.run(p, out=root / "out", progress=False)


def fresh_copy(src: Path, dst: Path) -> Path:
    shutil.copytree(src, dst)
    return dst
