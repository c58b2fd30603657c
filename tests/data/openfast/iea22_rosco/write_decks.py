"""Write, run and reduce the OpenFAST v5.0.0 reference runs of the IEA-22MW monopile deck with ROSCO in steady wind,
rigid foundation, quasi-steady aerodynamics, ElastoDyn's blades: the deck bladefem runs with ``--foundation rigid
--quasi-steady --elastodyn-blades``.

The stored deck (``tests/data/iea22``, OpenFAST 3.x layouts written by WEIS) is brought to v5.0.0's layouts by
``../iea_rosco.py`` (shared with the IEA-15MW's runs; its docstring lists every change); for this deck:

- ``.fst``: ``CompElast`` 1, the blades of the ElastoDyn blade file the deck names (``BldFile1``-``3``) instead of
  its BeamDyn blades (bladefem's ``--elastodyn-blades``); ``DT`` 0.005 s (also the controller's ``DLL_DT``
  "default") instead of the deck's 0.0002 s, a step chosen for BeamDyn; the tower clamped at ``TowerBsHt`` 15 m.
- AeroDyn: the deck's ``WakeMod`` 11 (v3.5's BEM with the polar projection) as ``Wake_Mod`` 1, ``BEM_Mod`` 2,
  ``DBEMT_Mod`` 0.
- InflowWind: steady wind at ``RefHt`` 170 m with the power-law exponent 0.14.

Not run by the tests (OpenFAST is not needed to use ``steady.json``); rerun with

    python tests/data/openfast/iea22_rosco/write_decks.py OPENFAST LIBDISCON RUNS [--reduce]

(``--reduce``: only extract ``steady.json`` from runs made in RUNS).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from iea_rosco import IEADeck, main  # noqa: E402

MONO, SHARED = "IEA-22-280-RWT-Monopile", "IEA-22-280-RWT"
#: wind speed (m/s) -> initial rotor speed (rpm), pitch (deg), near the operating point of ROSCO's tuning (the
#: DISCON.IN's VS_TSRopt 9.15 and minimum pitch table below rated, VS_RefSpd 7.06 rpm and the Cp table above)
CASES = {8.0: (4.92, -1.0), 12.0: (7.06, 7.0), 16.0: (7.06, 14.1)}
DECK = IEADeck(name="iea22", title="IEA-22MW", tree="iea22", mono=MONO, shared=SHARED,
               ed=f"{SHARED}_ElastoDyn.dat", ad=f"{SHARED}_AeroDyn15.dat", sd=f"{SHARED}_ServoDyn.dat",
               iw=f"{SHARED}_InflowFile.dat", blade=f"{SHARED}_ElastoDyn_blade.dat", cases=CASES,
               out=HERE / "steady.json", dt="0.005", tmax=200.0, window=(70.0, 120.0), late=(150.0, 200.0))


if __name__ == "__main__":
    main(DECK, sys.argv[1:])
