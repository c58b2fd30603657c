"""The tower-support block of a BModes tower deck: tension wires and the platform (or monopile) block.

The block starts at ``tow_support``; which layout follows is found from the content: a ``draft`` entry on the next
line starts the platform block (see :mod:`bladefem.formats.bmodes`).
Matrices are read row by row from the lines after their labels, arrays from the line that ends with their key
(``0. 10.  : z_distr_m ...``), each with exactly the number of values the layout says.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ._fast_format import FastText
from .bmodes import BModesPlatform, BModesWires, is_number, label_line, leading_numbers, row

#: what tow_support means in each layout
TOW_SUPPORT = {0: "none", 1: "tension wires (v3.00) or platform block and wires (later layout)",
               2: "platform block (offshore branch of the v3 source)"}


@dataclass(frozen=True)
class Support:
    """What the support block holds: layout, ``tow_support``, platform and wires, and the lines of its keys."""

    layout: str
    tow_support: int
    platform: BModesPlatform | None = None
    wires: BModesWires | None = None
    key_lines: dict[str, int] = field(default_factory=dict)


def read_support(text: FastText, nselt: int) -> Support:
    """The support block of a tower deck (no block at all reads as ``tow_support = 0``)."""
    if not text.has("tow_support"):
        return Support("v3.00", 0)
    tow_support = text.int("tow_support")
    start = text.line_of("tow_support")
    if tow_support not in TOW_SUPPORT:
        raise text.error(f"must be 0 (none), 1 (tension wires, or platform and wires) or 2 (platform), got "
                         f"{tow_support}", start, "tow_support")
    block = _platform_follows(text, start)
    if tow_support == 2 and not block:
        raise text.error("tow_support = 2 must be followed by the platform block (draft, cm_pform, ...)", start + 1,
                         "draft")
    layout = ("offshore" if tow_support == 2 else "platform") if block else "v3.00"
    lines: dict[str, int] = {"tow_support": start}
    platform = _platform(text, start, lines) if block and tow_support > 0 else None
    wires = _wires(text, nselt, lines) if tow_support == 1 else None
    return Support(layout, tow_support, platform, wires, lines)


def _platform_follows(text: FastText, start: int) -> bool:
    """True when the first non-blank line after ``tow_support`` is a value for ``draft``."""
    for number in range(start + 1, len(text.lines) + 1):
        words = text.lines[number - 1].split()
        if words:
            return is_number(words[0]) and "draft" in (word.rstrip(":") for word in words[1:])
    return False


def word_line(text: FastText, key: str, after: int) -> int:
    """1-based number of the first line after ``after`` with the word ``key`` (a trailing colon allowed)."""
    for number in range(after + 1, len(text.lines) + 1):
        if key in (word.rstrip(":") for word in text.lines[number - 1].split()):
            return number
    raise text.error("missing key", len(text.lines) or None, key)


def _point(text: FastText, key: str, after: int, lines: dict[str, int]) -> tuple[float, float, float]:
    """A depth with an optional horizontal offset: ``d  key`` or ``d x y  key`` (pybmodes' extension; the key may
    be written ``key_xyz``)."""
    number = min((word_line(text, name, after) for name in (key, f"{key}_xyz") if _has_word(text, name, after)),
                 default=None)
    if number is None:
        raise text.error("missing key", len(text.lines) or None, key)
    values = leading_numbers(text, number, key)
    if len(values) not in (1, 3):
        raise text.error(f"expected the depth, or the depth and a horizontal offset x y (3 values), found "
                         f"{len(values)} values", number, key)
    lines[key] = number
    return (values[0], values[1], values[2]) if len(values) == 3 else (values[0], 0.0, 0.0)


def _has_word(text: FastText, key: str, after: int) -> bool:
    return any(key in (w.rstrip(":") for w in line.split()) for line in text.lines[after:])


def _matrix(text: FastText, label: str, size: int, after: int, lines: dict[str, int]) -> tuple[NDArray, int]:
    """A ``size`` x ``size`` matrix from the rows after the line holding ``label``; (matrix, its last line)."""
    number = label_line(text, label, after)
    lines[label] = number
    rows = [row(text, number + i, size, label) for i in range(1, size + 1)]
    return np.array(rows), number + size


def _array(text: FastText, key: str, count: int, after: int, lines: dict[str, int]) -> NDArray:
    """``count`` values from the line ending with ``key`` (when ``count`` is 0 the line is only a placeholder)."""
    number = word_line(text, key, after)
    lines[key] = number
    values = leading_numbers(text, number, key)
    if count == 0:
        return np.zeros(0)
    if len(values) != count:
        raise text.error(f"expected {count} values, found {len(values)}", number, key)
    return np.array(values)


def _distribution(text: FastText, count_key: str, z_key: str, value_key: str, after: int,
                  lines: dict[str, int]) -> tuple[NDArray, NDArray]:
    count = text.int(count_key, minimum=0)
    lines[count_key] = text.line_of(count_key)
    if count == 0 and not _placeholder_follows(text, z_key, lines[count_key]):
        # no sections: the placeholder rows may be left out (the IEA-15MW's BModes tower deck, pybmodes)
        return np.zeros(0), np.zeros(0)
    z = _array(text, z_key, count, after, lines)
    values = _array(text, value_key, count, lines[z_key], lines)
    if count > 0 and np.any(np.diff(z) <= 0):
        raise text.error("heights must increase strictly", lines[z_key], z_key)
    if np.any(values < 0):
        raise text.error(f"must not be negative, got {values[values < 0][0]}", lines[value_key], value_key)
    return z, values


def _placeholder_follows(text: FastText, key: str, count_line: int) -> bool:
    """True when the first non-blank line after the count line holds the word ``key`` (a placeholder row)."""
    for number in range(count_line + 1, len(text.lines) + 1):
        words = [word.rstrip(":") for word in text.lines[number - 1].split()]
        if words:
            return key in words
    return False


def _platform(text: FastText, start: int, lines: dict[str, int]) -> BModesPlatform:
    draft = text.float("draft")
    lines["draft"] = text.line_of("draft")
    cm_pform, cm_x, cm_y = _point(text, "cm_pform", start, lines)
    mass = text.float("mass_pform", non_negative=True)
    lines["mass_pform"] = text.line_of("mass_pform")
    inertia, last = _matrix(text, "i_matrix_pform", 3, start, lines)
    ref_msl, ref_x, ref_y = _point(text, "ref_msl", last, lines)
    hydro_m, last = _matrix(text, "hydro_M", 6, lines["ref_msl"], lines)
    hydro_k, last = _matrix(text, "hydro_K", 6, last, lines)
    mooring_k, last = _matrix(text, "mooring_K", 6, last, lines)
    z_m, m = _distribution(text, "n_secs_m_distr", "z_distr_m", "distr_m", last, lines)
    z_k, k = _distribution(text, "n_secs_k_distr", "z_distr_k", "distr_k", last, lines)
    return BModesPlatform(draft=draft, cm_pform=cm_pform, mass_pform=mass, i_matrix_pform=inertia, ref_msl=ref_msl,
                          hydro_M=hydro_m, hydro_K=hydro_k, mooring_K=mooring_k, added_mass_z=z_m, added_mass=m,
                          distributed_stiffness_z=z_k, distributed_stiffness=k, cm_pform_xy=(cm_x, cm_y),
                          ref_msl_xy=(ref_x, ref_y))


def _wires(text: FastText, nselt: int, lines: dict[str, int]) -> BModesWires | None:
    attachments = text.int("n_attachments", minimum=0)
    lines["n_attachments"] = start = text.line_of("n_attachments")
    if attachments == 0:
        return None
    counts = _array(text, "n_wires", attachments, start, lines)
    nodes = _array(text, "node_attach", attachments, start, lines)
    stiffness = _array(text, "wire_stfness", attachments, start, lines)
    angles = _array(text, "th_wire", attachments, start, lines)
    for name, values in (("n_wires", counts), ("node_attach", nodes)):
        if np.any(values != np.round(values)):
            raise text.error("expected whole numbers", lines[name], name)
    if np.any(counts < 3):
        raise text.error("at least 3 wires per attachment (BModes' rule)", lines["n_wires"], "n_wires")
    if np.any(nodes < 2) or np.any(nodes > nselt + 1):
        raise text.error(f"attachment nodes must lie in 2..{nselt + 1} (node 1 is the flexible base)",
                         lines["node_attach"], "node_attach")
    if np.any(stiffness < 0):
        raise text.error("must not be negative", lines["wire_stfness"], "wire_stfness")
    if np.any(angles < 0) or np.any(angles > 90):
        raise text.error("the wire angle from the horizontal plane must lie in 0..90 deg", lines["th_wire"],
                         "th_wire")
    return BModesWires(tuple(int(c) for c in counts), tuple(int(n) for n in nodes),
                       tuple(float(s) for s in stiffness), tuple(math.radians(a) for a in angles))
