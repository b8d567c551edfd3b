"""Pipelines: read, edit, validate, check and write pipeline files from Python."""

from __future__ import annotations

import copy
import json
import math
import os
import re
from pathlib import Path
from typing import Any, Dict, Iterator, List, Mapping, Optional, Tuple, Union

from . import _native
from .errors import PipelineError

PathLike = Union[str, "os.PathLike[str]"]


class Section:
    """A table of a pipeline file, its keys readable and settable as attributes or items.

    ``p.block.nx = 20`` and ``p["block"]["nx"] = 20`` are the same; a key the file does not set
    reads its default only after validation (``Pipeline.default()`` shows every default).
    """

    __slots__ = ("_data", "_path")

    def __init__(self, data: Dict[str, Any], path: str) -> None:
        object.__setattr__(self, "_data", data)
        object.__setattr__(self, "_path", path)

    def __getattr__(self, key: str) -> Any:
        if key.startswith("__"):
            raise AttributeError(key)
        try:
            return _wrap(self._data[key], f"{self._path}.{key}" if self._path else key)
        except KeyError:
            where = f"[{self._path}]" if self._path else "the pipeline"
            raise AttributeError(
                f"{where} does not set {key!r} (set it to add it; keys it sets: {', '.join(self._data) or 'none'})"
            ) from None

    def __setattr__(self, key: str, value: Any) -> None:
        self._data[key] = _unwrap(value)

    def __getitem__(self, key: str) -> Any:
        return _wrap(self._data[key], f"{self._path}.{key}" if self._path else key)

    def __setitem__(self, key: str, value: Any) -> None:
        self._data[key] = _unwrap(value)

    def __delitem__(self, key: str) -> None:
        del self._data[key]

    def __contains__(self, key: object) -> bool:
        return key in self._data

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __dir__(self) -> List[str]:
        return list(self._data)

    def keys(self):  # noqa: D102 - as dict.keys
        return self._data.keys()

    def to_dict(self) -> Dict[str, Any]:
        """A deep copy of the table as plain dicts and lists."""
        return copy.deepcopy(self._data)

    def __repr__(self) -> str:
        return f"Section({self._path!r}, {self._data!r})"


def _refuse_non_finite(node: Any, path: str) -> None:
    """Refuses NaN and infinities with their field before the pipeline is written."""
    if isinstance(node, dict):
        for k, v in node.items():
            _refuse_non_finite(v, f"{path}.{k}" if path else k)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            _refuse_non_finite(v, f"{path}[{i}]")
    elif isinstance(node, float) and not math.isfinite(node):
        allowed = "a finite number"
        raise PipelineError(f"{path} = {node} is not allowed: {allowed}", [(path, str(node), allowed)])


def _wrap(value: Any, path: str) -> Any:
    return Section(value, path) if isinstance(value, dict) else value


def _unwrap(value: Any) -> Any:
    if isinstance(value, Section):
        return value.to_dict()
    if isinstance(value, Mapping):
        return {k: _unwrap(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_unwrap(v) for v in value]
    if hasattr(value, "item") and callable(value.item):  # NumPy scalars
        return value.item()
    return value


class Check:
    """What ``stickslip check`` prints, as data.

    ``lines`` are ``(section, part, text)`` in the order the command prints them; ``facts`` the
    numbers it measured: ``bars``, ``critical_dt_s`` (smallest, largest over the seeds
    inspected), ``dt_s``, ``steps`` (self-weight at most, shear), ``per_step_s``, ``setup_s``.
    """

    def __init__(
        self, name: str, hash: str, lines: List[Tuple[str, str, str]], facts: Optional[Dict[str, Any]] = None
    ) -> None:
        self.name = name
        self.hash = hash
        self.lines = lines
        self.facts: Dict[str, Any] = facts or {}

    @property
    def sections(self) -> Dict[str, List[str]]:
        """The lines' texts by section, in order."""
        out: Dict[str, List[str]] = {}
        for section, _, text in self.lines:
            out.setdefault(section, []).append(text)
        return out

    @property
    def text(self) -> str:
        """The check as the command line prints it."""
        return "\n".join([f"pipeline {self.name}, hash {self.hash}"] + [f"  {t}" for _, _, t in self.lines])

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return f"<stickslip.Check {self.name} ({len(self.lines)} lines)>"


class Pipeline:
    """A pipeline file: its tables as attributes (``p.block.nx``), items (``p["block"]["nx"]``)
    or dotted keys (``p["block.nx"]``), validated by the product itself.

    Build one with :meth:`from_toml`, :meth:`from_dict` or :meth:`default`; :meth:`validate`,
    :meth:`check`, :func:`stickslip.run` and :meth:`to_toml` refuse a value the product does not
    accept with :class:`stickslip.PipelineError` naming the field, the value and the allowed range.
    """

    def __init__(
        self,
        data: Mapping[str, Any],
        *,
        name: str = "pipeline",
        base: Optional[PathLike] = None,
        source: Optional[PathLike] = None,
        text: Optional[str] = None,
    ) -> None:
        self._data: Dict[str, Any] = _unwrap(dict(data))
        self._default_name = name
        self._base = Path(base) if base is not None else Path(".")
        self._source = Path(source) if source is not None else None
        self._text = text
        self._as_read = copy.deepcopy(self._data) if text is not None else None

    # -- construction ------------------------------------------------------------------------
    @classmethod
    def from_toml(cls, path: PathLike) -> "Pipeline":
        """Reads a pipeline file; the files it names are read relative to its folder."""
        path = Path(path)
        text = path.read_text(encoding="utf-8")
        data = json.loads(_native.toml_to_json(text))
        return cls(data, name=path.stem, base=path.parent, source=path, text=text)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], *, name: str = "pipeline", base: Optional[PathLike] = None) -> "Pipeline":
        """A pipeline from nested dicts as the TOML file would hold them, e.g.
        ``{"name": "small", "block": {"nx": 10}, "seeds": {"list": [1, 2]}}``; keys left out
        take their defaults, ``version`` the format this stickslip reads."""
        data = dict(data)
        data.setdefault("version", cls.default()["version"])
        return cls(data, name=name, base=base)

    @classmethod
    def default(cls) -> "Pipeline":
        """Every key with its default (the paper's scene)."""
        return cls(json.loads(_native.toml_to_json(_native.default_toml())))

    # -- fields ------------------------------------------------------------------------------
    def __getattr__(self, key: str) -> Any:
        if key.startswith("_"):
            raise AttributeError(key)
        return getattr(Section(self._data, ""), key)

    def __setattr__(self, key: str, value: Any) -> None:
        if key.startswith("_"):
            object.__setattr__(self, key, value)
        else:
            self._data[key] = _unwrap(value)

    def __getitem__(self, key: str) -> Any:
        node: Any = self._data
        parts = key.split(".")
        for i, part in enumerate(parts):
            if not isinstance(node, dict) or part not in node:
                raise KeyError(f"{'.'.join(parts[: i + 1])}: not set in this pipeline")
            node = node[part]
        return _wrap(node, key)

    def __setitem__(self, key: str, value: Any) -> None:
        node = self._data
        *tables, last = key.split(".")
        for t in tables:
            node = node.setdefault(t, {})
        node[last] = _unwrap(value)

    def __contains__(self, key: str) -> bool:
        try:
            self[key]
        except KeyError:
            return False
        return True

    def to_dict(self) -> Dict[str, Any]:
        """A deep copy of the pipeline as nested dicts."""
        return copy.deepcopy(self._data)

    @property
    def source(self) -> Optional[Path]:
        """The file it was read from, if any."""
        return self._source

    # -- text --------------------------------------------------------------------------------
    def toml(self) -> str:
        """The pipeline as TOML: the file's own text while nothing was changed; otherwise written
        from its fields (keys in order, without the file's comments)."""
        if self._text is not None and self._data == self._as_read:
            return self._text
        _refuse_non_finite(self._data, "")
        return _native.json_to_toml(json.dumps(self._data))

    def _generated(self) -> bool:
        return not (self._text is not None and self._data == self._as_read)

    def _call(self, fn, *args):
        """Calls the native `fn`; a refusal of TOML written from the fields does not cite the
        line of a text the user never saw."""
        try:
            return fn(*args)
        except PipelineError as e:
            if not self._generated():
                raise
            message = re.sub(r"^line \d+: ", "", str(e))
            raise PipelineError(message, e.errors) from None

    def to_toml(self, path: Optional[PathLike] = None) -> str:
        """Writes the pipeline to ``path`` (after validating it) and returns its text."""
        text = self.toml()
        self.validate()
        if path is not None:
            path = Path(path)
            tmp = path.with_name(path.name + ".tmp")
            tmp.write_text(text, encoding="utf-8")
            os.replace(tmp, path)
        return text

    def _args(self) -> Tuple[str, str, str, Optional[str]]:
        source = str(self._source) if self._source is not None and self._data == self._as_read else None
        return self.toml(), self._default_name, str(self._base), source

    # -- the product's view ------------------------------------------------------------------
    def validate(self) -> Dict[str, Any]:
        """Validates the pipeline; returns its ``name``, ``hash``, ``seeds``, whether it is a
        ``fault`` scene, and its ``warnings`` as ``(field, value, why)``."""
        text, name, base, source = self._args()
        return dict(self._call(_native.validate, text, name, base, source))

    @property
    def name(self) -> str:
        """The pipeline's name (its ``name`` key, else the file's stem)."""
        return self.validate()["name"]

    @property
    def hash(self) -> str:
        """The hash of everything that determines its results."""
        return self.validate()["hash"]

    @property
    def seeds(self) -> List[int]:
        """The seeds it runs."""
        return list(self.validate()["seeds"])

    def check(
        self,
        *,
        seeds: Optional[int] = None,
        full_statics: bool = False,
        allow_long: bool = False,
        threads: int = 0,
    ) -> Check:
        """What ``stickslip check`` prints, as a :class:`Check` (it builds the lattice and times
        a probe of the steps; a scene that does not fit in memory is refused before)."""
        text, name, base, source = self._args()
        d = self._call(_native.check, text, name, base, source, seeds, full_statics, allow_long, threads)
        return Check(name=d["name"], hash=d["hash"], lines=[tuple(l) for l in d["lines"]], facts=dict(d["facts"]))

    def __repr__(self) -> str:
        where = f" from {self._source}" if self._source else ""
        return f"<stickslip.Pipeline {self._data.get('name', self._default_name)!r}{where}>"
