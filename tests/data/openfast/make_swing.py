"""Run OpenFAST v5.0.0 on copies of the shipped NREL 5MW deck with the sources of the blade's 1P out-of-plane swing
switched off one at a time, and extract ``rated_swing_v5.json``. Not run by the tests (OpenFAST is not needed to
use the JSON file).

Every case is ``rated_bem2`` of ``make_openfast_v5.py`` (v5 layout additions, 11.4 m/s steady without shear,
12.1 rpm held, GenDOF False, pitch 0, quasi-steady BEM_Mod 2, no tower influence) run for 60 s from the undeflected
state, with these changes:

- ``deck``: none;  ``skew0``: AeroDyn ``Skew_Mod`` 0 (no skewed-wake correction);
- ``gravity0``: the .fst's ``Gravity`` 0;  ``gravity0_skew0``: both;
- ``tilt0``: ElastoDyn ``ShftTilt`` 0 (gravity on, the skew model on);  ``tilt0_gravity0``: both;
- ``twist0``: the blade file's structural twist ``StrcTwst`` 0 at every station (ElastoDyn's flap and edge mode
  shapes then lie in and out of the rotor plane).

Extraction (:func:`harmonic`): blade 1's tip out-of-plane deflection ``OoPDefl1`` over the last four whole
revolutions (from 60 s less 4 x 60 / 12.1 s): its mean, the mean over the revolutions of the peak-to-peak within each
revolution, and its first azimuthal harmonic (amplitude and phase of ``c cos(psi) + s sin(psi)``, psi OpenFAST's
``Azimuth``, 0 = blade 1 up); likewise ``IPDefl1``.

    python tests/data/openfast/make_swing.py OPENFAST_EXECUTABLE RUN_FOLDER
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_aeroturbine import read_out  # noqa: E402  (one reader of OpenFAST's text outputs)
import make_openfast_v5  # noqa: E402  (one preparation of the decks)
from make_openfast_v5 import AD, ED, FST, OPENFAST  # noqa: E402

HERE = Path(__file__).resolve().parent
BLADE = "NRELOffshrBsline5MW_Blade.dat"
DURATION, RPM, REVOLUTIONS = 60.0, 12.1, 4
COMMON = {FST: {"TMax": f"{DURATION:g}", "DT_Out": "0.0125"},
          ED: {"GenDOF": "False", "RotSpeed": f"{RPM}", "BlPitch(1)": "0", "BlPitch(2)": "0", "BlPitch(3)": "0"}}
CASES = {
    "deck": {},
    "skew0": {AD: {"Skew_Mod": "0"}},
    "gravity0": {FST: {"Gravity": "0"}},
    "gravity0_skew0": {FST: {"Gravity": "0"}, AD: {"Skew_Mod": "0"}},
    "tilt0": {ED: {"ShftTilt": "0"}},
    "tilt0_gravity0": {FST: {"Gravity": "0"}, ED: {"ShftTilt": "0"}},
    "twist0": {BLADE: {"StrcTwst": "0"}},
}


def untwisted(path: Path) -> None:
    """The blade file's StrcTwst column (the third of the distributed properties) set to 0."""
    lines = path.read_text().splitlines()
    head = next(k for k, line in enumerate(lines) if line.split()[:1] == ["BlFract"])
    count = int(next(line.split()[0] for line in lines if "NBlInpSt" in line))
    for k in range(head + 2, head + 2 + count):
        words = lines[k].split()
        words[2] = "0.0"
        lines[k] = "  ".join(words)
    path.write_text("\n".join(lines) + "\n")


#: the files a case changes as a whole rather than label by label
SPECIAL = {BLADE: untwisted}


def prepare(case: str, runs: Path) -> Path:
    return make_openfast_v5.prepare(runs / case, COMMON, CASES[case], special=SPECIAL)


def edit(folder: Path, case: str) -> None:
    """The case's own changes (not :data:`COMMON`) made to the deck in ``folder``."""
    make_openfast_v5.apply_edits(folder, {}, CASES[case], special=SPECIAL)


def run(executable: str, runs: Path, workers: int = 2) -> None:
    folders = [prepare(case, runs) for case in CASES]
    with ThreadPoolExecutor(workers) as pool:
        list(pool.map(lambda f: subprocess.run([executable, FST], cwd=f, check=True, stdout=subprocess.DEVNULL),
                      folders))


def harmonic(time: np.ndarray, azimuth_rad: np.ndarray, values: np.ndarray, end: float, rpm: float = RPM,
             revolutions: int = REVOLUTIONS) -> dict:
    """Mean, mean per-revolution peak-to-peak and first azimuthal harmonic of ``values`` over the last
    ``revolutions`` whole revolutions before ``end`` (s), at the constant speed ``rpm``: amplitude (half the
    peak-to-peak of the 1P part) and phase (deg) of ``c cos(psi) + s sin(psi)`` = amplitude cos(psi - phase)."""
    period = 60.0 / rpm
    start = end - revolutions * period
    window = (time >= start - 1e-9) & (time <= end + 1e-9)
    t, psi, v = time[window], azimuth_rad[window], values[window]
    basis = np.column_stack([np.ones_like(psi), np.cos(psi), np.sin(psi)])
    (mean, c, s), *_ = np.linalg.lstsq(basis, v, rcond=None)
    turns = np.minimum(((t - start) / period).astype(int), revolutions - 1)
    peak_to_peak = float(np.mean([np.ptp(v[turns == k]) for k in range(revolutions)]))
    return {"mean": float(f"{mean:.7g}"), "peak_to_peak": float(f"{peak_to_peak:.5g}"),
            "amplitude_1p": float(f"{math.hypot(c, s):.5g}"),
            "phase_1p_deg": float(f"{math.degrees(math.atan2(s, c)):.4g}")}


def statistics(runs: Path) -> dict:
    cases = {}
    for case in CASES:
        data, _ = read_out(runs / case / FST.replace(".fst", ".out"))
        psi = np.radians(data["Azimuth"])
        cases[case] = {name: harmonic(data["Time"], psi, data[name], DURATION) for name in ("OoPDefl1", "IPDefl1")}
    return {"case": "rated_swing_v5",
            "description": "NREL 5MW, 11.4 m/s, 12.1 rpm held, pitch 0, quasi-steady BEM_Mod 2, 60 s from the "
                           "undeflected state; the tip's 1P swing with gravity, shaft tilt, skewed-wake correction "
                           "and structural twist switched off one at a time.",
            "provenance": {"openfast": OPENFAST, "deck": "cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst",
                           "changes_from_deck": ["as rated_bem2 of make_openfast_v5.py, TMax 60 s", "per case: "
                                                 + "; ".join(f"{c}: {e or 'none'}" for c, e in CASES.items())],
                           "script": "tests/data/openfast/make_swing.py",
                           "extraction": f"make_swing.harmonic over the last {REVOLUTIONS} revolutions before "
                                         f"{DURATION:g} s of the 0.0125 s text output"},
            "units": {"mean": "m", "peak_to_peak": "m", "amplitude_1p": "m", "phase_1p_deg": "deg"},
            "cases": cases}


if __name__ == "__main__":
    executable, runs = sys.argv[1], Path(sys.argv[2])
    run(executable, runs)
    (HERE / "rated_swing_v5.json").write_text(json.dumps(statistics(runs), indent=1) + "\n")
