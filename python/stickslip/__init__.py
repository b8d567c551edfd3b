"""stickslip from Python: earthquakes simulated with the Lattice Discrete Element Method.

    import stickslip
    p = stickslip.Pipeline.from_toml("pipelines/paper.toml")
    result = stickslip.run(p, seeds=[7, 123], out="reports/paper-py")
    result.events                  # a polars DataFrame, as tables/events.parquet
    result.stream("records")       # the MiniSEED records as an ObsPy Stream
    result.inventory(), result.catalog()

The numerics are the product's own (compiled, ``stickslip._native``): :func:`spectra` and
:func:`rotd` use the exact oscillator of ``stickslip spectra``; :func:`similarity` the paper's
scaling and Riera magnitude. See docs/guide/python.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Dict, Optional, Sequence

from . import _native
from .errors import PipelineError, RunError, StickslipError
from .pipeline import Check, Pipeline, Section
from .result import Result, open, run

if TYPE_CHECKING:  # NumPy is imported by the functions that use it, not with the package
    import numpy as np

__version__: str = _native.__version__

__all__ = [
    "Check",
    "Pipeline",
    "PipelineError",
    "Record",
    "Result",
    "RunError",
    "Section",
    "Spectra",
    "StickslipError",
    "open",
    "read_record",
    "rotd",
    "run",
    "similarity",
    "spectra",
]


def _floats(name: str, values) -> np.ndarray:
    import numpy as np

    a = np.ascontiguousarray(values, dtype=np.float64).ravel()
    if not np.all(np.isfinite(a)):
        k = int(np.flatnonzero(~np.isfinite(a))[0])
        raise PipelineError(
            f"{name}[{k}] = {a[k]} is not allowed: finite values", [(f"{name}[{k}]", str(a[k]), "finite values")]
        )
    return a


def _periods_dampings(periods, damping):
    import numpy as np

    t = _floats("periods", periods)
    xi = _floats("damping", np.atleast_1d(damping))
    for k, v in enumerate(t):
        if not v > 0:
            raise PipelineError(f"periods[{k}] = {v} is not allowed: a period > 0 s", [(f"periods[{k}]", str(v), "a period > 0 s")])
    for k, v in enumerate(xi):
        if not 0 <= v < 1:
            raise PipelineError(f"damping[{k}] = {v} is not allowed: 0 ≤ ξ < 1", [(f"damping[{k}]", str(v), "0 ≤ ξ < 1")])
    return t, xi


def _positive(name: str, value: float) -> float:
    import numpy as np

    v = float(value)
    if not (np.isfinite(v) and v > 0):
        raise PipelineError(f"{name} = {value} is not allowed: a finite value > 0", [(name, str(value), "a finite value > 0")])
    return v


class _Record:
    """A plain record of named fields (the package imports no dataclasses: a notebook's first
    import stays short)."""

    __slots__: tuple = ()

    def __init__(self, *args, **kwargs) -> None:
        names = self.__slots__
        for name, value in zip(names, args):
            object.__setattr__(self, name, value)
        for name, value in kwargs.items():
            object.__setattr__(self, name, value)

    def __repr__(self) -> str:
        fields = ", ".join(f"{n}={getattr(self, n)!r}" for n in self.__slots__)
        return f"{type(self).__name__}({fields})"


class Spectra(_Record):
    """Response spectra: ``sd`` (m), ``psv`` (m/s) and ``psa`` (m/s²) with shape
    ``(len(dampings), len(periods))`` for an acceleration in m/s²."""

    __slots__ = ("periods", "dampings", "sd")
    periods: np.ndarray
    dampings: np.ndarray
    sd: np.ndarray

    @property
    def psv(self) -> np.ndarray:
        import numpy as np

        return self.sd * (2 * np.pi / self.periods)

    @property
    def psa(self) -> np.ndarray:
        import numpy as np

        return self.sd * (2 * np.pi / self.periods) ** 2


def spectra(
    acceleration: Sequence[float],
    dt: float,
    periods: Sequence[float],
    damping: "float | Sequence[float]" = 0.05,
    *,
    band_limited: bool = False,
) -> Spectra:
    """Response spectra of an accelerogram by the product's exact piecewise-linear oscillator, as
    ``stickslip spectra`` computes them (``band_limited``: the samples read band-limited, FFT
    resampled, instead of as straight lines)."""
    import numpy as np

    a = _floats("acceleration", acceleration)
    t, xi = _periods_dampings(periods, damping)
    if len(a) == 0:
        raise PipelineError("acceleration = [] is not allowed: at least one sample", [("acceleration", "[]", "at least one sample")])
    sd = _native.response_spectrum(a, _positive("dt", dt), t, xi, band_limited)
    return Spectra(periods=t, dampings=xi, sd=np.asarray(sd).reshape(len(xi), len(t)))


class RotD(_Record):
    """RotD spectra of a horizontal pair (shape ``(len(dampings), len(periods))``): ``rotd50``
    and ``rotd100`` PSA (m/s²), the azimuth of RotD100 (degrees from x) and each component's PSA."""

    __slots__ = ("periods", "dampings", "rotd50", "rotd100", "rotd100_angle_deg", "x", "y")
    periods: np.ndarray
    dampings: np.ndarray
    rotd50: np.ndarray
    rotd100: np.ndarray
    rotd100_angle_deg: np.ndarray
    x: np.ndarray
    y: np.ndarray


def rotd(
    x: Sequence[float],
    y: Sequence[float],
    dt: float,
    periods: Sequence[float],
    damping: "float | Sequence[float]" = 0.05,
    *,
    band_limited: bool = False,
) -> RotD:
    """RotD50 and RotD100 (Boore 2010) of a horizontal pair, by the product's own algorithm (every
    angle's peak exact between samples), as PSA in the units of ``x`` and ``y`` (m/s² in, m/s² out)."""
    import numpy as np

    ax, ay = _floats("x", x), _floats("y", y)
    t, xi = _periods_dampings(periods, damping)
    if len(ax) != len(ay) or len(ax) == 0:
        raise PipelineError(
            f"y = {len(ay)} samples is not allowed: as many samples as x ({len(ax)}), at least one",
            [("y", f"{len(ay)} samples", f"as many samples as x ({len(ax)}), at least one")],
        )
    r50, r100, angle, sx, sy = _native.rotd(ax, ay, _positive("dt", dt), t, xi, band_limited)
    w2 = (2 * np.pi / t) ** 2
    shape = (len(xi), len(t))
    as_psa = lambda v: np.asarray(v).reshape(shape) * w2  # noqa: E731
    return RotD(t, xi, as_psa(r50), as_psa(r100), np.asarray(angle).reshape(shape), as_psa(sx), as_psa(sy))


def similarity(
    stress_drop_pa: float,
    model_length_m: float,
    model_area_m2: float,
    model_rate_m_s: float,
    *,
    duration_s: Optional[float] = None,
    recurrence_s: Optional[float] = None,
    prototype_length_m: float = 1.0e4,
    prototype_rate_m_s: float = 3.17e-10,
) -> Dict[str, Optional[float]]:
    """One model event scaled to its prototype by the paper's similarity rules: λ, the prototype
    area, duration and recurrence, both moments (the paper's Eq. 15 and the consistent one, dyne·cm)
    and their magnitudes (Riera's, interplate and intraplate, and Mw)."""
    return dict(
        _native.similarity(
            float(stress_drop_pa),
            float(model_length_m),
            float(model_area_m2),
            float(model_rate_m_s),
            duration_s,
            recurrence_s,
            float(prototype_length_m),
            float(prototype_rate_m_s),
        )
    )


class Record(_Record):
    """An accelerogram read from a file: ``dt`` (s), ``accel`` (m/s²) and its description."""

    __slots__ = ("dt", "accel", "description")
    dt: float
    accel: np.ndarray
    description: str

    @property
    def time(self) -> np.ndarray:
        import numpy as np

        return np.arange(len(self.accel)) * self.dt


def read_record(path: str, units: str = "m/s2") -> Record:
    """Reads a record as the product does: SAC (IDEP = IACC in nm/s²), PEER ``.AT2`` (g), the
    product's own MiniSEED (m/s²), or text columns in ``units`` (``"m/s2"``, ``"cm/s2"``, ``"g"``)."""
    import numpy as np

    dt, accel, description = _native.read_record(str(path), units)
    return Record(dt=dt, accel=np.asarray(accel), description=description)

