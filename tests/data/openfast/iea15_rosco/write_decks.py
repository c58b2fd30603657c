"""Write, run and reduce the OpenFAST v5.0.0 reference runs of the IEA-15MW monopile deck with ROSCO in steady wind,
rigid foundation, quasi-steady aerodynamics: the deck bladefem runs with ``--foundation rigid --quasi-steady``.

The stored deck (``tests/data/iea15``, OpenFAST 3.x layouts written by WEIS) is brought to v5.0.0's layouts by
``../iea_rosco.py`` (shared with the IEA-22MW's runs; its docstring lists every change); for this deck:

- ``.fst``: the IEA deck's ``DT`` 0.005 s (also the controller's); the tower clamped at ``TowerBsHt`` 15 m.
- AeroDyn: the deck's legacy ``WakeMod`` 1 as ``Wake_Mod`` 1, ``BEM_Mod`` 1, ``DBEMT_Mod`` 0.
- InflowWind: steady wind at ``RefHt`` 150 m with the power-law exponent 0.12.

Not run by the tests (OpenFAST is not needed to use ``steady.json``); rerun with

    python tests/data/openfast/iea15_rosco/write_decks.py OPENFAST LIBDISCON RUNS [--reduce]

(``--reduce``: only extract ``steady.json`` from runs made in RUNS).
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
import iea_rosco  # noqa: E402
# OPENFAST, edit, outputs: for the scripts built on these decks (make_blade_aeroelastic_iea15.py, iea15_rigid_rotor)
from iea_rosco import OPENFAST, IEADeck, edit, main, outputs  # noqa: E402, F401

MONO, SHARED = "IEA-15-240-RWT-Monopile", "IEA-15-240-RWT"
#: wind speed (m/s) -> initial rotor speed (rpm), pitch (deg), near the operating point (ROSCO's steady schedule)
CASES = {8.0: (5.68, 0.0), 11.0: (7.55, 4.0), 16.0: (7.55, 12.0)}
DECK = IEADeck(name="iea15", title="IEA-15MW", tree="iea15", mono=MONO, shared=SHARED,
               ed=f"{MONO}_ElastoDyn.dat", ad=f"{MONO}_AeroDyn15.dat", sd=f"{MONO}_ServoDyn.dat",
               iw=f"{SHARED}_InflowFile.dat", blade=f"{SHARED}_ElastoDyn_blade.dat", cases=CASES,
               out=HERE / "steady.json", tmax=200.0, window=(70.0, 120.0), late=(150.0, 200.0))

#: the deck's files, as the scripts that build on these decks name them
FST, ED, AD = DECK.fst, DECK.ed, DECK.ad


def write_case(folder: Path, wind: float, library: str, seconds: float | None = None) -> Path:
    """The v5 deck of one case in ``folder`` for the scripts that build on it (the blade linearizations of
    ``make_blade_aeroelastic_iea15.py``, the rigid rotor of ``iea15_rigid_rotor``): a wind speed outside
    :data:`CASES` starts at rated speed, 7.56 rpm, pitch 0; its .fst."""
    deck = DECK if wind in CASES else replace(DECK, cases={**CASES, wind: (7.56, 0.0)})
    return iea_rosco.write_case(deck, folder, wind, library, seconds)


if __name__ == "__main__":
    main(DECK, sys.argv[1:])
