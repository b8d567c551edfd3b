"""Pipelines from Python: read, edited, validated, checked and written as the CLI does."""

from __future__ import annotations

from pathlib import Path

import pytest

import stickslip
from conftest import REPO, run_cli


def test_fields_read_and_set():
    p = stickslip.Pipeline.from_toml(REPO / "pipelines/paper.toml")
    assert p.name == "paper"
    assert p.block.nx == 10 and p["block"]["lc_m"] == 0.1 and p["material.poisson"] == 0.2
    assert p.seeds == [123, 200, 7]
    hash_before = p.hash
    p.block.nx = 12
    p["material.young_cv"] = 0.1
    assert p["block.nx"] == 12 and p.material.young_cv == 0.1
    assert p.hash != hash_before, "a changed scene is another pipeline"
    p.block.nx = 10
    p["material.young_cv"] = 0.05
    assert p.hash == hash_before
    # Unchanged, the file's own text is what is run and copied into the output folder.
    assert p.toml() == (REPO / "pipelines/paper.toml").read_text()


def test_to_toml_round_trip_and_from_dict(tmp_path: Path):
    p = stickslip.Pipeline.from_toml(REPO / "pipelines/paper.toml")
    p["seeds.list"] = [1, 2]
    out = tmp_path / "small.toml"
    p.to_toml(out)
    q = stickslip.Pipeline.from_toml(out)
    assert q.to_dict() == p.to_dict()
    assert q.hash == p.hash and q.seeds == [1, 2]
    # The same pipeline as a dict: the same hash.
    r = stickslip.Pipeline.from_dict(p.to_dict(), name="paper")
    assert r.hash == p.hash
    # A dict of a few keys: the rest take their defaults (the paper's scene).
    d = stickslip.Pipeline.from_dict({"name": "tiny", "seeds": {"list": [3]}})
    assert d.seeds == [3] and d.name == "tiny"
    assert stickslip.Pipeline.default().block.nx == 10


def test_check_returns_what_the_cli_prints():
    p = stickslip.Pipeline.from_toml(REPO / "pipelines/paper.toml")
    c = p.check()
    printed = run_cli("check", "pipelines/paper.toml").stdout.splitlines()
    assert printed[0].startswith("pipeline paper") and c.hash in printed[0]
    # Every line the CLI prints, in order, but the timed ones (the probe's speed varies).
    timed = ("per step", "steps/s", " s of set-up", "bar-updates/s", "≈", "min", " s ")
    ours = [f"  {t}" for _, _, t in c.lines]
    assert len(ours) == len(printed) - 1
    for a, b in zip(ours, printed[1:]):
        if not any(w in b for w in timed):
            assert a == b
    assert {"seeds", "cost", "block", "friction", "step"} <= set(c.sections)
    assert c.facts["bars"] > 0 and 0 < c.facts["critical_dt_s"][0] <= c.facts["critical_dt_s"][1]
    assert c.facts["dt_s"] == pytest.approx(0.5 * c.facts["critical_dt_s"][0], rel=1e-12)
