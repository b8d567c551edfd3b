"""The wall time of a pipeline run from Python against the same run by the CLI, measured side by
side: each round runs `stickslip pipeline` and then `stickslip.run` in a fresh Python process,
each into a fresh folder, and prints min/median/max of the CLI's process, the Python process
(interpreter start and `import stickslip` included) and the `stickslip.run` call alone (what a
notebook user waits for), and the ratios of the medians.

    python python/benchmarks/wall_time.py [PIPELINE] [SEEDS] [ROUNDS]
    # default: pipelines/paper.toml "7,123" 7
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
pipeline = sys.argv[1] if len(sys.argv) > 1 else "pipelines/paper.toml"
seeds = sys.argv[2] if len(sys.argv) > 2 else "7,123"
rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 7
target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
cli = os.environ.get("STICKSLIP_BIN", str(target / "release" / "stickslip"))

py = (
    "import time, sys; import stickslip; t = time.perf_counter(); "
    "stickslip.run(sys.argv[1], seeds=sys.argv[2], out=sys.argv[3], progress=False); "
    "print(time.perf_counter() - t)"
)


def timed(cmd):
    t = time.perf_counter()
    r = subprocess.run(cmd, cwd=REPO, check=True, capture_output=True, text=True)
    return time.perf_counter() - t, r.stdout


times = {"cli": [], "python": [], "run call": []}
with tempfile.TemporaryDirectory() as tmp:
    for k in range(rounds):
        a, b = Path(tmp) / f"cli{k}", Path(tmp) / f"py{k}"
        times["cli"].append(timed([cli, "pipeline", pipeline, "--seeds", seeds, "--out", str(a), "--quiet"])[0])
        whole, out = timed([sys.executable, "-c", py, pipeline, seeds, str(b)])
        times["python"].append(whole)
        times["run call"].append(float(out.strip().splitlines()[-1]))
        shutil.rmtree(a), shutil.rmtree(b)
for name, t in times.items():
    print(f"{name:8s} min {min(t):.3f} s  median {statistics.median(t):.3f} s  max {max(t):.3f} s  ({rounds} runs)")
cli_median = statistics.median(times["cli"])
print(f"python process / cli (medians): {statistics.median(times['python']) / cli_median:.3f}")
print(f"run call / cli (medians): {statistics.median(times['run call']) / cli_median:.3f}")
