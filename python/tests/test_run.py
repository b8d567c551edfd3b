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


def quick_paper(duration_s: float = 0.06) -> stickslip.Pipeline:
    p = stickslip.Pipeline.from_toml(Path(__file__).resolve().parents[2] / "pipelines/paper.toml")
    p["shear.duration_s"] = duration_s
    p["report.enabled"] = False
    return p


def test_the_gil_is_released_while_the_solver_runs(tmp_path):
    import threading

    count = [0]
    running = threading.Event()

    def spin():
        running.set()
        while not stop.is_set():
            count[0] += 1

    stop = threading.Event()
    t = threading.Thread(target=spin)
    t.start()
    running.wait()
    before = count[0]
    stickslip.run(quick_paper(0.16), seeds=[1, 2], out=tmp_path / "out", threads=1, progress=False)
    during = count[0] - before
    stop.set()
    t.join()
    # A thread that held the GIL for the whole run would leave the counter where it was but for
    # the 0.1 s polls; released, the other thread counts millions in the same time.
    assert during > 100_000, during


def test_ctrl_c_keeps_finished_seeds_and_the_same_call_resumes(tmp_path):
    import signal
    import subprocess
    import sys

    out = tmp_path / "out"
    script = (
        "import sys, stickslip\n"
        "p = stickslip.Pipeline.from_toml(sys.argv[1])\n"
        "p['report.enabled'] = False\n"
        "try:\n"
        "    stickslip.run(p, seeds=range(1, 13), out=sys.argv[2], threads=1, progress=lambda d, t: print(d, flush=True))\n"
        "except KeyboardInterrupt as e:\n"
        "    print('interrupted:', e, flush=True)\n"
    )
    paper = Path(__file__).resolve().parents[2] / "pipelines/paper.toml"
    proc = subprocess.Popen([sys.executable, "-c", script, str(paper), str(out)], stdout=subprocess.PIPE, text=True)
    # Wait for two finished seeds, then interrupt as a terminal's Ctrl-C does.
    lines = []
    while True:
        line = proc.stdout.readline()
        assert line, f"the run ended before it was interrupted: {lines}"
        lines.append(line.strip())
        if line.strip().isdigit() and int(line) >= 2:
            break
    proc.send_signal(signal.SIGINT)
    rest, _ = proc.communicate(timeout=120)
    # The CLI's message: how many seeds are finished and that the same command resumes.
    assert "interrupted: interrupted:" in rest and "run the same command again to resume" in rest, rest
    done = len(list((out / "tables" / "runs").glob("seed-*.parquet")))
    assert 2 <= done < 12, done
    # The same call resumes: it runs only the seeds not finished.
    p = stickslip.Pipeline.from_toml(paper)
    p["report.enabled"] = False
    again = stickslip.run(p, seeds=range(1, 13), out=out, threads=1, progress=False)
    assert again.run["skipped"] == done and again.run["ran"] == 12 - done


def test_a_failing_progress_callback_stops_the_run_with_its_error(tmp_path):
    def fail(done, total):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        stickslip.run(quick_paper(), seeds=[1, 2, 3], out=tmp_path / "out", threads=1, progress=fail)
