"""Run OpenFAST v5.0.0 on the shipped NREL 5MW torque-law deck at its time step and at half of it, and store how
far the two runs lie apart: an estimate of OpenFAST's own time-integration error at the deck's step, against which
bladefem's default integrator tolerance is held (tests/test_turbine_step_error.py). Not run by the tests (OpenFAST
is not needed to use the JSON file).

The deck is ``cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst`` as shipped (11.4 m/s steady wind, ServoDyn's torque
law, all ElastoDyn DOFs on, ``DT`` 0.00625 s, ElastoDyn's ABM4, outputs every 0.05 s), brought to v5's layout by
``make_openfast_v5.prepare`` (the v5 layout, the extended output lists); ``TMax`` 100 s. The second
run sets ``DT`` 0.003125 s (AeroDyn and ServoDyn follow the glue code's step: ``DTAero`` and ``DT`` "default").
For every channel of :data:`CHANNELS`: the largest absolute difference of the two runs over the 100 s (the output
times are the same) and the standard deviation of the finer run over 20-100 s (the channel's scale).

    python tests/data/openfast/make_step_error.py OPENFAST_EXECUTABLE RUN_FOLDER
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_aeroturbine import read_out  # noqa: E402
from make_openfast_v5 import FST, OPENFAST, prepare  # noqa: E402

HERE = Path(__file__).resolve().parent
#: OpenFAST's steps: the deck's and half of it, s
STEPS = ("0.00625", "0.003125")
#: the channels compared (OpenFAST's names and units; bladefem writes the same names with the unit appended)
CHANNELS = ("OoPDefl1", "IPDefl1", "TTDspFA", "TTDspSS", "RotSpeed", "GenPwr", "GenTq", "RotThrust", "RotTorq",
            "RootMOoP1", "RootMIP1", "TwrBsMyt", "RtAeroFxh", "RtAeroPwr")


def run(executable: str, folder: Path, step: str) -> dict[str, np.ndarray]:
    case = prepare(folder / f"dt_{step}", {}, {FST: {"TMax": "100", "DT": step}})
    subprocess.run([executable, FST], cwd=case, check=True, stdout=subprocess.DEVNULL)
    return read_out(case / FST.replace(".fst", ".out"))[0]


def main(executable: str, folder: str) -> None:
    coarse, fine = (run(executable, Path(folder), step) for step in STEPS)
    window = fine["Time"] >= 20.0 - 1e-9
    channels = {name: {"max_difference": float(f"{np.abs(coarse[name] - fine[name]).max():.4g}"),
                       "std": float(f"{fine[name][window].std():.4g}")} for name in CHANNELS}
    result = {"case": "NREL 5MW torque law, 11.4 m/s, 100 s: OpenFAST at DT and DT/2",
              "provenance": {"openfast": {**OPENFAST, "executable": executable}, "deck": "cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst",
                             "steps_s": [float(s) for s in STEPS], "tmax_s": 100.0,
                             "script": "tests/data/openfast/make_step_error.py"},
              "channels": channels}
    (HERE / "step_error.json").write_text(json.dumps(result, indent=1) + "\n")


if __name__ == "__main__":
    main(*sys.argv[1:3])
