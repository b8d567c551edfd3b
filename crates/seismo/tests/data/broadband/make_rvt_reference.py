"""Random-vibration-theory reference for tests/broadband.rs: the 5%-damped PSA that pyrvt 0.8.1
(A. Kottke, MIT licence; https://github.com/arkottke/pyrvt) gives for the Fourier amplitude
spectrum of the stochastic part's point source, written to rvt_point_source.csv.

The spectrum is computed here from its formula with numpy, independently of the Rust code (the
test checks that both give the same numbers): one subfault of moment M0 = 10^(1.5·6 + 9.1) N·m
(Mw 6) whose size dl = (M0/Δσ)^(1/3) makes its subevent moment M0 (so N = 1, C = 1), at R = 20 km,
in the crust of the product's fault scenes (β = 3464 m/s, ρ = 2670 kg/m³), with the Western-US
parameters of the Graves–Pitarka method: Δσ = 50 bar, κ0 = 0.04 s, Q(f) = (57 + 34·3.464)·f^0.6,
rupture speed 0.775 β (f_c = 2·0.775·β/(π·dl)), Boore & Joyner (1997) generic rock crust, radiation
0.42 on a horizontal component, free surface 2.

Durations (RVT's ground-motion duration T_gm): T_gm = 1/f_c + D_p(R), D_p the Boore & Thompson
(2014) Western-US path duration. Peak factors: Boore & Thompson (2015) ("BT15", the RMS-duration
correction fitted to time-domain stochastic simulations whose Saragoni–Hart window reaches η at
2·T_gm), and Cartwright & Longuet-Higgins (1956) with Boore & Joyner (1984)'s correction ("BJ84")
for comparison.

Run: python3 make_rvt_reference.py   (pip install pyrvt==0.8.1)
"""

import numpy as np
import pyrvt

beta, rho = 3464.0, 2670.0
m0 = 10 ** (1.5 * 6.0 + 9.1)
sp = 5e6
dl = (m0 / sp) ** (1.0 / 3.0)
fc = 2.0 * 0.775 * beta / (np.pi * dl)
r = 20e3
kappa, q0, eta = 0.04, 57.0 + 34.0 * beta / 1000.0, 0.6
radiation, free_surface = 0.42, 2.0
generic_rock = np.array(
    [
        (0.01, 1.00), (0.09, 1.10), (0.16, 1.18), (0.51, 1.42), (0.84, 1.58), (1.25, 1.74),
        (2.26, 2.06), (3.17, 2.25), (6.05, 2.58), (16.6, 3.13), (61.2, 4.00), (100.0, 4.40),
    ]
)


def crust(f):
    return np.interp(np.log(f), np.log(generic_rock[:, 0]), generic_rock[:, 1])


def fas(f):
    w = 2 * np.pi * f
    source = free_surface * radiation / (4 * np.pi * rho * beta**3) * m0 * w**2 / (1 + (f / fc) ** 2)
    path = np.exp(-np.pi * f * (kappa + r / beta / (q0 * f**eta))) / r
    return source * path * crust(f)


bt14 = [(0.0, 0.0), (7.0, 2.4), (45.0, 8.4), (125.0, 10.9), (175.0, 17.4), (270.0, 34.2)]
dp = np.interp(r / 1e3, [p[0] for p in bt14], [p[1] for p in bt14])
t_gm = 1.0 / fc + dp

freqs = np.geomspace(0.01, 50.0, 2048)
amps = fas(freqs)
periods = [0.02, 0.03, 0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0]
osc = 1.0 / np.array(periods)
bt15 = pyrvt.motions.RvtMotion(freqs, amps, t_gm, "BT15", {"region": "wna", "mag": 6.0, "dist": r / 1e3})
bj84 = pyrvt.motions.RvtMotion(freqs, amps, t_gm, "BJ84")
psa_bt15 = bt15.calc_osc_accels(osc, 0.05)
psa_bj84 = bj84.calc_osc_accels(osc, 0.05)

with open("rvt_point_source.csv", "w") as out:
    out.write("# " + __doc__.strip().replace("\n", "\n# ") + "\n")
    out.write(f"# f_c = {fc!r} Hz, dl = {dl!r} m, T_gm = {t_gm!r} s; pyrvt {pyrvt.__version__}\n")
    out.write("# Rows 'fas': frequency (Hz), Fourier amplitude (m/s). Rows 'psa': period (s), PSA (m/s^2) BT15, BJ84.\n")
    out.write("kind,x,a,b\n")
    for f in [0.05, 0.1, 0.27, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 40.0]:
        out.write(f"fas,{f!r},{float(fas(np.array(f)))!r},\n")
    for t, a, b in zip(periods, psa_bt15, psa_bj84):
        out.write(f"psa,{t!r},{float(a)!r},{float(b)!r}\n")
print(f"T_gm = {t_gm:.4f} s, f_c = {fc:.5f} Hz")
