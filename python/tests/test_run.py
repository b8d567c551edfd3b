"""The paper pipeline run from Python: the same tables as the CLI's, read lazily as polars
DataFrames (and by pyarrow, an independent reader)."""

from __future__ import annotations

from pathlib import Path

import polars as pl
import pyarrow.parquet as pq
import pytest

import stickslip
from conftest import PAPER_SEEDS

# Columns that hold how long something took, not what it computed.
TIMES = {"wall_time_s"}


def parquet_files(folder: Path):
    return sorted(p.relative_to(folder) for p in (folder / "tables").rglob("*.parquet"))


def test_the_same_tables_as_the_cli(paper_runs):
    cli_out, result = paper_runs
    files = parquet_files(cli_out)
    assert files == parquet_files(result.folder), "the same tables and parts"
    assert len(files) > 20
    for rel in files:
        a, b = pl.read_parquet(cli_out / rel), pl.read_parquet(result.folder / rel)
        keep = [c for c in a.columns if c not in TIMES]
        assert a.columns == b.columns, rel
        assert a.select(keep).equals(b.select(keep)), f"{rel} differs"
        # pyarrow reads the same values.
        t = pq.read_table(result.folder / rel)
        assert t.num_rows == b.height and t.column_names == b.columns


def test_tables_as_dataframes(paper_runs):
    cli_out, result = paper_runs
    assert result.run["ran"] == len(PAPER_SEEDS) and result.run["failed"] == []
    assert "S1" in result.run["digest"] and "M (paper)" in result.run["digest"], "the CLI's closing summary"
    events = result.events
    assert isinstance(events, pl.DataFrame)
    assert events.equals(pl.read_parquet(cli_out / "tables/events.parquet"))
    assert sorted(events["seed"].unique().to_list()) == sorted(PAPER_SEEDS)
    # A per-seed table, lazily over its parts.
    lazy = result.scan("control")
    assert isinstance(lazy, pl.LazyFrame)
    control = lazy.filter(pl.col("seed") == PAPER_SEEDS[0]).collect()
    assert control.height > 0 and set(control["seed"].unique().to_list()) == {PAPER_SEEDS[0]}
    for name in ["similarity", "summary", "runs", "records", "spectra"]:
        assert name in result.tables and result.table(name).height > 0
    with pytest.raises(AttributeError):
        result.no_such_table
    # Opening the folder again reads the same.
    again = stickslip.open(result.folder)
    assert again.similarity.equals(result.similarity)
    assert again.pipeline.hash == stickslip.Pipeline.from_toml(result.folder / "pipeline.toml").hash


def test_an_interrupted_run_resumes(paper_runs, tmp_path):
    # A second run over a finished folder runs nothing and says so.
    _, result = paper_runs
    again = stickslip.run(result.folder / "pipeline.toml", seeds=PAPER_SEEDS, out=result.folder, progress=False)
    assert again.run["ran"] == 0 and again.run["skipped"] == len(PAPER_SEEDS)


def test_progress_callback(tmp_path):
    p = stickslip.Pipeline.from_toml(Path(__file__).resolve().parents[2] / "pipelines/paper.toml")
    p["shear.duration_s"] = 0.06
    p["report.enabled"] = False
    seen = []
    stickslip.run(p, seeds=[1, 2], out=tmp_path / "out", threads=1, progress=lambda d, t: seen.append((d, t)))
    assert seen and seen[-1] == (2, 2) and all(t == 2 for _, t in seen)
