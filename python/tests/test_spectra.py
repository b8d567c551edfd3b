"""The product's numerics from Python equal the CLI's: response spectra of a real record (the
1992 Landers earthquake at station 5071) to round-off, RotD against the components' own spectra,
and the paper's similarity scaling against its closed forms."""

from __future__ import annotations

import numpy as np
import polars as pl
import pytest

import stickslip
from conftest import REPO, run_cli

RECORD = REPO / "examples" / "data" / "landers-1992-5071-ns.csv"


def test_spectra_equal_the_cli(tmp_path):
    run_cli("spectra", str(RECORD), "--units", "cm/s2", "--dampings", "0.02,0.05", "--out", str(tmp_path))
    table = pl.read_parquet(tmp_path / "spectra.parquet")
    rec = stickslip.read_record(RECORD, units="cm/s2")
    assert rec.dt == 0.005 and len(rec.accel) == 15998
    periods = np.unique(table["period_s"].to_numpy())
    s = stickslip.spectra(rec.accel, rec.dt, periods, [0.02, 0.05])
    for k, xi in enumerate([0.02, 0.05]):
        rows = table.filter(pl.col("damping") == xi).sort("period_s")
        assert np.allclose(s.psa[k], rows["psa_m_s2"].to_numpy(), rtol=1e-12, atol=0)
        assert np.allclose(s.sd[k], rows["sd_m"].to_numpy(), rtol=1e-12, atol=0)
    # PGA at the shortest periods: the record's peak.
    short = stickslip.spectra(rec.accel, rec.dt, [0.001], 0.05)
    assert short.psa[0, 0] == pytest.approx(np.abs(rec.accel).max(), rel=2e-3)


def test_rotd_bounds():
    rec = stickslip.read_record(RECORD, units="cm/s2")
    x = rec.accel
    y = np.roll(x, 50) * 0.7
    periods = np.array([0.1, 0.3, 1.0, 3.0])
    r = stickslip.rotd(x, y, rec.dt, periods, 0.05)
    sx, sy = stickslip.spectra(x, rec.dt, periods).psa[0], stickslip.spectra(y, rec.dt, periods).psa[0]
    assert np.allclose(r.x[0], sx, rtol=1e-12) and np.allclose(r.y[0], sy, rtol=1e-12)
    assert np.all(r.rotd100[0] >= np.maximum(sx, sy) * (1 - 1e-12))
    assert np.all(r.rotd50[0] <= r.rotd100[0])


def test_similarity_closed_forms():
    # A model event of Δσ = 1 MPa on the paper's 1.0 × 0.1 m base, scaled to a 10 km fault.
    s = stickslip.similarity(1.0e6, 1.0, 0.1, 1.1e-4, duration_s=2e-3, recurrence_s=0.03)
    lam = 1.0e4
    assert s["lambda"] == lam and s["prototype_area_m2"] == pytest.approx(0.1 * lam**2)
    m0 = 1.0e6 * 1.0e4 * 0.1 * lam**2  # Δσ·L_p·A_p (N·m)
    assert s["m0_consistent_dyne_cm"] == pytest.approx(m0 * 1e7, rel=1e-14)
    assert s["m0_paper_dyne_cm"] == pytest.approx(m0 * lam * 1e7, rel=1e-14)
    assert s["mw_consistent"] == pytest.approx(2 / 3 * np.log10(m0 * 1e7) - 10.7, abs=1e-12)
    assert s["m_riera_paper_interplate"] == pytest.approx(0.6536 * (np.log10(m0 * lam * 1e7) - 15.51), abs=1e-12)
    assert s["prototype_duration_s"] == pytest.approx(2e-3 * lam)
    assert s["prototype_recurrence_s"] == pytest.approx(0.03 * lam * 1.1e-4 / 3.17e-10)
