"""Running pipelines and reading their output folders."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Dict, Iterable, List, Optional, Union

from . import _native
from .pipeline import PathLike, Pipeline

if TYPE_CHECKING:  # polars is imported when a table is first read, not with the package
    import polars as pl

Progress = Union[bool, None, Callable[[int, int], Any]]


SEEDS_ALLOWED = "whole numbers 0 … 2^64−1, each once: a list such as [1, 5, 7], range(1, 11), or a string \"1,5,10-20\""


def _refuse(field: str, value: Any, allowed: str):
    from .errors import PipelineError

    return PipelineError(f"{field} = {value!r} is not allowed: {allowed}", [(field, repr(value), allowed)])


def _parse_seeds(seeds: Union[str, Iterable[int], None]) -> Optional[List[int]]:
    """The seeds asked for, refused before anything runs unless each is a whole number in range,
    given once, and there is at least one."""
    if seeds is None:
        return None
    out: List[int] = []
    if isinstance(seeds, str):
        for part in seeds.split(","):
            part = part.strip()
            lo, _, hi = part.partition("-")
            if not lo.strip().isdigit() or (hi and not hi.strip().isdigit()):
                raise _refuse("seeds", seeds, SEEDS_ALLOWED)
            lo_i, hi_i = int(lo), int(hi) if hi else int(lo)
            if hi_i < lo_i:
                raise _refuse("seeds", seeds, f"ranges from low to high ({part} is empty); " + SEEDS_ALLOWED)
            out.extend(range(lo_i, hi_i + 1))
    else:
        try:
            items = list(seeds)
        except TypeError:
            raise _refuse("seeds", seeds, SEEDS_ALLOWED) from None
        for s in items:
            whole = isinstance(s, int) or (hasattr(s, "is_integer") and not isinstance(s, float) and s.is_integer())
            if isinstance(s, bool) or not (whole or type(s).__name__.startswith(("int", "uint"))):
                raise _refuse("seeds", s, SEEDS_ALLOWED)
            out.append(int(s))
    if not out:
        raise _refuse("seeds", seeds, "at least one seed; " + SEEDS_ALLOWED)
    for s in out:
        if not 0 <= s < 2**64:
            raise _refuse("seeds", s, SEEDS_ALLOWED)
    if len(set(out)) != len(out):
        twice = next(s for s in out if out.count(s) > 1)
        raise _refuse("seeds", twice, "each seed once (it is given twice); " + SEEDS_ALLOWED)
    return out


def _progress_callback(progress: Progress, name: str) -> Optional[Callable[[int, int], Any]]:
    if progress is None or progress is False:
        return None
    if callable(progress):
        return progress
    try:  # a bar that works in terminals and Jupyter alike
        from tqdm.auto import tqdm  # type: ignore[import-not-found]
    except ImportError:
        tqdm = None
    if tqdm is not None:
        bar: Dict[str, Any] = {}

        def update(done: int, total: int) -> None:
            if "bar" not in bar:
                bar["bar"] = tqdm(total=total, desc=name, unit="seed")
            b = bar["bar"]
            b.total = total
            b.n = done
            b.refresh()
            if done >= total:
                b.close()

        return update

    def line(done: int, total: int) -> None:
        sys.stderr.write(f"\r{name}: {done}/{total} seeds")
        if done >= total:
            sys.stderr.write("\n")
        sys.stderr.flush()

    return line


def run(
    pipeline: Union[Pipeline, PathLike],
    *,
    seeds: Union[str, Iterable[int], None] = None,
    out: Optional[PathLike] = None,
    threads: Optional[int] = None,
    fresh: bool = False,
    allow_long: bool = False,
    progress: Progress = True,
) -> "Result":
    """Runs a pipeline's seeds as ``stickslip pipeline`` does and returns the output folder.

    ``seeds`` replaces the pipeline's (a list or ``"1,5,10-20"``); ``out`` defaults to
    ``reports/<name>``; ``threads`` to one per core; ``fresh`` discards another pipeline's results
    found in ``out``. Finished seeds found in ``out`` are kept (an interrupted run resumes). The
    solver runs with the GIL released; Ctrl-C stops the running seeds (finished ones are kept) and
    raises ``KeyboardInterrupt``. ``progress``: ``True`` for a bar (tqdm when installed, a line on
    stderr otherwise), ``False`` for none, or a callable ``(done, total)``.
    """
    if not isinstance(pipeline, Pipeline):
        pipeline = Pipeline.from_toml(pipeline)
    if threads is not None and (isinstance(threads, bool) or not isinstance(threads, int) or threads < 1):
        raise _refuse("threads", threads, "a whole number ≥ 1 (or None for one per core)")
    if not (progress is None or isinstance(progress, bool) or callable(progress)):
        raise _refuse("progress", progress, "True (a bar), False or None (none), or a callable (done, total)")
    chosen = _parse_seeds(seeds)
    info = pipeline.validate()
    text, name, base, source = pipeline._args()
    out_path = Path(out) if out is not None else Path("reports") / info["name"]
    callback = _progress_callback(progress, info["name"])
    from .errors import RunError

    try:
        report = pipeline._call(
            _native.run, text, name, base, str(out_path), source, chosen, threads or 0, fresh, allow_long, callback
        )
    except RunError as e:
        # The library's advice names the CLI's flags; here they are arguments.
        message = str(e).replace("Use --fresh", "Use fresh=True").replace("--out", "out=").replace("--allow-long", "allow_long=True")
        raise RunError(message) from None
    return Result(out_path, run=dict(report))


def open(folder: PathLike) -> "Result":  # noqa: A001 - the package's verb, as in stickslip.open(...)
    """The output folder of a run (``stickslip pipeline`` or :func:`run`)."""
    return Result(folder)


class Result:
    """An output folder: its tables as polars DataFrames, its records, stations and catalogue.

    ``result.events``, ``result.similarity``, ``result.summary``, ``result.stations``,
    ``result.station_spectra``, … are the tables of the same names (every table the folder
    holds: ``result.tables``), read on first use and kept. ``result.scan(name)`` is the lazy
    form over the per-seed parts (``tables/<name>/seed-*.parquet``) or the gathered file.
    """

    def __init__(self, folder: PathLike, run: Optional[Dict[str, Any]] = None) -> None:
        self.folder = Path(folder)
        if not self.folder.is_dir():
            raise FileNotFoundError(f"{self.folder}: no such folder")
        if not (self.folder / "manifest.toml").is_file():
            raise FileNotFoundError(f"{self.folder}: not a stickslip output folder (no manifest.toml)")
        # What the run that returned this did (empty when the folder was opened).
        self.run: Dict[str, Any] = run or {}
        self._cache: Dict[str, pl.DataFrame] = {}

    # -- tables ------------------------------------------------------------------------------
    @property
    def tables(self) -> List[str]:
        """The tables the folder holds."""
        root = self.folder / "tables"
        names = {p.stem for p in root.glob("*.parquet")} | {p.name for p in root.iterdir() if p.is_dir()}
        return sorted(names)

    def scan(self, name: str) -> pl.LazyFrame:
        """Table ``name`` as a LazyFrame: the gathered file when there is one, else its per-seed
        parts (columns a seed lacks are null)."""
        import polars as pl

        root = self.folder / "tables"
        gathered = root / f"{name}.parquet"
        if gathered.is_file():
            return pl.scan_parquet(gathered)
        parts = sorted((root / name).glob("seed-*.parquet"))
        if not parts:
            raise KeyError(f"{self.folder}: no table {name!r} (tables: {', '.join(self.tables)})")
        return pl.concat([pl.scan_parquet(p) for p in parts], how="diagonal_relaxed")

    def table(self, name: str) -> pl.DataFrame:
        """Table ``name`` as a DataFrame."""
        if name not in self._cache:
            self._cache[name] = self.scan(name).collect()
        return self._cache[name]

    def __getattr__(self, name: str) -> pl.DataFrame:
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self.table(name)
        except KeyError as e:
            raise AttributeError(str(e)) from None

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self.tables))

    @property
    def pipeline(self) -> Pipeline:
        """The pipeline that made the folder (its copy in the folder)."""
        return Pipeline.from_toml(self.folder / "pipeline.toml")

    # -- files -------------------------------------------------------------------------------
    def mseed_files(self, kind: str = "all") -> List[Path]:
        """The MiniSEED records: ``"records"`` (a block's event records), ``"stations"`` (a
        fault scenario's station records, one file per seed), ``"set"`` (a matched set), or
        ``"all"``."""
        folders = {"records": ["records"], "stations": ["mseed"], "set": ["set"]}
        chosen = [d for k in folders for d in folders[k]] if kind == "all" else folders.get(kind)
        if chosen is None:
            raise ValueError(f"kind = {kind!r} is not allowed: one of 'records', 'stations', 'set', 'all'")
        return sorted(p for d in chosen for p in (self.folder / d).glob("*.mseed"))

    @property
    def inventory_path(self) -> Path:
        """The StationXML inventory of the folder's MiniSEED records."""
        return self.folder / "stations.xml"

    @property
    def catalogue_path(self) -> Path:
        """The QuakeML catalogue of the folder's events."""
        return self.folder / "catalogue.xml"

    def stream(self, kind: str = "all", pattern: str = "*"):
        """The MiniSEED records as an ObsPy ``Stream`` (needs ObsPy): ``kind`` as in
        :meth:`mseed_files` (``"records"``, ``"stations"``, ``"set"``, ``"all"``); ``pattern``
        filters the file names (e.g. ``"*seed7*"``). Refused when no file matches."""
        import fnmatch

        from obspy import Stream, read  # type: ignore[import-not-found]

        st = Stream()
        files = [p for p in self.mseed_files(kind) if fnmatch.fnmatch(p.name, pattern)]
        if not files:
            have = [k for k in ("records", "stations", "set") if self.mseed_files(k)]
            raise FileNotFoundError(
                f"{self.folder}: no MiniSEED files of kind {kind!r} matching {pattern!r}; this folder has "
                + (", ".join(repr(k) for k in have) if have else "none (add \"mseed\" to accelerograms.formats)")
            )
        for p in files:
            st += read(str(p), format="MSEED")
        return st

    def inventory(self):
        """The stations as an ObsPy ``Inventory`` (needs ObsPy)."""
        from obspy import read_inventory  # type: ignore[import-not-found]

        return read_inventory(str(self.inventory_path), format="STATIONXML")

    def catalog(self):
        """The events as an ObsPy ``Catalog`` (needs ObsPy)."""
        from obspy import read_events  # type: ignore[import-not-found]

        return read_events(str(self.catalogue_path), format="QUAKEML")

    def __repr__(self) -> str:
        return f"<stickslip.Result {self.folder}>"
