"""BeamDyn input files (OpenFAST v3 to v5): the primary file (key points of the reference axis, the settings and the
name of the blade file) and the blade file (a 6x6 stiffness and a 6x6 mass matrix per station).

The records hold the files' numbers as written, in BeamDyn's axes (OpenFAST docs/source/user/beamdyn/
input_files.rst): key points ``kp_xr`` toward the suction side, ``kp_yr`` toward the trailing edge, ``kp_zr`` along
the blade, twist in degrees about -z; the matrices in the section frame turned by the twist, rows and columns
(shear x, shear y, extension, bending about x = edgewise, bending about y = flapwise, torsion). No physics here:
:mod:`bladefem.builders.beamdyn` maps them onto a blade.

Blade files in the v1.00 layout (``damp_type`` and the six ``mu``) and in the v5 layout (``damp_flag``, ``mu``, then
``n_modes`` modal damping ratios) are read; the writer reproduces the layout it was given.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..files import write_atomic
from ._fast_format import KEY_LINE
from ._text import exact, number, numbered_lines, row

AXES = ("shear x", "shear y", "extension", "bending x (edge)", "bending y (flap)", "torsion")


def _same(a: object, b: object) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return a is None and b is None or (a is not None and b is not None and np.array_equal(a, b))
    return a == b


@dataclass(frozen=True, eq=False)
class BeamDynBlade:
    """A BeamDyn blade file.

    eta : station positions as fractions of the reference axis's arc length (0 root, 1 tip)
    stiffness : (n, 6, 6) section stiffness matrices, N, N m, N m^2
    mass : (n, 6, 6) section mass matrices, kg/m, kg, kg m
    damping_type : damp_type / damp_flag (0 none, 1 stiffness-proportional, 2 modal)
    mu : the six stiffness-proportional damping coefficients, s
    modal_zeta : modal damping ratios (v5 layout), or None for the v1.00 layout
    """

    title: str
    eta: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    mass: NDArray[np.float64]
    damping_type: int = 0
    mu: NDArray[np.float64] = field(default_factory=lambda: np.zeros(6))
    modal_zeta: NDArray[np.float64] | None = None
    path: str = ""
    lines: tuple[int, ...] = ()

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, BeamDynBlade):
            return NotImplemented
        return all(_same(getattr(self, n), getattr(other, n))
                   for n in ("title", "eta", "stiffness", "mass", "damping_type", "mu", "modal_zeta"))


@dataclass(frozen=True, eq=False)
class BeamDynPrimary:
    """A BeamDyn primary file.

    settings_before / settings_after : (label, value as written) of every key line before and after the geometry
    members : key points per member
    key_points : (k, 4) kp_xr, kp_yr, kp_zr (m), initial_twist (deg), as written
    outputs : the lines from ``OutList`` to the end of the file, verbatim
    """

    title: str
    settings_before: tuple[tuple[str, str], ...]
    members: tuple[int, ...]
    key_points: NDArray[np.float64]
    settings_after: tuple[tuple[str, str], ...]
    outputs: tuple[str, ...] = ()
    path: str = ""
    key_lines: dict[str, int] = field(default_factory=dict)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, BeamDynPrimary):
            return NotImplemented
        return all(_same(getattr(self, n), getattr(other, n)) for n in (
            "title", "settings_before", "members", "key_points", "settings_after", "outputs"))

    def setting(self, label: str) -> str | None:
        for key, value in self.settings_before + self.settings_after:
            if key.lower() == label.lower():
                return value
        return None

    @property
    def blade_file(self) -> str:
        """The blade file's name as given (quotes removed), relative to the primary file."""
        value = self.setting("BldFile")
        if value is None:
            raise InputError("missing key", file=self.path, field="BldFile")
        return value.strip("\"'")

    def blade_path(self) -> Path:
        return Path(self.path).parent / self.blade_file


def _is_separator(text: str) -> bool:
    stripped = text.strip()
    return stripped.startswith(("---", "===", "- -")) or not stripped


def _key(text: str) -> tuple[str, str] | None:
    """(label, value) of a 'value label - description' line, or None; a quoted value may hold blanks."""
    tokens = text.split()
    if len(tokens) < 2 or _is_separator(text):
        return None
    if text.lstrip().startswith(('"', "'")) and (match := KEY_LINE.match(text)):
        return match["key"], match["value"]
    value, label = tokens[0], tokens[1]
    if not (label[0].isalpha() or label[0] == "_"):
        return None
    return label, value


def read_beamdyn_primary(path: str | Path) -> BeamDynPrimary:
    """Read a BeamDyn primary input file."""
    lines = numbered_lines(path)
    if len(lines) < 3:
        raise InputError("too short for a BeamDyn primary file", file=str(path), line=len(lines) or 1)
    before: list[tuple[str, str]] = []
    after: list[tuple[str, str]] = []
    key_lines: dict[str, int] = {}
    members: list[int] = []
    points = np.zeros((0, 4))
    outputs: tuple[str, ...] = ()
    i = 2
    while i < len(lines):
        number_, text = lines[i]
        if text.split()[:1] == ["OutList"]:
            outputs = tuple(t for _, t in lines[i:])
            break
        key = _key(text)
        if key is None:
            i += 1
            continue
        label, value = key
        key_lines[label] = number_
        if label == "member_total":
            members, points, i = _geometry(lines, i, path)
            before.append((label, value))
            continue
        (after if members else before).append((label, value))
        i += 1
    if not members:
        raise InputError("missing key", file=str(path), line=len(lines), field="member_total")
    primary = BeamDynPrimary(lines[1][1].strip(), tuple(before), tuple(members), points, tuple(after), outputs,
                             str(path), key_lines)
    if primary.setting("BldFile") is None:
        raise InputError("missing key", file=str(path), line=len(lines), field="BldFile")
    return primary


def _geometry(lines: list[tuple[int, str]], i: int, path: str | Path) -> tuple[list[int], NDArray, int]:
    """Members and key points from the 'member_total' line at index ``i``; the index after the table."""
    def integer(index: int, name: str, minimum: int) -> int:
        line, text = lines[index]
        value = number(text.split()[0], path, line, name)
        if value != int(value) or value < minimum:
            raise InputError(f"expected an integer of at least {minimum}, got {text.split()[0]}", file=str(path),
                             line=line, field=name)
        return int(value)

    total = integer(i, "member_total", 1)
    if i + 1 >= len(lines) or (_key(lines[i + 1][1]) or ("",))[0] != "kp_total":
        raise InputError("missing key (expected on the line after member_total)", file=str(path),
                         line=lines[min(i + 1, len(lines) - 1)][0], field="kp_total")
    kp_total = integer(i + 1, "kp_total", 3)
    members = []
    for m in range(total):
        if i + 2 + m >= len(lines):
            raise InputError("file ends in the member table", file=str(path), line=lines[-1][0], field="kp_member")
        line, text = lines[i + 2 + m]
        values = row(text, 2, path, line, ("member number", "key points in this member"))
        if values[0] != m + 1 or values[1] != int(values[1]) or values[1] < 3:
            raise InputError(f"expected member {m + 1} with at least 3 key points, got {text.strip()!r}",
                             file=str(path), line=line, field="kp_member")
        members.append(int(values[1]))
    if sum(members) != kp_total + total - 1:
        raise InputError(f"the members' key points ({sum(members)}) must be kp_total + member_total - 1 "
                         f"({kp_total + total - 1}): members share their end points", file=str(path),
                         line=lines[i + 1][0], field="kp_total")
    start = i + 2 + total + 2                                   # two header lines (names, units)
    points = []
    for k in range(kp_total):
        if start + k >= len(lines):
            raise InputError(f"file ends after {k} of {kp_total} key points", file=str(path), line=lines[-1][0],
                             field="key points")
        line, text = lines[start + k]
        points.append(row(text, 4, path, line, ("kp_xr", "kp_yr", "kp_zr", "initial_twist")))
    points_ = np.array(points)
    steps = np.flatnonzero(np.linalg.norm(np.diff(points_[:, :3], axis=0), axis=1) == 0)
    if steps.size:
        raise InputError("two consecutive key points coincide", file=str(path), line=lines[start + steps[0] + 1][0],
                         field="kp_zr")
    return members, points_, start + kp_total


def read_beamdyn_blade(path: str | Path) -> BeamDynBlade:
    """Read a BeamDyn blade file."""
    lines = numbered_lines(path)
    keys: dict[str, tuple[int, str]] = {}
    start = None
    for index, (line, text) in enumerate(lines[2:], start=2):
        if "DISTRIBUTED" in text.upper() and _is_separator(text):
            start = index + 1
            break
        key = _key(text)
        if key:
            keys[key[0].lower()] = (line, key[1])
    if start is None:
        raise InputError("no 'DISTRIBUTED PROPERTIES' section", file=str(path), line=len(lines) or 1,
                         field="DISTRIBUTED PROPERTIES")

    def integer(name: str, *aliases: str) -> int:
        for key in (name,) + aliases:
            if key in keys:
                line, token = keys[key]
                value = number(token, path, line, key)
                if value != int(value) or value < 0:
                    raise InputError(f"expected a non-negative integer, got {token}", file=str(path), line=line,
                                     field=key)
                return int(value)
        raise InputError("missing key", file=str(path), line=lines[start - 1][0], field=name)

    total = integer("station_total")
    damping = integer("damp_type", "damp_flag")
    numeric = [(line, text) for line, text in lines[2:start] if _numbers(text) == 6]
    mu = row(numeric[0][1], 6, path, numeric[0][0], "mu") if numeric else np.zeros(6)
    zeta = None
    if "n_modes" in keys:
        count = integer("n_modes")
        line = keys["n_modes"][0]
        rest = [(n, t) for n, t in lines if n > line and n < lines[start - 1][0] and _numbers(t) > 0]
        if count and not rest:
            raise InputError(f"n_modes is {count} but no zeta line follows", file=str(path), line=line, field="zeta")
        zeta = row(rest[0][1], count, path, rest[0][0], "zeta") if count else np.zeros(0)
    if total < 2:
        raise InputError(f"need at least two stations, got {total}", file=str(path), line=keys["station_total"][0],
                         field="station_total")
    data = [(line, text) for line, text in lines[start:] if text.strip()]
    needed = 13 * total
    if len(data) < needed:
        line = data[-1][0] if data else lines[-1][0]
        raise InputError(f"file ends after {len(data) // 13} of {total} stations (each: eta, 6 stiffness rows, 6 mass "
                         "rows)", file=str(path), line=line, field="station_total")
    eta, stiffness, mass, station_lines = [], [], [], []
    for s in range(total):
        block = data[13 * s:13 * s + 13]
        line, text = block[0]
        if len(text.split()) != 1:
            raise InputError(f"expected the station's eta alone on its line, got {len(text.split())} values",
                             file=str(path), line=line, field=f"station {s + 1} eta")
        eta.append(number(text.split()[0], path, line, f"station {s + 1} eta"))
        station_lines.append(line)
        stiffness.append([row(t, 6, path, n, f"station {s + 1} stiffness row {r + 1}")
                          for r, (n, t) in enumerate(block[1:7])])
        mass.append([row(t, 6, path, n, f"station {s + 1} mass row {r + 1}") for r, (n, t) in enumerate(block[7:])])
    blade = BeamDynBlade(lines[1][1].strip() if len(lines) > 1 else "", np.array(eta), np.array(stiffness),
                         np.array(mass), damping, mu, zeta, str(path), tuple(station_lines))
    _check_blade(blade)
    return blade


def _numbers(text: str) -> int:
    """How many leading tokens of the line are numbers."""
    count = 0
    for token in text.split():
        try:
            float(token.replace("d", "e").replace("D", "E"))
        except ValueError:
            break
        count += 1
    return count


def _check_blade(blade: BeamDynBlade) -> None:
    """BeamDyn's own rules (BD_ValidateInputData): eta from 0 to 1, increasing; plus symmetric matrices with
    positive diagonals."""
    def error(message: str, s: int, name: str) -> InputError:
        return InputError(message, file=blade.path, line=blade.lines[s] if blade.lines else None, field=name)

    if blade.eta[0] != 0.0 or blade.eta[-1] != 1.0:
        s = 0 if blade.eta[0] != 0.0 else len(blade.eta) - 1
        raise error(f"station eta must run from 0 to 1, got {blade.eta[s]}", s, "eta")
    bad = np.flatnonzero(np.diff(blade.eta) <= 0)
    if bad.size:
        raise error("station eta must increase", int(bad[0]) + 1, "eta")
    for name, matrices in (("stiffness", blade.stiffness), ("mass", blade.mass)):
        for s, matrix in enumerate(matrices):
            scale = np.max(np.abs(matrix))
            i, j = np.unravel_index(np.argmax(np.abs(matrix - matrix.T)), (6, 6))
            if abs(matrix[i, j] - matrix[j, i]) > 1e-6 * scale:
                raise error(f"{name} matrix not symmetric: ({i + 1},{j + 1}) {matrix[i, j]:g} against "
                            f"({j + 1},{i + 1}) {matrix[j, i]:g}", s, f"{name} row {i + 1}")
            diagonal = np.diag(matrix)
            if np.any(diagonal < 0) or (name == "mass" and diagonal[0] <= 0):
                k = int(np.argmin(diagonal))
                raise error(f"{name} diagonal ({k + 1},{k + 1}) must be positive, got {diagonal[k]:g}", s,
                            f"{name} row {k + 1}")


# -- writing ------------------------------------------------------------------------------------------------------

def _key_line(label: str, value: str) -> str:
    return f"{value:<14} {label}"


def beamdyn_primary_text(primary: BeamDynPrimary) -> str:
    """A BeamDyn primary file holding the record."""
    out = ["--------- BEAMDYN with OpenFAST INPUT FILE (written by bladefem) ----------------------------",
           primary.title or "-", "---------------------- SIMULATION CONTROL --------------------------------------"]
    for label, value in primary.settings_before:
        if label == "member_total":
            out.append("---------------------- GEOMETRY PARAMETER --------------------------------------")
            out.append(_key_line("member_total", str(len(primary.members))))
            out.append(_key_line("kp_total", str(sum(primary.members) - len(primary.members) + 1)))
            out += [f"{m + 1:>6} {n:>6}" for m, n in enumerate(primary.members)]
            out += ["kp_xr kp_yr kp_zr initial_twist", "(m) (m) (m) (deg)"]
            out += [" ".join(exact(v) for v in point) for point in primary.key_points]
            out.append("---------------------- MESH, MATERIAL AND OUTPUT PARAMETERS ---------------------")
        elif label != "kp_total":
            out.append(_key_line(label, value))
    out += [_key_line(label, value) for label, value in primary.settings_after]
    out += list(primary.outputs)
    return "\n".join(out) + "\n"


def beamdyn_blade_text(blade: BeamDynBlade) -> str:
    """A BeamDyn blade file holding the record (the v1.00 layout, or v5's when it has modal damping)."""
    v5 = blade.modal_zeta is not None
    out = [" ------- BEAMDYN INDIVIDUAL BLADE INPUT FILE (written by bladefem) -------------", blade.title or "-",
           " ---------------------- BLADE PARAMETERS --------------------------------------",
           _key_line("station_total", str(len(blade.eta))),
           _key_line("damp_flag" if v5 else "damp_type", str(blade.damping_type)),
           " ---------------------- DAMPING COEFFICIENT------------------------------------",
           "mu1 mu2 mu3 mu4 mu5 mu6", "(s) (s) (s) (s) (s) (s)", " ".join(exact(v) for v in blade.mu)]
    if v5:
        zeta = blade.modal_zeta
        out += [" ---------------------- MODAL DAMPING ----------------------------------------",
                _key_line("n_modes", str(len(zeta))), " ".join(exact(v) for v in zeta) if len(zeta) else "0"]
    out.append(" ---------------------- DISTRIBUTED PROPERTIES---------------------------------")
    for s, eta in enumerate(blade.eta):
        out.append(exact(eta))
        out += [" ".join(exact(v) for v in r) for r in blade.stiffness[s]]
        out.append("")
        out += [" ".join(exact(v) for v in r) for r in blade.mass[s]]
        out.append("")
    return "\n".join(out)


def write_beamdyn_primary(primary: BeamDynPrimary, path: str | Path) -> None:
    write_atomic(path, beamdyn_primary_text(primary))


def write_beamdyn_blade(blade: BeamDynBlade, path: str | Path) -> None:
    write_atomic(path, beamdyn_blade_text(blade))
