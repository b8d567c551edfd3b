"""The exceptions stickslip raises."""

from __future__ import annotations

from typing import List, Optional, Sequence, Tuple


class StickslipError(Exception):
    """Base of every stickslip error."""


class PipelineError(StickslipError, ValueError):
    """A pipeline refused before anything ran.

    ``errors`` lists every refused value as ``(field, value, allowed)``; ``field``, ``value`` and
    ``allowed`` are those of the first (``None`` when the refusal names no field, e.g. TOML that
    does not parse at all).
    """

    def __init__(self, message: str, errors: Sequence[Tuple[str, str, str]] = ()) -> None:
        super().__init__(message)
        self.errors: List[Tuple[str, str, str]] = [tuple(e) for e in errors]  # type: ignore[misc]
        first = self.errors[0] if self.errors else (None, None, None)
        self.field: Optional[str] = first[0]
        self.value: Optional[str] = first[1]
        self.allowed: Optional[str] = first[2]


class RunError(StickslipError, RuntimeError):
    """A run that could not be done: refused by its memory or length budget, an output folder
    holding another pipeline's results, a file that could not be written."""
