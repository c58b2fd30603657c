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
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from iea_rosco import IEADeck, main  # noqa: E402

MONO, SHARED = "IEA-15-240-RWT-Monopile", "IEA-15-240-RWT"
#: wind speed (m/s) -> initial rotor speed (rpm), pitch (deg), near the operating point (ROSCO's steady schedule)
CASES = {8.0: (5.68, 0.0), 11.0: (7.55, 4.0), 16.0: (7.55, 12.0)}
DECK = IEADeck(name="iea15", title="IEA-15MW", tree="iea15", mono=MONO, shared=SHARED,
               ed=f"{MONO}_ElastoDyn.dat", ad=f"{MONO}_AeroDyn15.dat", sd=f"{MONO}_ServoDyn.dat",
               iw=f"{SHARED}_InflowFile.dat", blade=f"{SHARED}_ElastoDyn_blade.dat", cases=CASES,
               out=HERE / "steady.json", tmax=200.0, window=(70.0, 120.0), late=(150.0, 200.0))


if __name__ == "__main__":
    main(DECK, sys.argv[1:])
