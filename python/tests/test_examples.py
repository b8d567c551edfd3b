"""The examples run as a user would run them, and draw their figures."""

from __future__ import annotations

import subprocess
import sys

from conftest import REPO


def run_example(name: str, *args: str) -> str:
    r = subprocess.run([sys.executable, str(REPO / "examples" / name), *args], capture_output=True, text=True, cwd=REPO)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_paper_example(tmp_path):
    out = tmp_path / "paper"
    text = run_example("paper.py", str(out), "7")
    assert (out / "paper-python.png").stat().st_size > 10_000
    assert "m_riera_paper_interplate" in text


def test_scenario_obspy_example(tmp_path):
    out = tmp_path / "tpv5"
    text = run_example("scenario_obspy.py", str(out), "3")
    assert (out / "scenario-obspy.png").stat().st_size > 10_000
    assert "Trace(s) in Stream" in text and "Event(s) in Catalog" in text
