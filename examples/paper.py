"""The paper's case end to end from Python: run the paper pipeline for a few seeds, read its
tables as polars DataFrames, and draw the shear stress on the base with the main shocks and their
scaled magnitudes (the paper's M ≈ 6.77).

    python examples/paper.py [OUT_FOLDER] [SEEDS]      # default reports/paper-python, "7,123"
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import polars as pl  # noqa: E402

import stickslip  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
out = Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "reports" / "paper-python"
seeds = sys.argv[2] if len(sys.argv) > 2 else "7,123"

pipeline = stickslip.Pipeline.from_toml(REPO / "pipelines" / "paper.toml")
result = stickslip.run(pipeline, seeds=seeds, out=out)
print(result.run["digest"])

main = result.similarity.filter(pl.col("kind") == "main")
print(main.select("seed", "label", "stress_drop_pa", "m_riera_paper_interplate", "mw_consistent"))

fig, (ax, bx) = plt.subplots(2, 1, figsize=(8, 7), constrained_layout=True)
for seed in sorted(result.runs["seed"].to_list()):
    s = result.scan("series").filter(pl.col("seed") == seed).select("time_s", "shear_stress_pa").collect()
    ax.plot(s["time_s"], s["shear_stress_pa"] / 1e3, lw=0.8, label=f"seed {seed}")
    shocks = result.events.filter((pl.col("seed") == seed) & (pl.col("kind") == "main"))
    at = np.interp(shocks["start_s"], s["time_s"], s["shear_stress_pa"] / 1e3)
    ax.plot(shocks["start_s"], at, "v", ms=7, mec="k", color=ax.lines[-1].get_color())
ax.set(
    xlabel="time (s, model scale)",
    ylabel="shear stress on the base (kPa)",
    title="Stick-slip of the paper's block (▼ main shocks)",
)
ax.legend()
bx.hist(main["m_riera_paper_interplate"], bins=10, color="tab:blue", alpha=0.7, label="main shocks S1, S2, …")
bx.axvline(6.77, color="k", ls="--", label="paper: M ≈ 6.77")
bx.set(xlabel="Riera magnitude (paper's moment, interplate)", ylabel="count")
bx.legend()
figure = out / "paper-python.png"
fig.savefig(figure, dpi=120)
print(f"figure: {figure}")
