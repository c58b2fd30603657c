"""The ElastoDyn coefficients in their real client: OpenFAST v5.0.0 with ElastoDyn blades, linearized parked and at
rated speed, for the coefficients the IEA-15MW and IEA-22MW repositories ship and for those ``bladefem elastodyn
--write`` fits to their BeamDyn blades, against BeamDyn's own blade frequencies (OpenFAST v5.0.0, hub held, gravity
off). ``python examples/elastodyn_openfast.py`` prints the tables of docs/elastodyn-openfast.md from the stored runs
(tests/data/openfast/elastodyn_client/ and tests/data/openfast/beamdyn/) and bladefem's prediction of each ElastoDyn
run from its coupled blade equations.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from bladefem.builders.detect import Geometry, read_model
from bladefem.modal.elastodyn_integrals import elastodyn_coupled_frequencies
from bladefem.sections.principal import elastodyn_sections

DATA = Path(__file__).resolve().parent.parent / "tests" / "data"
CLIENT = json.loads((DATA / "openfast/elastodyn_client/linearizations.json").read_text())
BEAMDYN = json.loads((DATA / "openfast/beamdyn/linearizations.json").read_text())
MAINS = {"iea15": DATA / "iea15/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn.dat",
         "iea22": DATA / "iea22/IEA-22-280-RWT-Monopile/IEA-22-280-RWT_ElastoDyn.dat"}
NAMES = {"iea15": "IEA-15MW", "iea22": "IEA-22MW"}
SETS = {"shipped": "ElastoDyn, coefficients as shipped", "bladefem": "ElastoDyn, bladefem's fit",
        "compatible": "ElastoDyn, bladefem's fit, --elastodyn-compatible"}
MODES = ("flap1", "edge1", "flap2")


def predicted(run: dict) -> dict[str, float]:
    """bladefem's ElastoDyn frequencies (Hz) for a stored run: its blade file's sections, the run's coefficients,
    rotor speed, no cone (as the runs)."""
    blade = read_model(str(MAINS[run["turbine"]]), "blade", Geometry())
    coefficients = {name: np.array(values) for name, values in run["coefficient_values"].items()}
    return elastodyn_coupled_frequencies(coefficients, elastodyn_sections(blade.sections), 50, tip_mass=0.0,
                                         omega=run["rpm"] * math.pi / 30, hub_radius=blade.hub_radius,
                                         precone=0.0, twist_pitch=blade.pitch)


def beamdyn(turbine: str, rpm: float, axis: str) -> list[float]:
    """BeamDyn's flap 1, edge 1, flap 2 (Hz: its three lowest) at the finest element order stored."""
    runs = [r for r in BEAMDYN["runs"] if r["turbine"] == turbine and abs(r["rpm"] - rpm) < 0.05
            and r["reference_axis"] == axis]
    return sorted(max(runs, key=lambda r: r["order_elem"])["frequencies_hz"])[:3]


def table(turbine: str) -> list[str]:
    rated = max(r["rpm"] for r in CLIENT["runs"] if r["turbine"] == turbine)
    head = ["| model | " + " | ".join(f"{m} {rpm:g} rpm" for rpm in (0, rated) for m in MODES) + " |",
            "|---|" + "---|" * 6]
    straight = beamdyn(turbine, 0, "straight") + beamdyn(turbine, rated, "straight")
    rows = []
    for axis in ("prebent", "straight"):
        values = beamdyn(turbine, 0, axis) + beamdyn(turbine, rated, axis)
        rows.append(f"| BeamDyn, {axis} | " + " | ".join(f"{v:.4f}" for v in values) + " |")
    for name, label in SETS.items():
        runs = [next(r for r in CLIENT["runs"] if (r["turbine"], r["coefficients"], r["rpm"]) == (turbine, name, rpm))
                for rpm in (0, rated)]
        values = [f for run in runs for f in run["frequencies_hz"][:3]]
        cells = [f"{v:.4f} ({100 * (v / s - 1):+.1f} %)" for v, s in zip(values, straight)]
        rows.append(f"| {label} | " + " | ".join(cells) + " |")
    return [f"{NAMES[turbine]} (Hz; in brackets against BeamDyn's straight blade):", ""] + head + rows


def prediction_lines() -> list[str]:
    worst = 0.0
    for run in CLIENT["runs"]:
        ours = predicted(run)
        for name, theirs in zip(MODES, run["frequencies_hz"]):
            worst = max(worst, abs(ours[name] / theirs - 1))
    return [f"bladefem's prediction of the {len(CLIENT['runs'])} ElastoDyn runs from its coupled blade equations: "
            f"largest difference {100 * worst:.4f} %."]


def main() -> str:
    return "\n".join(table("iea15") + [""] + table("iea22") + [""] + prediction_lines())


if __name__ == "__main__":
    print(main())
