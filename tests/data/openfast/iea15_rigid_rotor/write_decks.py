"""Write, run and reduce the OpenFAST v5.0.0 reference runs of the IEA-15MW's rigid rotor (every ElastoDyn DOF off)
in steady sheared wind at a fixed rotor speed and pitch: the aerodynamic loads of the prebent blade's AeroDyn nodes.

The decks are those of ``../iea15_rosco/write_decks.py`` (the IEA-15MW monopile deck in v5.0.0's layouts, rigid
foundation, quasi-steady BEM: its docstring lists every change) with these further changes:

- ``.fst``: ``CompServo`` 0 (no controller: the pitch stays at ``BlPitch``), ``DT_Out`` = ``DT`` 0.005 s, ``TMax``
  one rotor revolution and a step;
- ElastoDyn: every DOF off (``GenDOF`` included: the rotor turns at ``RotSpeed``);
- AeroDyn: ``BEM_Mod`` 1 (legacy projection, as the ROSCO runs) or 2 (polar projection).

And one flexible case (``FLEXIBLE``): 8 m/s, 5.68 rpm, pitch 0, ``BEM_Mod`` 1, 60 s with the deck's blade and
tower DOFs and only ``GenDOF`` off (the rotor held at its speed, no controller), output every 0.05 s: the means over
the last three revolutions of ``RtAeroFxh``, ``RtAeroMxh``, ``RootMyc1``, ``OoPDefl1`` and ``TTDspFA``.

Per rigid case: the means over the samples of the first whole revolution (0 <= t < 60 / rpm) of ``RtAeroFxh`` (N),
``RtAeroMxh`` (N m), ``RtAeroPwr`` (W) and the blade-root moments ``RootMyc1``, ``RootMxc1`` (kN m). Not run by the
tests; rerun with

    python tests/data/openfast/iea15_rigid_rotor/write_decks.py OPENFAST LIBDISCON RUNS

(LIBDISCON: any path; the controller is not run but the ServoDyn file names it.)
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "iea15_rosco"))
sys.path.insert(0, str(HERE.parent))
import write_decks as rosco  # noqa: E402  (the ROSCO runs' decks)
from make_aeroturbine import read_out  # noqa: E402

#: (wind m/s, rotor speed rpm, pitch deg, BEM_Mod)
CASES = ((8.0, 5.68, 0.0, 1), (16.0, 7.56, 12.95, 1), (8.0, 5.68, 0.0, 2), (16.0, 7.56, 12.95, 2))
DOFS = ("FlapDOF1", "FlapDOF2", "EdgeDOF", "TeetDOF", "DrTrDOF", "GenDOF", "YawDOF", "TwFADOF1", "TwFADOF2",
        "TwSSDOF1", "TwSSDOF2")
CHANNELS = ("RtAeroFxh", "RtAeroMxh", "RtAeroPwr", "RootMyc1", "RootMxc1")


def name(case: tuple) -> str:
    wind, rpm, pitch, bem = case
    return f"u{wind:g}_bem{bem}"


def write_case(folder: Path, case: tuple, library: str) -> Path:
    wind, rpm, pitch, bem = case
    deck = rosco.write_case(folder, wind, library, seconds=60.0 / rpm + 0.1)
    rosco.edit(deck, "CompServo", "0")
    rosco.edit(deck, "DT_Out", "0.005")
    ed = folder / rosco.MONO / rosco.ED
    for dof in DOFS:
        rosco.edit(ed, dof, "False")
    rosco.edit(ed, "RotSpeed", f"{rpm:g}")
    for b in (1, 2, 3):
        rosco.edit(ed, f"BlPitch({b})", f"{pitch:g}")
    rosco.outputs(ed, ("RootMyc1", "RootMxc1"))
    ad = folder / rosco.MONO / rosco.AD
    rosco.edit(ad, "BEM_Mod", str(bem))
    rosco.outputs(ad, ("RtAeroMxh", "RtAeroPwr"))
    return deck


FLEXIBLE = (8.0, 5.68, 0.0, 1)
FLEXIBLE_SECONDS, FLEXIBLE_CHANNELS = 60.0, ("RtAeroFxh", "RtAeroMxh", "RootMyc1", "OoPDefl1", "TTDspFA")


def write_flexible(folder: Path, library: str) -> Path:
    wind, rpm, pitch, bem = FLEXIBLE
    deck = rosco.write_case(folder, wind, library, seconds=FLEXIBLE_SECONDS)
    rosco.edit(deck, "CompServo", "0")
    ed = folder / rosco.MONO / rosco.ED
    rosco.edit(ed, "GenDOF", "False")
    rosco.edit(ed, "RotSpeed", f"{rpm:g}")
    for b in (1, 2, 3):
        rosco.edit(ed, f"BlPitch({b})", f"{pitch:g}")
    rosco.outputs(ed, ("RootMyc1",))
    ad = folder / rosco.MONO / rosco.AD
    rosco.edit(ad, "BEM_Mod", str(bem))
    rosco.outputs(ad, ("RtAeroMxh",))
    return deck


def flexible_means(runs: Path) -> dict:
    wind, rpm, pitch, bem = FLEXIBLE
    data, _ = read_out(runs / "flexible" / rosco.MONO / rosco.FST.replace(".fst", ".out"))
    start = FLEXIBLE_SECONDS - 3 * 60.0 / rpm
    window = data["Time"] >= start - 1e-9
    return {"wind_speed_m_s": wind, "rotor_speed_rpm": rpm, "pitch_deg": pitch, "bem_mod": bem,
            "run_s": FLEXIBLE_SECONDS, "window_s": [start, FLEXIBLE_SECONDS],
            "means": {c: float(f"{data[c][window].mean():.7g}") for c in FLEXIBLE_CHANNELS}}


def reduce(runs: Path) -> None:
    results = []
    for case in CASES:
        wind, rpm, pitch, bem = case
        data, _ = read_out(runs / name(case) / rosco.MONO / rosco.FST.replace(".fst", ".out"))
        revolution = data["Time"] < 60.0 / rpm - 1e-9
        means = {channel: float(f"{data[channel][revolution].mean():.7g}") for channel in CHANNELS}
        results.append({"wind_speed_m_s": wind, "rotor_speed_rpm": rpm, "pitch_deg": pitch, "bem_mod": bem,
                        "samples": int(revolution.sum()), "means": means})
    out = {"case": "IEA-15MW rigid rotor (every ElastoDyn DOF off), fixed speed and pitch, steady sheared wind, "
                   "quasi-steady BEM",
           "provenance": {"openfast": rosco.OPENFAST, "deck": f"tests/data/iea15/{rosco.MONO}/{rosco.FST}",
                          "script": "tests/data/openfast/iea15_rigid_rotor/write_decks.py (the changes: its "
                                    "docstring and that of ../iea15_rosco/write_decks.py)",
                          "extraction": "means over the samples (every 0.005 s) of the first whole revolution; "
                                        "7 significant digits; OpenFAST's units (N, N m, W, kN m)"},
           "cases": results, "flexible": flexible_means(runs)}
    (HERE / "rigid_rotor.json").write_text(json.dumps(out, indent=1) + "\n")


def main(openfast: str, library: str, runs: str) -> None:
    for case in CASES:
        deck = write_case(Path(runs) / name(case), case, library)
        subprocess.run([openfast, deck.name], cwd=deck.parent, check=True, stdout=subprocess.DEVNULL)
    deck = write_flexible(Path(runs) / "flexible", library)
    subprocess.run([openfast, deck.name], cwd=deck.parent, check=True, stdout=subprocess.DEVNULL)
    reduce(Path(runs))


if __name__ == "__main__":
    main(*sys.argv[1:4])
