"""Extract the OpenFAST v4.2.1 results of the issue-11 part 2 runs (aerodynamics in the turbine model) into JSON.

Not run by the tests (OpenFAST is not needed to use the JSON files). The runs are copies of
``/work/openfast/runs/rated_fixed_speed`` (see README.md) with the changes listed in each file's provenance, run with
``/work/openfast/install/bin/openfast NRELOffshrBsline5MW_Onshore.fst`` in ``RUNS/<case>``:

- ``rated_mod1``: AeroDyn ``BEM_Mod`` 1 (legacy "NoSweepPitchTwist" projection, bladefem's) instead of the deck's 2
  -> ``rated_fixed_speed_bem_mod1.json`` (mean, std, min, max over 80-100 s, as rated_fixed_speed.json);
- ``signs_fixed`` and ``signs_free``: ElastoDyn initial conditions OoPDefl 2 m, IPDefl -0.5 m, Azimuth 30 deg,
  NacYaw 3 deg, TTDspFA 0.2 m, TTDspSS 0.1 m, ``YawPzn`` added to the outputs, TMax 10 s, DT_Out 0.05 s; GenDOF
  False (rotor speed held at 12.1 rpm) and True (ServoDyn's torque law) -> ``channel_signs.json`` (every channel
  every 0.1 s).

    python tests/data/openfast/make_aeroturbine.py RUNS
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
OPENFAST = {"version": "v4.2.1", "commit": "2daa99a0f9f573642816d6f52c07a2e3b77a85f1",
            "build": "gfortran 12.2.0 (Debian 12), CMake Release, double precision, openfast glue code only",
            "executable": "/work/openfast/install/bin/openfast (outside the repository)"}
SIGN_CHANNELS = ("OoPDefl1", "IPDefl1", "TTDspFA", "TTDspSS", "YawPzn", "Azimuth", "RotSpeed", "LSSGagVxa",
                 "GenSpeed", "RootMOoP1", "RootMIP1", "RotThrust", "RotTorq", "RotPwr", "GenTq", "GenPwr",
                 "BldPitch1", "RtAeroFxh", "RtAeroMxh", "RtAeroPwr", "RtTSR", "RtAeroCp", "RtAeroCt")
CONDITIONS = "ElastoDyn OoPDefl 2 m, IPDefl -0.5 m, Azimuth 30 deg, NacYaw 3 deg, TTDspFA 0.2 m, TTDspSS 0.1 m"


def read_out(path: Path) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    lines = path.read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("Time"))
    names, units = lines[start].split(), lines[start + 1].split()
    data = np.loadtxt(lines[start + 2:])
    return {n: data[:, j] for j, n in enumerate(names)}, {n: u.strip("()") for n, u in zip(names, units)}


def statistics(runs: Path) -> dict:
    data, units = read_out(runs / "rated_mod1" / "NRELOffshrBsline5MW_Onshore.out")
    window = data["Time"] >= 80.0 - 1e-9
    channels = {name: {"unit": units[name], "mean": float(f"{values[window].mean():.7g}"),
                       "std": float(f"{values[window].std():.7g}"), "min": float(f"{values[window].min():.7g}"),
                       "max": float(f"{values[window].max():.7g}")}
                for name, values in data.items() if name != "Time"}
    return {"case": "rated_fixed_speed_bem_mod1",
            "description": "As rated_fixed_speed.json (NREL 5MW, 11.4 m/s, 12.1 rpm fixed, pitch 0, quasi-steady "
                           "BEM, 100 s) with AeroDyn's legacy BEM_Mod 1 projection instead of the deck's BEM_Mod 2.",
            "provenance": {"openfast": OPENFAST, "deck": "cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst",
                           "changes_from_deck": ["all changes of rated_fixed_speed.json",
                                                 "AeroDyn BEM_Mod 1 (was 2)"],
                           "extraction": "mean, population standard deviation, min and max over 80 <= t <= 100 s "
                                         "of the text output (every 0.0125 s); 7 significant digits"},
            "window_s": [80.0, 100.0], "channels": channels}


def signs(runs: Path) -> dict:
    cases = {}
    for case, generator in (("signs_fixed", "GenDOF False: rotor speed held at 12.1 rpm"),
                            ("signs_free", "GenDOF True: ServoDyn's simple variable-speed torque law")):
        data, units = read_out(runs / case / "NRELOffshrBsline5MW_Onshore.out")
        rows = np.isclose(np.round(data["Time"] / 0.1) * 0.1, data["Time"], atol=1e-9)
        cases[case] = {"generator": generator, "time_s": [round(float(t), 4) for t in data["Time"][rows]],
                       "channels": {name: {"unit": units[name],
                                           "values": [float(f"{v:.7g}") for v in data[name][rows]]}
                                    for name in SIGN_CHANNELS}}
    return {"case": "channel_signs",
            "description": "NREL 5MW at 11.4 m/s from a deflected, yawed initial state (" + CONDITIONS + "), 10 s: "
                           "every output channel's time history, to check bladefem's names, units and signs.",
            "provenance": {"openfast": OPENFAST, "deck": "cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst",
                           "changes_from_deck": ["all changes of rated_fixed_speed.json", CONDITIONS,
                                                 "TMax 10 s, DT_Out 0.05 s (every second row kept)",
                                                 "signs_free: GenDOF True"],
                           "notes": [("At t = 0 OpenFAST writes the root moments without the blades' inertial "
                                      "loads; compare from the first step on."),
                                     ("With GenDOF False ServoDyn's GenTq/GenPwr are the torque law at the imposed "
                                      "speed, not the torque that holds it.")]},
            "cases": cases}


if __name__ == "__main__":
    runs = Path(sys.argv[1])
    (HERE / "rated_fixed_speed_bem_mod1.json").write_text(json.dumps(statistics(runs), indent=1) + "\n")
    (HERE / "channel_signs.json").write_text(json.dumps(signs(runs), indent=1) + "\n")
