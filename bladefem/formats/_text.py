"""Small helpers shared by the whitespace-separated text formats: numbered lines and located number parsing."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, shown
from ..files import read_input


def numbered_lines(path: str | Path) -> list[tuple[int, str]]:
    """The lines of a text file with their 1-based numbers (UTF-8, undecodable bytes replaced)."""
    data = read_input(path)
    if b"\x00" in data[:65536]:
        raise InputError("not a text file (contains NUL bytes)", file=str(path),
                         line=data[:data.index(b"\x00")].count(b"\n") + 1)
    return list(enumerate(data.decode("utf-8", errors="replace").splitlines(), start=1))


def number(token: str, path: str | Path, line: int, field: str) -> float:
    """A finite float from ``token`` (Fortran ``d`` exponents accepted), else an InputError at ``line``."""
    try:
        value = float(token.replace("d", "e").replace("D", "E"))
    except ValueError:
        raise InputError(f"expected a number, got {shown(token)}", file=str(path), line=line, field=field) from None
    if not math.isfinite(value):
        raise InputError(f"expected a finite number, got {shown(token)}", file=str(path), line=line, field=field)
    return value


def row(text: str, count: int, path: str | Path, line: int, fields: tuple[str, ...] | str) -> NDArray[np.float64]:
    """The first ``count`` numbers of a line; ``fields`` names each column (or one name for all)."""
    tokens = text.split()
    names = fields if isinstance(fields, tuple) else tuple(f"{fields}[{i + 1}]" for i in range(count))
    if len(tokens) < count:
        raise InputError(f"expected {count} numbers, got {len(tokens)}", file=str(path), line=line,
                         field=names[len(tokens)] if len(tokens) < len(names) else names[-1])
    return np.array([number(tokens[i], path, line, names[i]) for i in range(count)])


def exact(value: float) -> str:
    """A float written so that it reads back to the same double."""
    return repr(float(value))
