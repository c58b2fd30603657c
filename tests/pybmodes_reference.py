"""Mesh-converged pybmodes frequencies of the reference BModes decks, the peer reference of test_pybmodes_decks.py.

pybmodes (Apache-2.0, on the package index) is a Python port of BModes: on the native meshes of BModes' CertTest it
reproduces BModes' printed frequencies to all five printed digits (``test_pybmodes_is_bmodes`` checks it). Like
BModes it takes the section properties constant over each element (at its midpoint), so its frequencies converge
only as h^2. The reference is therefore extrapolated: each deck is written with bladefem's BModes writer on nested
meshes (every station of the deck a node, each interval split into ``2^k`` as many pieces),
solved with pybmodes' public API, and the last two meshes whose changes fall by a factor 3.2-6 (the h^2 regime, not
yet round-off) are Richardson-extrapolated, ``f = f_2 + (f_2 - f_1) / 3``; the error estimate stored with each
frequency is ``|f_2 - f_1| / 3``, an upper bound of the extrapolated value's error in that regime. Where round-off
sets in before the h^2 regime shows (decks whose axial stiffness is a million times the bending stiffness per
square metre, as pybmodes' reference-turbine decks have), the mesh with the smallest change is kept and its bound
is the larger of the changes into and out of it.

Run ``python tests/pybmodes_reference.py [DECK ...]`` to regenerate tests/data/pybmodes_reference.json (an hour of
CPU for all decks), ``python tests/pybmodes_reference.py --causes`` for the table of named differences in
docs/VALIDATION.md.
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
LEVELS = (0, 1, 2, 3, 4)
#: meshes finer than this are skipped (pybmodes solves dense; on the reference-turbine decks round-off has set in
#: well before it)
MAX_ELEMENTS = 800
#: the ratios of successive changes where Richardson's ``f_2 + (f_2 - f_1) / 3`` is used with the bound
#: ``|f_2 - f_1| / 3``: for changes falling geometrically by ``r`` the remaining error is ``|f_2 - f_1| / (r - 1)``,
#: within the bound of the extrapolated value for every ``r >= 2.5`` (h^2 gives 4; these decks' blades show 3-3.6
#: on the finest meshes); above 6 the changes are no longer the discretization's
H2_RATIO = (2.5, 6.0)
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


def attachments(deck) -> np.ndarray:
    """Where the deck's tension wires attach, fraction of the flexible length."""
    return np.array([deck.el_loc[node - 1] for node in deck.wires.node_attach]) if deck.wires else np.zeros(0)


def nested_mesh(deck, level: int) -> np.ndarray:
    """el_loc of mesh ``level``: the deck's stations and wire attachments, each interval evenly subdivided. (The
    deck's other element boundaries are left out, and stations a millimetre apart are one node as in bladefem's
    meshes: such sliver elements spoil both codes' round-off.)"""
    from bladefem.assembly.mesh import merge_near_steps
    points = merge_near_steps(np.concatenate([deck.sections.columns["sec_loc"], attachments(deck)]))
    pieces = [np.linspace(a, b, max(1, math.ceil((b - a) * PIECES * len(points) - 1e-9)) * 2**level,
                          endpoint=False) for a, b in zip(points[:-1], points[1:])]
    return np.concatenate(pieces + [[1.0]])


def mode_count(deck) -> int:
    return MODES + (6 if deck.beam_type == 2 and deck.hub_conn == 2 else 0)


def pybmodes_frequencies(path: Path, level: int) -> np.ndarray:
    """pybmodes' frequencies (Hz) of the deck at ``path`` on nested mesh ``level``."""
    from pybmodes.models import RotatingBlade, Tower

    from bladefem.formats.bmodes import read_bmodes
    from bladefem.formats.bmodes_writer import write_bmodes
    deck = read_bmodes(path)
    el_loc = nested_mesh(deck, level)
    refined = replace(deck, el_loc=el_loc)
    if deck.wires:                           # the same attachment points, numbered in the new mesh
        nodes = tuple(int(np.argmin(np.abs(el_loc - x))) + 1 for x in attachments(deck))
        refined = replace(refined, wires=replace(deck.wires, node_attach=nodes))
    with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        write_bmodes(refined, Path(folder) / "deck.bmi")
        model = (RotatingBlade if deck.beam_type == 1 else Tower)(Path(folder) / "deck.bmi")
        return np.asarray(model.run(n_modes=mode_count(deck), check_model=False).frequencies, dtype=float)


def extrapolate(levels: dict[int, np.ndarray]) -> tuple[np.ndarray, np.ndarray, list[int]]:
    """Per mode, Richardson on the finest pair of meshes in the h^2 regime; (frequencies, error bounds, the finer
    level used). A mode never in that regime keeps the mesh whose larger change (into or out of it) is smallest,
    with that change as its bound."""
    keys = sorted(levels)
    f = np.array([levels[k] for k in keys])
    changes = np.abs(np.diff(f, axis=0))
    best, bound, used = np.empty(f.shape[1]), np.empty(f.shape[1]), []
    for mode in range(f.shape[1]):
        step = np.diff(f[:, mode])
        for i in range(len(step) - 1, 0, -1):
            ratio = step[i - 1] / step[i] if step[i] else np.inf
            if H2_RATIO[0] <= ratio <= H2_RATIO[1]:
                best[mode], bound[mode] = f[i + 1, mode] + step[i] / 3, abs(step[i]) / 3
                used.append(keys[i + 1])
                break
        else:
            around = np.maximum(changes[:, mode], np.append(changes[1:, mode], 0.0))
            k = int(np.argmin(around))
            best[mode], bound[mode] = f[k + 1, mode], around[k]
            used.append(keys[k + 1])
    return best, bound, used


def converged(path: Path, known: dict[str, list[float]] | None = None) -> dict[str, object]:
    """The reference entry of a deck; ``known`` levels (as stored) are not solved again."""
    from bladefem.formats.bmodes import read_bmodes
    known = known or {}
    deck = read_bmodes(path)
    levels = {level: np.array(known[str(level)]) if str(level) in known else pybmodes_frequencies(path, level)
              for level in LEVELS if len(nested_mesh(deck, level)) - 1 <= MAX_ELEMENTS}
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
        stored["decks"][name] = converged(decks[name], stored["decks"].get(name, {}).get("levels"))
        REFERENCE.write_text(json.dumps(stored, indent=1) + "\n")


def causes(elements: int = 160) -> str:
    """A Markdown table: per deck, bladefem's largest difference from the reference with its own physics and with
    every difference switched to BModes', and the largest effect of each named difference alone (relative, over the
    stored modes)."""
    from bmodes_physics import NAMES, frequencies

    from bladefem.formats.bmodes import read_bmodes
    decks, reference = reference_decks(), load()
    rows = [f"| deck | bladefem | all switched | {' | '.join(NAMES)} |", "|---" * (len(NAMES) + 3) + "|"]
    for name, entry in reference.items():
        deck = read_bmodes(decks[name])
        expected, count = np.array(entry["frequencies_hz"]), len(entry["frequencies_hz"])
        switched = frequencies(deck, count, elements, NAMES)
        effects = [np.abs(frequencies(deck, count, elements, tuple(n for n in NAMES if n != cause)) / switched - 1)
                   .max() for cause in NAMES]
        own = np.abs(frequencies(deck, count, elements) / expected - 1).max()
        cells = [f"{own:.1e}", f"{np.abs(switched / expected - 1).max():.1e}"]
        cells += [f"{effect:.1e}" if effect > 1e-7 else "-" for effect in effects]
        rows.append(f"| {name} | {' | '.join(cells)} |")
    return "\n".join(rows)


if __name__ == "__main__":
    if sys.argv[1:] == ["--causes"]:
        print(causes())
    else:
        main(sys.argv[1:])
