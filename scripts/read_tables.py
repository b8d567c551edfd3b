#!/usr/bin/env python3
"""Read a stickslip output folder's tables in Python and plot the shear stress of each seed.

    python3 scripts/read_tables.py reports/paper [tau.png]

Needs polars and pyarrow (pip install polars pyarrow); matplotlib for the figure. Kept runnable by
the test `python_example_reads_the_tables` (crates/cli/tests/usability.rs).
"""
import sys

import polars as pl
import pyarrow.parquet as pq

folder = sys.argv[1] if len(sys.argv) > 1 else "reports/paper"
png = sys.argv[2] if len(sys.argv) > 2 else None

# Per-seed parts read lazily with a glob; gathered tables are single files.
series = pl.scan_parquet(f"{folder}/tables/series/*.parquet")
events = pl.read_parquet(f"{folder}/tables/events/*.parquet")
mains = events.filter(pl.col("kind") == "main").sort("seed", "start_s")
print(mains.select("seed", "label", "start_s", "stress_drop_pa").head(8))

# The same tables through pyarrow: strings are plain strings, not string_view.
runs = pq.read_table(f"{folder}/tables/runs.parquet")
print("runs.status:", runs.schema.field("status").type)

tau = series.select("seed", "time_s", "shear_stress_pa").collect()
print("samples per seed:", dict(tau.group_by("seed").len().sort("seed").iter_rows()))

if png:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4))
    for (seed,), part in tau.group_by("seed", maintain_order=True):
        ax.plot(part["time_s"], part["shear_stress_pa"] / 1e3, lw=0.7, label=f"seed {seed}")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("τ (kPa)")
    ax.legend()
    fig.savefig(png, dpi=120)
    print("wrote", png)
