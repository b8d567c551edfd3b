#!/usr/bin/env python3
"""Read a record set's files back with readers stickslip did not write, and recompute its RotD100.

    python3 scripts/check_set_files.py reports/scenario-m6

For each chosen record of `<folder>/set/` (a scenario's set: `FP` and `FN` horizontal pairs): the
SAC files read by ObsPy, the AT2 files by a plain parser of the PEER format written here, the
pair's 5%-damped RotD100 recomputed by pyrotd (A. Kottke's frequency-domain oscillators) at the
periods of stickslip's grid inside the set's matching range (`[set]` of `<folder>/set/set.toml`,
written by `stickslip select --set`, else of the folder's pipeline: 0.2·T₁ … 2·T₁ or period_min_s
… period_max_s), and compared with stickslip's own RotD100 of the record (its `station_spectra`
row) times the record's scale factor (the `set` table). Prints the largest relative difference per
record and format; exits 1 above 1e-3.

Needs obspy, pyrotd, numpy and polars (pip install obspy pyrotd polars pyarrow).
"""
import glob
import os
import sys
import tomllib

import numpy as np
import obspy
import polars as pl
import pyrotd

TOLERANCE = 1e-3


def read_at2(path):
    """PEER AT2: four header lines (the fourth holds NPTS and DT), then accelerations in g."""
    with open(path) as f:
        lines = f.read().splitlines()
    header = lines[3].replace(",", " ").split()
    npts = int(header[header.index("NPTS=") + 1]) if "NPTS=" in header else int(header[0])
    dt = float(header[header.index("DT=") + 1]) if "DT=" in header else float(header[1])
    values = np.array([float(v) for line in lines[4:] for v in line.split()])
    assert len(values) == npts, f"{path}: {len(values)} values for NPTS = {npts}"
    return values * 9.80665, dt


def matching_range(folder):
    """The set's period range (s): from set/set.toml if `stickslip select --set` wrote one."""
    for path in (os.path.join(folder, "set", "set.toml"), os.path.join(folder, "pipeline.toml")):
        if os.path.exists(path):
            with open(path, "rb") as f:
                section = tomllib.load(f).get("set")
            if section:
                t1 = section.get("t1_s", 1.0)
                if t1 > 0:
                    return 0.2 * t1, 2.0 * t1
                return section["period_min_s"], section["period_max_s"]
    raise SystemExit(f"{folder}: no [set] section")


def main(folder):
    lo, hi = matching_range(folder)
    set_table = pl.read_parquet(os.path.join(folder, "tables", "set.parquet"))
    spectra = pl.read_parquet(os.path.join(folder, "tables", "station_spectra.parquet"))
    name = os.path.basename(os.path.normpath(folder))
    worst_all = 0.0
    for rank, row in enumerate(set_table.iter_rows(named=True), start=1):
        seed, station, scale = row["seed"], row["record"], row["scale_factor"]
        own = spectra.filter((pl.col("seed") == seed) & (pl.col("station") == station)).sort("period_s")
        stem_glob = os.path.join(folder, "set", f"*_set{rank:02d}_seed{seed}_{station}_")
        for fmt in ("sac", "at2"):
            pair = []
            for code in ("FP", "FN"):
                [path] = glob.glob(stem_glob + f"{code}.{fmt.upper()}")
                if fmt == "sac":
                    tr = obspy.read(path, format="SAC")[0]
                    # SAC's own unit of an acceleration trace is nm/s² (IDEP = IACC = 8).
                    assert tr.stats.sac.idep == 8, f"{path}: IDEP {tr.stats.sac.idep}"
                    pair.append((tr.data.astype(float) * 1e-9, tr.stats.delta))
                else:
                    pair.append(read_at2(path))
            (x, dt), (z, _) = pair
            periods = own["period_s"].to_numpy()
            keep = (periods >= lo * (1 - 1e-9)) & (periods <= hi * (1 + 1e-9))
            freqs = 1.0 / periods[keep]
            # Resampled (in pyrotd, by zero-padding the spectrum) to 40 samples per oscillator period, so
            # that its peaks are read between the 0.01 s samples as stickslip's band-limited reading does.
            rotd = pyrotd.calc_rotated_spec_accels(dt, x, z, freqs, 0.05, percentiles=[100], max_freq_ratio=40)
            theirs = np.array([r.spec_accel for r in rotd])
            ours = scale * own["rotd100_m_s2"].to_numpy()[keep]
            worst = float(np.max(np.abs(theirs / ours - 1.0)))
            if os.environ.get("VERBOSE"):
                for t, a, b in zip(periods[keep], theirs, ours):
                    print(f"  T = {t:.3f} s: pyrotd {a:.5g}, stickslip {b:.5g}, {a / b - 1:+.2e}")
            worst_all = max(worst_all, worst)
            print(f"{name} record {rank:2d} (seed {seed}, {station}, ×{scale:.3f}) {fmt.upper()}: "
                  f"{len(x)} samples every {dt} s, RotD100 at {keep.sum()} periods within {worst:.1e}")
    print(f"largest relative difference over {lo:g} … {hi:g} s: {worst_all:.2e} (tolerance {TOLERANCE})")
    return 0 if worst_all <= TOLERANCE else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "reports/scenario-m6"))
