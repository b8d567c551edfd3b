"""A fault scenario's records into ObsPy: run TPV5 at 500 m (its first seconds), read its station
records as an ObsPy Stream with their StationXML inventory and its rupture as a QuakeML catalogue,
and plot the response spectrum of the station nearest the fault beside a real record (the 1992
Landers earthquake at station 5071, examples/data).

    python examples/scenario_obspy.py [OUT_FOLDER] [DURATION_S]   # default reports/tpv5-obspy, 6 s
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import stickslip  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
out = Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "reports" / "tpv5-obspy"
duration = float(sys.argv[2]) if len(sys.argv) > 2 else 6.0

p = stickslip.Pipeline.from_toml(REPO / "pipelines" / "tpv5-500m.toml")
p["shear.duration_s"] = duration
p["report.enabled"] = False
result = stickslip.run(p, out=out)

stream = result.stream("stations")
inventory = result.inventory()
catalog = result.catalog()
print(stream)
print(catalog)

# The surface station nearest the fault: its horizontal pair, HN1 (along strike) and HN2
# (fault-normal), as acceleration: one count is one m/s², so removing the response leaves the
# samples as they are (and shows the inventory describes every channel).
stations = result.stations.sort("r_rup_m")
surface = stations.filter(stations["y_m"].abs() < 1e-6)
name = surface["station"][0]
code = next(s.code for s in inventory[0] if s.site.name == name)
pair = stream.select(station=code, channel="??[12]").copy()
pair.remove_response(inventory=inventory, output="ACC", zero_mean=False, taper=False)
x, z = pair.select(channel="??1")[0], pair.select(channel="??2")[0]

periods = np.logspace(np.log10(0.05), np.log10(10.0), 80)
sim = stickslip.rotd(x.data, z.data, x.stats.delta, periods, 0.05)
real = stickslip.read_record(REPO / "examples" / "data" / "landers-1992-5071-ns.csv", units="cm/s2")
obs = stickslip.spectra(real.accel, real.dt, periods, 0.05)

fig, ax = plt.subplots(figsize=(7, 5), constrained_layout=True)
rrup = surface["r_rup_m"][0] / 1e3
mw = catalog[0].preferred_magnitude().mag
ax.loglog(periods, sim.rotd50[0] / 9.80665, label=f"TPV5 500 m, SS.{code} RotD50 (Mw {mw:.2f}, R_rup {rrup:.1f} km)")
ax.loglog(periods, obs.psa[0] / 9.80665, label="Landers 1992, station 5071 N-S (Mw 7.3, R_rup 14.8 km)")
usable = (surface["usable_min_period_s"][0], surface["usable_max_period_s"][0])
ax.axvspan(periods[0], usable[0], color="0.9", label="outside the simulation's usable band")
ax.axvspan(usable[1], periods[-1], color="0.9")
ax.set(xlabel="period (s)", ylabel="PSA, 5% damping (g)", title=f"The first {duration:g} s of TPV5 beside a real record")
ax.legend(fontsize=8)
figure = out / "scenario-obspy.png"
fig.savefig(figure, dpi=120)
print(f"usable {usable[0]:.2f}-{usable[1]:.2f} s; figure: {figure}")
