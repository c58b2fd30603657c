"""The parts of a HAWC2 ``.htc`` file that describe a beam body: each ``main_body``'s name, its
``timoschenko_input`` (st file, ``FPM`` flag, set and subset) and its ``c2_def`` reference axis (``sec i x y z
twist``: HAWC2's body axes, m, twist in degrees). Commands end with ';', the rest of a line after it is a comment.
The writer writes those blocks alone (a body file HAWC2 can ``continue_in_file``), not the whole model.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..files import write_atomic
from ._text import exact, number, numbered_lines


@dataclass(frozen=True, eq=False)
class MainBody:
    """One HAWC2 main body.

    c2_def : (n, 4) x, y, z (m) and twist (deg) of the half-chord reference axis, HAWC2's body axes
    st_file : the timoschenko_input filename as written (relative to the folder HAWC2 runs in)
    """

    name: str
    c2_def: NDArray[np.float64]
    st_file: str = ""
    fpm: bool = False
    st_set: tuple[int, int] = (1, 1)
    line: int = 0

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, MainBody) and (self.name, self.st_file, self.fpm, self.st_set) == (
            other.name, other.st_file, other.fpm, other.st_set) and np.array_equal(self.c2_def, other.c2_def))


@dataclass(frozen=True)
class HAWC2Bodies:
    bodies: dict[str, MainBody]
    path: str = field(default="", compare=False)

    def body(self, name: str) -> MainBody:
        if name not in self.bodies:
            raise InputError(f"no main_body '{name}' (the file has {', '.join(self.bodies) or 'none'})",
                             file=self.path, field="main_body")
        return self.bodies[name]


def _commands(path: str | Path) -> list[tuple[int, list[str]]]:
    """(line, words) of every command (text before ';', which may not span lines in the parts read here)."""
    out = []
    for line, text in numbered_lines(path):
        command = text.split(";")[0].split()
        if command:
            out.append((line, command))
    return out


def read_hawc2_bodies(path: str | Path) -> HAWC2Bodies:
    """The main bodies of a HAWC2 ``.htc`` file that have a ``c2_def``."""
    bodies: dict[str, MainBody] = {}
    stack: list[str] = []
    body: dict = {}
    sections: list[NDArray] = []
    nsec = 0
    for line, words in _commands(path):
        head = words[0].lower()
        if head == "begin" and len(words) > 1:
            stack.append(words[1].lower())
            if stack[-1] == "main_body":
                body = {"line": line, "name": "", "st_file": "", "fpm": False, "st_set": (1, 1)}
                sections, nsec = [], 0
            continue
        if head == "end" and len(words) > 1:
            if not stack or stack[-1] != words[1].lower():
                raise InputError(f"'end {words[1]}' closes {'begin ' + stack[-1] if stack else 'nothing'}",
                                 file=str(path), line=line, field="end")
            closed = stack.pop()
            if closed == "c2_def" and len(sections) != nsec:
                raise InputError(f"nsec {nsec} but {len(sections)} sec lines", file=str(path), line=line,
                                 field="nsec")
            if closed == "main_body" and sections:
                bodies[body["name"]] = MainBody(body["name"], np.array(sections), body["st_file"], body["fpm"],
                                                body["st_set"], body["line"])
            continue
        where = stack[-1] if stack else ""
        if where == "main_body" and head == "name" and len(words) > 1:
            body["name"] = words[1]
        elif where == "timoschenko_input" and head == "filename" and len(words) > 1:
            body["st_file"] = words[1]
        elif where == "timoschenko_input" and head == "fpm" and len(words) > 1:
            body["fpm"] = number(words[1], path, line, "FPM") != 0
        elif where == "timoschenko_input" and head == "set" and len(words) > 2:
            body["st_set"] = (int(number(words[1], path, line, "set")), int(number(words[2], path, line, "set")))
        elif where == "c2_def" and head == "nsec" and len(words) > 1:
            nsec = int(number(words[1], path, line, "nsec"))
        elif where == "c2_def" and head == "sec":
            if len(words) < 6:
                raise InputError("expected 'sec i x y z twist'", file=str(path), line=line, field="sec")
            index = number(words[1], path, line, "sec")
            if index != len(sections) + 1:
                raise InputError(f"expected sec {len(sections) + 1}, got {words[1]}", file=str(path), line=line,
                                 field="sec")
            sections.append(np.array([number(w, path, line, n) for w, n in zip(words[2:6], "xyz") ] +
                                     [number(words[5], path, line, "twist")]))
    if stack:
        raise InputError(f"'begin {stack[-1]}' never ended", file=str(path), line=None, field="end")
    return HAWC2Bodies(bodies, str(path))


def hawc2_bodies_text(bodies: HAWC2Bodies) -> str:
    out = []
    for body in bodies.bodies.values():
        out += ["begin main_body;", f"  name {body.name} ;", "  type timoschenko ;", "  begin timoschenko_input;",
                f"    filename {body.st_file} ;", f"    FPM {int(body.fpm)} ;",
                f"    set {body.st_set[0]} {body.st_set[1]} ;", "  end timoschenko_input;", "  begin c2_def;",
                f"    nsec {len(body.c2_def)} ;"]
        out += [f"    sec {i + 1} " + " ".join(exact(v) for v in s) + " ;" for i, s in enumerate(body.c2_def)]
        out += ["  end c2_def ;", "end main_body;"]
    return "\n".join(out) + "\n"


def write_hawc2_bodies(bodies: HAWC2Bodies, path: str | Path) -> None:
    write_atomic(path, hawc2_bodies_text(bodies))
