"""Mesh-converged pybmodes frequencies of the reference BModes decks: the peer reference of tests/test_pybmodes_decks.py.

pybmodes (Apache-2.0, on the package index) is a Python port of BModes: on the native meshes of BModes' CertTest it
reproduces BModes' printed frequencies to all five printed digits (``test_pybmodes_is_bmodes`` checks it). Like
BModes it takes the section properties constant over each element (at its midpoint), so its frequencies converge
only as h^2. The reference is therefore extrapolated: each deck is written with bladefem's BModes writer on nested
meshes (every station and element boundary of the deck a node, each interval split into ``2^k`` as many pieces),
solved with pybmodes' public API, and the last two meshes whose changes fall by a factor 3.2-6 (the h^2 regime, not
yet round-off) are Richardson-extrapolated, ``f = f_2 + (f_2 - f_1) / 3``; the error estimate stored with each
frequency is ``|f_2 - f_1| / 3``, an upper bound of the extrapolated value's error in that regime.

Run ``python tests/pybmodes_reference.py`` to regenerate tests/data/pybmodes_reference.json (about ten minutes).
"""

from __future__ import annotations

import json
import math
import sys
import tempfile
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REFERENCE = HERE / "data" / "pybmodes_reference.json"
CERTTEST = HERE / "data" / "bmodes_certtest"
#: meshes: every deck interval split into ceil(its length x PIECES) x 2^level elements
PIECES = 1.0
LEVELS = (1, 2, 3, 4)
#: the ratio of successive changes that marks the h^2 regime
H2_RATIO = (3.2, 6.0)
#: modes stored per deck (clamped decks; floating decks add their six platform modes)
MODES = 10


def pybmodes_root() -> Path:
    import pybmodes
    return Path(pybmodes.__file__).parent / "_examples" / "sample_inputs" / "reference_turbines"


def reference_decks() -> dict[str, Path]:
    """The 22 reference-turbine decks of the installed pybmodes and BModes' four CertTest decks, by name."""
    decks = {path.stem: path for path in sorted(pybmodes_root().glob("*/*.bmi"))}
    decks.update({path.stem: path for path in sorted(CERTTEST.glob("*.bmi"))})
    return decks


def nested_mesh(deck, level: int) -> np.ndarray:
    """el_loc of mesh ``level``: the deck's stations and element boundaries, each interval evenly subdivided."""
    points = np.unique(np.concatenate([deck.sections.columns["sec_loc"], deck.el_loc]))
    pieces = [np.linspace(a, b, max(1, math.ceil((b - a) * PIECES * len(points) - 1e-9)) * 2**level,
                          endpoint=False) for a, b in zip(points[:-1], points[1:])]
    return np.concatenate(pieces + [[1.0]])


def mode_count(deck) -> int:
    return MODES + (6 if deck.beam_type == 2 and deck.hub_conn == 2 else 0)


def pybmodes_frequencies(path: Path, level: int) -> np.ndarray:
    """pybmodes' frequencies (Hz) of the deck at ``path`` on nested mesh ``level``."""
    from pybmodes.models import RotatingBlade, Tower

    from bladefem.io.bmodes import read_bmodes
    from bladefem.io.bmodes_writer import write_bmodes
    deck = read_bmodes(path)
    refined = replace(deck, el_loc=nested_mesh(deck, level))
    with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        write_bmodes(refined, Path(folder) / "deck.bmi")
        model = (RotatingBlade if deck.beam_type == 1 else Tower)(Path(folder) / "deck.bmi")
        return np.asarray(model.run(n_modes=mode_count(deck), check_model=False).frequencies, dtype=float)


def extrapolate(levels: dict[int, np.ndarray]) -> tuple[np.ndarray, np.ndarray, list[int]]:
    """Per mode, Richardson on the finest pair of meshes in the h^2 regime; (frequencies, error bounds, the finer
    level used). A mode never in that regime keeps the finest value with the last change as its bound."""
    keys = sorted(levels)
    f = np.array([levels[k] for k in keys])
    changes = np.diff(f, axis=0)
    best, bound, used = f[-1].copy(), np.abs(changes[-1]), [keys[-1]] * f.shape[1]
    for mode in range(f.shape[1]):
        for i in range(len(changes) - 1, 0, -1):
            ratio = changes[i - 1, mode] / changes[i, mode] if changes[i, mode] else np.inf
            if H2_RATIO[0] <= ratio <= H2_RATIO[1]:
                best[mode] = f[i + 1, mode] + changes[i, mode] / 3
                bound[mode] = abs(changes[i, mode]) / 3
                used[mode] = keys[i + 1]
                break
    return best, bound, used


def converged(path: Path) -> dict[str, object]:
    levels = {level: pybmodes_frequencies(path, level) for level in LEVELS}
    frequencies, bound, used = extrapolate(levels)
    return {"frequencies_hz": frequencies.tolist(), "error_bound_hz": bound.tolist(), "finer_level": used,
            "levels": {str(k): v.tolist() for k, v in levels.items()}}


def load() -> dict[str, dict]:
    """The stored reference: deck name -> frequencies_hz, error_bound_hz, ..."""
    return json.loads(REFERENCE.read_text())["decks"]


def main(names: list[str]) -> None:
    import pybmodes
    decks = reference_decks()
    stored = json.loads(REFERENCE.read_text()) if REFERENCE.exists() else {"decks": {}}
    stored["provenance"] = (f"pybmodes {pybmodes.__version__} (PyPI), decks rewritten by bladefem's BModes writer on "
                            f"nested meshes (PIECES = {PIECES}, levels {list(LEVELS)}), Richardson-extrapolated: "
                            "tests/pybmodes_reference.py")
    for name in names or list(decks):
        print(name, flush=True)
        stored["decks"][name] = converged(decks[name])
        REFERENCE.write_text(json.dumps(stored, indent=1) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
