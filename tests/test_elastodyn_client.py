"""The real client of the ElastoDyn coefficients: OpenFAST v5.0.0 with ElastoDyn blades, linearized parked and at
rated speed (tests/data/openfast/elastodyn_client/, made by its make_decks.py), against bladefem's prediction of
ElastoDyn's coupled blade equations (:func:`bladefem.modal.elastodyn_integrals.elastodyn_coupled_frequencies`), for
the coefficients the IEA repositories ship and for those ``bladefem elastodyn --write`` fits to the BeamDyn blades.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.detect import Geometry, read_model
from bladefem.modal.elastodyn_integrals import elastodyn_coupled_frequencies, elastodyn_frequency
from bladefem.sections.principal import elastodyn_sections

DATA = Path(__file__).parent / "data"
RUNS = json.loads((DATA / "openfast/elastodyn_client/linearizations.json").read_text())
MAINS = {"iea15": DATA / "iea15/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn.dat",
         "iea22": DATA / "iea22/IEA-22-280-RWT-Monopile/IEA-22-280-RWT_ElastoDyn.dat"}
#: OpenFAST linearizes by finite differences and prints the A matrix to 7 significant digits, and the stored
#: frequencies have 6 decimals: 1e-4 covers both, far below the couplings checked (0.4 % to 4 %)
TOLERANCE = 1e-4


def predicted(run: dict) -> dict[str, float]:
    blade = read_model(str(MAINS[run["turbine"]]), "blade", Geometry())
    coefficients = {name: np.array(values) for name, values in run["coefficient_values"].items()}
    return elastodyn_coupled_frequencies(
        coefficients, elastodyn_sections(blade.sections), 50, tip_mass=0.0, omega=run["rpm"] * math.pi / 30,
        hub_radius=blade.hub_radius, precone=0.0, twist_pitch=blade.pitch)     # the runs have no cone


@pytest.mark.parametrize("run", RUNS["runs"], ids=lambda r: f"{r['turbine']}-{r['coefficients']}-{r['rpm']:g}rpm")
def test_elastodyn_coupled_blade_frequencies_are_openfasts(run):
    flap1, edge1, flap2 = run["frequencies_hz"][:3]
    ours = predicted(run)
    for name, theirs in (("flap1", flap1), ("edge1", edge1), ("flap2", flap2)):
        assert ours[name] == pytest.approx(theirs, rel=TOLERANCE), name


def test_each_mode_alone_misses_the_coupling_openfast_sees():
    """The per-mode frequency (what ElastoDyn prints as FreqBF) is not what its equations give together: on the
    IEA-15MW with bladefem's coefficients the second flap mode moves by more than 1 % when coupled."""
    run = next(r for r in RUNS["runs"] if (r["turbine"], r["coefficients"], r["rpm"]) == ("iea15", "bladefem", 0))
    blade = read_model(str(MAINS["iea15"]), "blade", Geometry())
    alone = elastodyn_frequency(np.array(run["coefficient_values"]["flap2"]), elastodyn_sections(blade.sections),
                                "flap_stiffness", 50, twist_pitch=blade.pitch)
    assert abs(run["frequencies_hz"][2] / alone - 1) > 0.01
    assert predicted(run)["flap2"] == pytest.approx(run["frequencies_hz"][2], rel=TOLERANCE)
