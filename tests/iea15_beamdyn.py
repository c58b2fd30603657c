"""The IEA-15-240-RWT BeamDyn blade of tests/data/iea15mw_sections as six-by-six sections (a test helper: the
package's own BeamDyn reader is bladefem.formats)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from bladefem.builders.section_axes import full_sections_from_beamdyn
from bladefem.sections import FullSections

DATA = Path(__file__).resolve().parent / "data" / "iea15mw_sections"


def key_points() -> np.ndarray:
    """(kp_xr, kp_yr, kp_zr, twist in deg) rows of the primary file."""
    lines = (DATA / "IEA-15-240-RWT_BeamDyn.dat").read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if "kp_xr" in line) + 2
    rows = []
    for line in lines[start:]:
        try:
            rows.append([float(v) for v in line.split()[:4]])
        except ValueError:
            break
        if len(rows[-1]) < 4:
            rows.pop()
            break
    return np.array(rows)


def stations() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(eta, stiffness, mass) of the blade file's 26 stations: eta along the axis (0 to 1), the 6x6 matrices in
    BeamDyn's axes, the stiffness made exactly symmetric (the file's differs in the last digits)."""
    lines = (DATA / "IEA-15-240-RWT_BeamDyn_blade.dat").read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if "DISTRIBUTED PROPERTIES" in line) + 1
    rows = [[float(v) for v in line.split()] for line in lines[start:] if line.strip()]
    eta = np.array([rows[i][0] for i in range(0, len(rows), 13)])
    K = np.array([rows[i + 1:i + 7] for i in range(0, len(rows), 13)])
    M = np.array([rows[i + 7:i + 13] for i in range(0, len(rows), 13)])
    return eta, 0.5 * (K + np.swapaxes(K, 1, 2)), M


def iea15_sections() -> FullSections:
    """The 26 stations at eta times the key points' arc length (117.15 m; the prebend and sweep left out: a
    straight blade), the twist interpolated in arc length."""
    eta, K, M = stations()
    points = key_points()
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points[:, :3], axis=0), axis=1))])
    span = eta * arc[-1]
    twist = np.radians(np.interp(span, arc, points[:, 3]))
    return full_sections_from_beamdyn(span, K, M, twist, source=str(DATA / "IEA-15-240-RWT_BeamDyn_blade.dat"))
