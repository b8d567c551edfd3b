"""ObsPy (an independent reader) reads what the product writes: every MiniSEED record with its
StationXML inventory, and the QuakeML catalogue, each validated against its schema."""

from __future__ import annotations

import numpy as np
import polars as pl
import pytest

obspy = pytest.importorskip("obspy")
from obspy.io.quakeml.core import _validate as validate_quakeml  # noqa: E402
from obspy.io.stationxml.core import validate_stationxml  # noqa: E402


def test_block_records_equal_the_sac_records(paper_runs):
    _, result = paper_runs
    files = result.mseed_files("records")
    records = result.records
    assert len(files) == records.height, "one MiniSEED file per record and scale"
    for path in files:
        ms = obspy.read(str(path), format="MSEED")
        assert len(ms) == 1
        tr = ms[0]
        sac = obspy.read(str(path.with_suffix(".SAC")), format="SAC")[0]
        # SAC holds nm/s² as 32-bit floats; MiniSEED the m/s² the product computed, as 64-bit.
        assert tr.data.dtype == np.float64 and len(tr.data) == len(sac.data)
        scale = np.abs(tr.data).max()
        assert np.abs(tr.data * 1e9 - sac.data).max() <= 1e-6 * scale * 1e9
        # The sampling rate: the table's interval, exact (to 32-bit precision when no ratio of
        # 16-bit integers gives it, as ObsPy's own writer does).
        stem = path.stem  # paper_seed<k>_<record>_<scale>
        seed = int(stem.split("_seed")[1].split("_")[0])
        scale_name = stem.rsplit("_", 1)[1]
        record = stem.split(f"_seed{seed}_")[1].rsplit("_", 1)[0]
        row = records.filter((pl.col("seed") == seed) & (pl.col("record") == record) & (pl.col("scale") == scale_name))
        rate = 1.0 / row["dt_s"][0]
        assert tr.stats.sampling_rate == np.float32(rate) or tr.stats.sampling_rate == rate
        assert abs(tr.stats.sampling_rate / rate - 1) < 6e-8
        assert tr.stats.network == "SS" and tr.stats.location in ("M", "P")


def test_block_inventory(paper_runs):
    _, result = paper_runs
    ok, errors = validate_stationxml(str(result.inventory_path))
    assert ok, errors
    inv = result.inventory()
    records = result.records
    for path in result.mseed_files("records"):
        tr = obspy.read(str(path))[0]
        sel = inv.select(network=tr.stats.network, station=tr.stats.station, location=tr.stats.location,
                         channel=tr.stats.channel)
        assert len(sel.get_contents()["channels"]) == 1, tr.id
        cha = sel[0][0][0]
        assert cha.sample_rate == pytest.approx(tr.stats.sampling_rate, rel=6e-8)
        resp = inv.get_response(tr.id, tr.stats.starttime)
        assert resp.instrument_sensitivity.input_units == "M/S**2"
        # One count is one m/s²: removing the response leaves the samples as they are (ObsPy's
        # own mean removal and taper switched off), to 1e-8 of the peak: ObsPy makes the Nyquist
        # term of the padded spectrum positive, an alternating ±2e-7 m/s² on an 81 m/s² record.
        removed = tr.copy().remove_response(inventory=inv, output="ACC", zero_mean=False, taper=False)
        assert np.abs(removed.data - tr.data).max() <= 1e-8 * np.abs(tr.data).max()
        assert np.array_equal(tr.copy().remove_sensitivity(inv).data, tr.data)
    # Coordinates: the node's position at that scale, x east and y north of 0°N 0°E.
    node = records.filter(pl.col("scale") == "prototype").row(0, named=True)
    sta = inv.select(station=f"N{node['node']}", location="P")[0][0]
    r = 6_371_000.0
    assert sta.latitude == pytest.approx(np.degrees(node["y_m"] / r), abs=1e-9)
    assert sta.longitude == pytest.approx(np.degrees(node["x_m"] / r), abs=1e-9)
    assert sta.elevation == pytest.approx(node["z_m"], abs=1e-6)


def test_block_catalogue(paper_runs):
    _, result = paper_runs
    assert validate_quakeml(str(result.catalogue_path)) is True
    cat = result.catalog()
    sim = result.similarity
    assert len(cat) == sim.height
    by_id = {str(e.resource_id).rsplit("/", 2)[-2] + "/" + str(e.resource_id).rsplit("/", 1)[-1]: e for e in cat}
    for row in sim.iter_rows(named=True):
        e = by_id[f"seed{row['seed']}/event{row['event']}"]
        mags = {m.magnitude_type: m.mag for m in e.magnitudes}
        assert e.preferred_magnitude().magnitude_type == "Mw"
        assert mags["Mw"] == pytest.approx(row["mw_consistent"], abs=1e-9)
        assert mags["M"] == pytest.approx(row["m_riera_paper_interplate"], abs=1e-9)
        assert e.preferred_focal_mechanism().moment_tensor.scalar_moment == pytest.approx(
            row["m0_consistent_dyne_cm"] * 1e-7, rel=1e-12
        )
        assert e.event_type == "earthquake"
    events = result.events
    first = events.filter(pl.col("seed") == sim["seed"][0]).sort("start_s").row(0, named=True)
    e = by_id[f"seed{first['seed']}/event{first['event']}"]
    lam = sim.filter((pl.col("seed") == first["seed"]) & (pl.col("event") == first["event"]))["lambda"][0]
    t0 = obspy.UTCDateTime(2000, 1, 1)
    assert e.preferred_origin().time - t0 == pytest.approx(first["start_s"] * lam, abs=2e-6)


def test_fault_station_records(fault_run):
    result = fault_run
    files = result.mseed_files("stations")
    assert len(files) == 1, "one file per seed"
    st = result.stream("stations")
    stations = result.stations
    assert len({tr.stats.station for tr in st}) == stations.filter(pl.col("f_low_hz").is_not_null()).height
    ok, errors = validate_stationxml(str(result.inventory_path))
    assert ok, errors
    inv = result.inventory()
    for tr in st:
        assert inv.select(station=tr.stats.station, channel=tr.stats.channel), tr.id
    # Placed about [exchange]'s origin: strike (x) north, fault-normal (z) east, y the depth.
    r = 6_371_000.0
    sta = inv[0][0]
    row = stations.filter(pl.col("station") == sta.site.name.split(" (V_S30")[0]).row(0, named=True)
    assert sta.latitude == pytest.approx(34.2 + np.degrees(row["x_m"] / r), abs=1e-9)
    assert sta.longitude == pytest.approx(-116.4 + np.degrees(row["z_m"] / (r * np.cos(np.radians(34.2)))), abs=1e-9)
    # The station stands on the ground surface; a buried sensor is its channel's depth.
    assert sta.elevation == 0.0
    for cha in sta:
        assert cha.depth == pytest.approx(row["y_m"], abs=1e-6)
        assert cha.elevation == pytest.approx(-row["y_m"], abs=1e-6)
    # The site's full name and its scene coordinates are in the inventory.
    names = {s.site.name for s in inv[0]}
    assert names == set(stations["station"].to_list()) or names <= set(stations["station"].to_list())
    assert validate_quakeml(str(result.catalogue_path)) is True
    cat = result.catalog()
    source = result.source
    assert len(cat) == source.height == 1
    with pytest.raises(FileNotFoundError, match="'stations'"):
        result.stream("records")
    e = cat[0]
    assert e.preferred_magnitude().mag == pytest.approx(source["mw"][0], abs=1e-9)
    assert e.preferred_origin().depth == pytest.approx(abs(source["hypocentre_y_m"][0]), abs=1e-3)
