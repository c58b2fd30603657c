"""The ElastoDyn deck is honoured: DOF switches set the free coordinates, initial conditions the initial state as
ElastoDyn's InitBlDefl and Init_ContStates do (tip and tower-top deflections in m, azimuth relative to AzimB1Up,
NacYaw, RotSpeed), unmodelled motions and unequal blade pitches are refused."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.errors import InputError
from bladefem.formats.elastodyn_main import read_elastodyn_main, write_elastodyn_main
from bladefem.builders.turbine_elastodyn import deck_conditions, turbine_from_elastodyn
from bladefem.models.turbine import TurbineModel, select_dofs
from bladefem.models.turbine.initial import (
    InitialConditions,
    free_from_switches,
    initial_state,
)

MAIN = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


@pytest.fixture(scope="module")
def model() -> TurbineModel:
    return TurbineModel(turbine_from_elastodyn(MAIN, "polynomial", elastodyn_compatible=True))


def deck(tmp_path: Path, **changes: object) -> Path:
    """A copy of the NREL 5MW main file with some entries changed (attributes of ElastoDynMain)."""
    main = read_elastodyn_main(MAIN)
    path = tmp_path / "main.dat"
    write_elastodyn_main(replace(main, **changes), path)
    return path


def tip(model: TurbineModel, q: np.ndarray, blade: int) -> np.ndarray:
    """(out-of-plane downwind, in-plane toward the trailing edge) tip deflection of a blade, m."""
    value = q[model.blade_columns[blade]] @ model.params.blade.tip_value
    return np.array([value[1], -value[0]])


def test_switches_set_the_free_coordinates(model):
    switches = {"GenDOF": False, "FlapDOF2": False, "TwSSDOF2": False, "TeetDOF": False}
    free = free_from_switches(model.dofs, switches)
    locked = {dof for dof, is_free in zip(model.dofs, free) if not is_free}
    assert locked == {"generator_azimuth", "tower_ss2", "blade1_flap2", "blade2_flap2", "blade3_flap2"}
    # the command line changes the deck's set (NAME=off / on) or replaces it (plain names)
    changed = select_dofs(model.dofs, ["GenDOF=on", "yaw=off"], base=free)
    assert changed[model.dofs.index("generator_azimuth")] and not changed[model.dofs.index("yaw")]
    assert select_dofs(model.dofs, ["TwFADOF1", "edge1"], base=free).sum() == 4


@pytest.mark.parametrize("switch", ["PtfmPDOF", "PtfmSgDOF"])
def test_unmodelled_motions_are_refused(model, switch):
    with pytest.raises(InputError) as error:
        free_from_switches(model.dofs, {switch: True})
    assert error.value.field == switch


def test_teeter_switch_is_ignored_for_three_blades(model):
    assert free_from_switches(model.dofs, {"TeetDOF": True}).all()


def test_tip_deflections_become_modal_amplitudes_as_in_elastodyn(model):
    free = np.ones(model.n, dtype=bool)
    q, u, notes = initial_state(model, free, InitialConditions(oop_deflection=2.5, ip_deflection=-0.4))
    for blade in range(3):
        np.testing.assert_allclose(tip(model, q, blade), [2.5, -0.4], rtol=1e-12)
        assert q[model.blade_columns[blade, 2]] == 0.0                 # flap 2 is not used while flap 1 is free
    assert notes == () and not u.any()
    # flap 1 locked: flap 2 carries the out-of-plane deflection (InitBlDefl's second branch)
    free[model.blade_columns[:, 0]] = False
    q, _, _ = initial_state(model, free, InitialConditions(oop_deflection=2.5, ip_deflection=-0.4))
    np.testing.assert_allclose(tip(model, q, 0), [2.5, -0.4], rtol=1e-12)
    assert q[model.blade_columns[0, 0]] == 0.0
    # no edge mode: the two deflections cannot both be met; a least-squares amplitude and a note
    free[model.blade_columns[:, 1]] = False
    q, _, notes = initial_state(model, free, InitialConditions(oop_deflection=2.5, ip_deflection=-0.4))
    assert notes and "approximately" in notes[0]
    assert tip(model, q, 0)[0] == pytest.approx(2.5, rel=0.05)


def test_tower_top_yaw_azimuth_and_speed(model):
    conditions = InitialConditions(tower_top_fa=0.3, tower_top_ss=-0.2, nacelle_yaw=0.1, azimuth=0.5,
                                   rotor_speed=1.2)
    q, u, _ = initial_state(model, np.ones(model.n, dtype=bool), conditions)
    motion = model.motion(q, u)
    top = motion.tower_top.r - np.array([0.0, 0.0, model.params.tower_height])
    # TTDspFA downwind (x), TTDspSS to the left looking downwind (y); the vertical drop is second order
    np.testing.assert_allclose(top[:2], [0.3, -0.2], rtol=1e-12)
    assert q[model.dofs.index("yaw")] == 0.1 and q[model.dofs.index("generator_azimuth")] == 0.5
    assert u[model.dofs.index("generator_azimuth")] == 1.2 and np.count_nonzero(u) == 1
    # only the second fore-aft mode free: it carries TTDspFA (Init_ContStates)
    free = select_dofs(model.dofs, ["tower_fa2", "tower_ss1"])
    q, _, _ = initial_state(model, free, conditions)
    assert q[0] == 0.0 and q[1] * model.params.tower.tip_value[1, 0] == pytest.approx(0.3, rel=1e-12)


def test_deck_initial_conditions_are_read(tmp_path, model):
    path = deck(tmp_path, oop_deflection=1.5, ip_deflection=0.25, azimuth=math.radians(40.0),
                azimuth_blade1_up=math.radians(10.0), nacelle_yaw=math.radians(5.0), tower_top_fa=0.1,
                dofs={**read_elastodyn_main(MAIN).dofs, "GenDOF": False})
    switches, conditions = deck_conditions(path)
    assert switches["GenDOF"] is False
    assert conditions.azimuth == pytest.approx(math.radians(30.0), rel=1e-12)     # Azimuth - AzimB1Up
    assert conditions.nacelle_yaw == pytest.approx(math.radians(5.0), rel=1e-12)
    assert conditions.rotor_speed == pytest.approx(12.1 * math.pi / 30, rel=1e-12)
    assert (conditions.oop_deflection, conditions.ip_deflection, conditions.tower_top_fa) == (1.5, 0.25, 0.1)
    q = initial_state(model, free_from_switches(model.dofs, switches), conditions)[0]
    np.testing.assert_allclose(tip(model, q, 2), [1.5, 0.25], rtol=1e-12)


def test_unequal_blade_pitches_are_refused(tmp_path):
    path = deck(tmp_path, blade_pitch=(0.0, 0.1, 0.0))
    with pytest.raises(InputError) as error:
        turbine_from_elastodyn(path, "polynomial")
    assert error.value.field == "BlPitch(2)" and error.value.line is not None


def test_deck_pitch_turns_the_blade_shapes(tmp_path):
    """BlPitch of the deck is the pitch of the model: the same as asking for it."""
    pitched = turbine_from_elastodyn(deck(tmp_path, blade_pitch=(0.2, 0.2, 0.2)), "polynomial",
                                     elastodyn_compatible=True)
    asked = turbine_from_elastodyn(MAIN, "polynomial", pitch=0.2, elastodyn_compatible=True)
    plain = turbine_from_elastodyn(MAIN, "polynomial", elastodyn_compatible=True)
    np.testing.assert_array_equal(pitched.blade.tip_value, asked.blade.tip_value)
    assert not np.allclose(pitched.blade.tip_value, plain.blade.tip_value)
