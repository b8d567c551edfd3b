"""Bad input from Python: an exception naming the field, the value and the allowed range."""

from __future__ import annotations

from pathlib import Path

import pytest

import stickslip
from conftest import REPO


def paper() -> stickslip.Pipeline:
    return stickslip.Pipeline.from_toml(REPO / "pipelines/paper.toml")


def test_misspelled_field():
    p = paper()
    p["block.lc_mm"] = 0.1
    with pytest.raises(stickslip.PipelineError) as e:
        p.validate()
    assert e.value.field == "block.lc_mm"
    assert e.value.value == "0.1"
    assert "lc_m" in e.value.allowed and "nx" in e.value.allowed, e.value.allowed
    assert isinstance(e.value, ValueError)


def test_negative_value():
    p = paper()
    p.material.poisson = -0.3
    with pytest.raises(stickslip.PipelineError) as e:
        p.check()
    assert (e.value.field, e.value.value) == ("material.poisson", "-0.3")
    assert "0" in e.value.allowed and "0.5" in e.value.allowed, e.value.allowed
    # Every refused value is listed, not only the first.
    p.block.nx = -4
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.run(p, out="/nonexistent/never-written", progress=False)
    fields = [f for f, _, _ in e.value.errors]
    assert "material.poisson" in fields and "block.nx" in fields
    assert not Path("/nonexistent/never-written").exists()


def test_place_on_the_earth():
    p = paper()
    p["exchange.origin_lat_deg"] = 95.0
    with pytest.raises(stickslip.PipelineError) as e:
        p.validate()
    assert (e.value.field, e.value.value) == ("exchange.origin_lat_deg", "95")
    assert "90" in e.value.allowed


def test_wrong_type():
    p = paper()
    p.block.nx = "ten"
    with pytest.raises(stickslip.PipelineError) as e:
        p.validate()
    assert e.value.field == "block.nx" and e.value.value == '"ten"'
    assert "integer" in e.value.allowed


def test_missing_files(tmp_path: Path):
    with pytest.raises(FileNotFoundError):
        stickslip.Pipeline.from_toml(tmp_path / "no-such-pipeline.toml")
    p = stickslip.Pipeline.from_toml(REPO / "pipelines/scenario-m6-crust.toml")
    p["medium.profile_file"] = "profiles/no-such-profile.vel"
    with pytest.raises(stickslip.PipelineError) as e:
        p.validate()
    assert e.value.field == "medium.profile_file"
    assert "no-such-profile.vel" in e.value.value
    with pytest.raises(FileNotFoundError):
        stickslip.open(tmp_path)
    with pytest.raises(FileNotFoundError):
        stickslip.read_record(tmp_path / "missing.SAC")


def test_misspelled_section_and_non_finite_values():
    p = paper()
    p["blok.nx"] = 3
    with pytest.raises(stickslip.PipelineError) as e:
        p.validate()
    assert e.value.field == "blok" and "block" in e.value.allowed
    assert not str(e.value).startswith("line "), "no line of a text the user never wrote"
    p = paper()
    p["material.young_pa"] = float("nan")
    with pytest.raises(stickslip.PipelineError) as e:
        p.validate()
    assert (e.value.field, e.value.value, e.value.allowed) == ("material.young_pa", "nan", "a finite number")


@pytest.mark.parametrize(
    "seeds", [[], "10-5", [7, 7], "7,x", 7, [2**64], [7.5], [True], "-3"]
)
def test_bad_seeds_are_refused_before_anything_runs(seeds, tmp_path):
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.run(paper(), seeds=seeds, out=tmp_path / "out", progress=False)
    assert e.value.field == "seeds", e.value
    assert not (tmp_path / "out").exists()


def test_bad_arguments():
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.run(paper(), seeds=[-1], progress=False)
    assert e.value.field == "seeds"
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.run(paper(), threads=0, progress=False)
    assert e.value.field == "threads"
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.spectra([0.0, 1.0, float("nan")], 0.01, [0.1])
    assert e.value.field == "acceleration[2]"
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.spectra([0.0, 1.0], -0.01, [0.1])
    assert (e.value.field, e.value.value) == ("dt", "-0.01")
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.spectra([0.0, 1.0], 0.01, [0.1, 0.0])
    assert (e.value.field, e.value.value) == ("periods[1]", "0.0")
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.spectra([0.0, 1.0], 0.01, [0.1], 1.5)
    assert e.value.field == "damping[0]"
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.spectra([], 0.01, [0.1])
    assert e.value.field == "acceleration"
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.run(paper(), threads="2", progress=False)
    assert e.value.field == "threads"
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.run(paper(), progress=42)
    assert e.value.field == "progress"
    with pytest.raises(stickslip.PipelineError) as e:
        stickslip.similarity(-1e6, 1.0, 0.1, 1e-4)
    assert e.value.field == "stress_drop_pa"
