"""HAWC2 structural (``.st``) files: sets (``#n``) of subsets (``$m rows``) of section tables.

Two layouts (HAWC2 manual, ``timoschenko_input``): the isotropic one, 19 columns, and the fully populated matrix
(``FPM 1``), 30 columns. Everything outside a subset's rows is a comment and is kept verbatim so that a file reads
back to the same record. No physics: :mod:`bladefem.builders.hawc2` maps a subset onto a blade.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..files import write_atomic
from ._text import exact, number, numbered_lines, row

#: The isotropic layout: r, mass, centre of gravity, radii of gyration, shear centre, E, G, area moments, torsion
#: constant, shear factors, area, structural pitch (deg), elastic centre
ISOTROPIC = ("r", "m", "x_cg", "y_cg", "ri_x", "ri_y", "x_sh", "y_sh", "E", "G", "I_x", "I_y", "I_p", "k_x", "k_y",
             "A", "pitch", "x_e", "y_e")
#: The fully populated layout: the 21 upper-triangle entries of the 6x6 stiffness row by row
FPM = ("r", "m", "x_cg", "y_cg", "ri_x", "ri_y", "pitch", "x_e", "y_e") + tuple(
    f"K{i}{j}" for i in range(1, 7) for j in range(i, 7))


@dataclass(frozen=True, eq=False)
class StSubset:
    """One subset: its rows in the file's columns (:data:`ISOTROPIC` or :data:`FPM`)."""

    data: NDArray[np.float64]
    lines: tuple[int, ...] = ()

    @property
    def fpm(self) -> bool:
        return self.data.shape[1] == len(FPM)

    @property
    def columns(self) -> tuple[str, ...]:
        return FPM if self.fpm else ISOTROPIC

    def column(self, name: str) -> NDArray[np.float64]:
        return self.data[:, self.columns.index(name)]

    def stiffness(self) -> NDArray[np.float64]:
        """(n, 6, 6) symmetric stiffness of an FPM subset, as in the file (HAWC2's axes)."""
        K = np.zeros((len(self.data), 6, 6))
        for i in range(6):
            for j in range(i, 6):
                K[:, i, j] = K[:, j, i] = self.column(f"K{i + 1}{j + 1}")
        return K


@dataclass(frozen=True, eq=False)
class HAWC2St:
    """A HAWC2 ``.st`` file: (set, subset) -> rows, and the comment lines before each set and subset."""

    subsets: dict[tuple[int, int], StSubset]
    comments: dict[tuple[int, int], tuple[str, ...]] = field(default_factory=dict)
    head: tuple[str, ...] = ()
    tail: tuple[str, ...] = ()
    path: str = ""

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, HAWC2St):
            return NotImplemented
        return (self.subsets.keys() == other.subsets.keys() and (self.head, self.tail) == (other.head, other.tail)
                and self.comments == other.comments
                and all(np.array_equal(self.subsets[k].data, other.subsets[k].data) for k in self.subsets))

    def subset(self, set_: int = 1, sub: int = 1) -> StSubset:
        if (set_, sub) not in self.subsets:
            raise InputError(f"no set {set_} subset {sub} (the file has "
                             f"{', '.join(f'{a} {b}' for a, b in self.subsets)})", file=self.path, field="set")
        return self.subsets[(set_, sub)]


def read_hawc2_st(path: str | Path) -> HAWC2St:
    """Read a HAWC2 structural file (both layouts; the layout of each subset from its number of columns)."""
    lines = numbered_lines(path)
    subsets: dict[tuple[int, int], StSubset] = {}
    comments: dict[tuple[int, int], tuple[str, ...]] = {}
    head: list[str] = []
    pending: list[str] = []
    current_set = None
    i = 0
    while i < len(lines):
        line, text = lines[i]
        token = text.split()[0] if text.split() else ""
        if token.startswith("#") and token[1:].isdigit():
            current_set = int(token[1:])
            pending.append(text)
            i += 1
            continue
        if token.startswith("$") and token[1:].isdigit():
            if current_set is None:
                raise InputError("subset before any set ('#n' line)", file=str(path), line=line, field="set")
            tokens = text.split()
            if len(tokens) < 2:
                raise InputError("expected '$subset rows'", file=str(path), line=line, field="rows")
            count = number(tokens[1], path, line, "rows")
            if count != int(count) or count < 2:
                raise InputError(f"expected at least 2 rows, got {tokens[1]}", file=str(path), line=line,
                                 field="rows")
            key = (current_set, int(token[1:]))
            if key in subsets:
                raise InputError(f"set {key[0]} subset {key[1]} given twice", file=str(path), line=line, field="set")
            rows, numbers = [], []
            for k in range(int(count)):
                if i + 1 + k >= len(lines):
                    raise InputError(f"file ends after {k} of {int(count)} rows", file=str(path), line=lines[-1][0],
                                     field="rows")
                n, t = lines[i + 1 + k]
                width = len(t.split())
                if not rows:
                    columns = FPM if width >= len(FPM) else ISOTROPIC
                rows.append(row(t, len(columns), path, n, columns))
                numbers.append(n)
            data = np.array(rows)
            comments[key] = tuple(pending) + (text,)
            pending = []
            subsets[key] = StSubset(data, tuple(numbers))
            _check(subsets[key], path)
            i += 1 + int(count)
            continue
        (pending if current_set is not None else head).append(text)
        i += 1
    if not subsets:
        raise InputError("no section table ('#set' then '$subset rows')", file=str(path), line=1, field="set")
    return HAWC2St(subsets, comments, tuple(head), tuple(pending), str(path))


def _check(subset: StSubset, path: str | Path) -> None:
    r = subset.column("r")
    bad = np.flatnonzero(np.diff(r) <= 0)
    if bad.size:
        raise InputError("r must increase", file=str(path), line=subset.lines[bad[0] + 1], field="r")
    positive = ("m",) + (("K11", "K22", "K33", "K44", "K55", "K66") if subset.fpm else ("E", "G", "I_x", "I_y",
                                                                                         "I_p", "A"))
    for name in positive:
        values = subset.column(name)
        bad = np.flatnonzero(values <= 0)
        if bad.size:
            raise InputError(f"must be positive, got {values[bad[0]]:g}", file=str(path),
                             line=subset.lines[bad[0]], field=name)


def hawc2_st_text(st: HAWC2St) -> str:
    out = list(st.head)
    for key, subset in st.subsets.items():
        out += list(st.comments.get(key, (f"#{key[0]}", f"${key[1]} {len(subset.data)}")))[:-1]
        out.append(f"${key[1]} {len(subset.data)}")
        out += ["\t".join(exact(v) for v in values) for values in subset.data]
    return "\n".join(out + list(st.tail)) + "\n"


def write_hawc2_st(st: HAWC2St, path: str | Path) -> None:
    write_atomic(path, hawc2_st_text(st))
