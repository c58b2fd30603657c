"""Rigid-rotor kinematics and the skewed-wake model: cone, tilt, yaw and shear as the BEM nodes see them."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bladefem.aero import BEMOptions, Inflow, Rotor, rotor_performance
from bladefem.aero.kinematics import rigid_rotor
from bladefem.aero.options import PITT_PETERS_FACTOR
from bladefem.builders.openfast_fst import read_openfast_deck

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def rotor():
    deck = read_openfast_deck(ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst")
    return Rotor(**{**deck.rotor().__dict__, "curve": None, "sweep": None})


def variant(rotor, **changes):
    return Rotor(**{**rotor.__dict__, **changes})


def test_cone_and_tilt_geometry(rotor):
    """r_local = (HubRad + BlSpn) cos(precone); with shaft tilt and level wind the skew angle is the tilt and the
    disk-averaged axial wind U cos(tilt). Legacy projection (BEM_Mod 1): blade up (azimuth 0): vy = Omega r_local,
    vx = U cos(precone - tilt); blade level (azimuth 90 deg, moving down): vy = Omega r_local - U sin(tilt),
    vx = U cos(precone) cos(tilt); the section plane (no cant, no toe, dr/dz 1). Polar projection (BEM_Mod 2) of a
    blade without aerodynamic-centre offsets: vx = U cos(tilt) along the shaft at every azimuth, the same vy, the
    cant the precone, no toe and dr/dz = cos(precone)."""
    inflow = Inflow(10.0, 90.0)
    plain = variant(rotor, curve=None, sweep=None, options=BEMOptions(formulation=2))
    polar = rigid_rotor(plain, inflow, 1.2, np.radians([0.0, 90.0]))
    assert np.allclose(polar.vx, 10.0 * math.cos(rotor.shaft_tilt), rtol=1e-13)
    assert np.allclose(polar.cant, rotor.precone, rtol=1e-13)
    assert np.allclose(polar.toe, 0.0, atol=1e-13)
    assert np.allclose(polar.drdz, math.cos(rotor.precone), rtol=1e-13)
    assert np.allclose(polar.vy[0, 0], 1.2 * polar.r_local[0, 0], rtol=1e-13)
    assert np.allclose(polar.vy[1, 0], 1.2 * polar.r_local[1, 0] - 10.0 * math.sin(rotor.shaft_tilt), rtol=1e-13)
    rotor = variant(rotor, options=BEMOptions(formulation=1))
    kin = rigid_rotor(rotor, inflow, 1.2, np.radians([0.0, 90.0]))
    assert np.all(kin.cant == 0) and np.all(kin.toe == 0) and np.all(kin.drdz == 1)
    along = rotor.hub_radius + rotor.span
    assert np.allclose(kin.r_local, along * math.cos(rotor.precone), rtol=1e-13)
    assert np.allclose(kin.chi0, abs(rotor.shaft_tilt), atol=1e-13)
    assert np.allclose(kin.disk_velocity, 10.0 * math.cos(rotor.shaft_tilt), rtol=1e-13)
    cone, tilt = rotor.precone, rotor.shaft_tilt
    assert np.allclose(kin.vy[0, 0], 1.2 * kin.r_local[0, 0], rtol=1e-13)
    assert np.allclose(kin.vx[0, 0], 10.0 * math.cos(cone - tilt), rtol=1e-13)
    assert np.allclose(kin.vy[1, 0], 1.2 * kin.r_local[1, 0] - 10.0 * math.sin(tilt), rtol=1e-13)
    assert np.allclose(kin.vx[1, 0], 10.0 * math.cos(tilt) * math.cos(cone), rtol=1e-13)


def test_power_law_shear_at_the_nodes(rotor):
    """vx at every node of an untilted, unconed rotor is the power-law wind at the node's height."""
    flat = variant(rotor, precone=0.0, shaft_tilt=0.0)
    kin = rigid_rotor(flat, Inflow(10.0, 90.0, 0.2), 1.2, np.radians([0.0, 37.0]))
    height = flat.hub_height + kin.position[..., 2]
    assert np.allclose(kin.vx, 10.0 * (height / 90.0) ** 0.2, rtol=1e-13)


def test_skewed_wake_redistribution(rotor):
    """Yawed rotor: the axial induction with the Glauert/Pitt-Peters model is a0 (1 + 15 pi/32 tan(chi/2) r/R cos psi)
    with chi = (1 + 0.6 a0) chi0 and psi measured from the most downwind azimuth, which for a rotor yawed by +20 deg
    is blade 1 at 90 deg (pointing to -y); a0 the induction of the same solve without the model. The legacy
    formulation (BEM_Mod 1) has no loss factor in it."""
    yawed = variant(rotor, precone=0.0, shaft_tilt=0.0, options=BEMOptions(formulation=1))
    plain = variant(yawed, options=BEMOptions(formulation=1, skew_redistribution=False))
    on = rotor_performance(yawed, 11.4, 12.1, 0.0, yaw_deg=20.0, azimuths=16)
    off = rotor_performance(plain, 11.4, 12.1, 0.0, yaw_deg=20.0, azimuths=16)
    a0 = off.a
    psi = on.azimuths[:, None] + 2 * np.pi * np.arange(3) / 3
    cos_psi = np.sin(psi)[..., None]                       # cos(psi - 90 deg)
    ratio = on.r_local / on.r_local.max(axis=-1, keepdims=True)
    chi = (1 + 0.6 * a0) * math.radians(20.0)
    expected = a0 * (1 + PITT_PETERS_FACTOR * np.tan(chi / 2) * ratio * cos_psi)
    inner = slice(1, -1)                                   # the end nodes have no flow through them: a = 1
    assert np.allclose(on.a[..., inner], expected[..., inner], atol=1e-12)
    assert on.thrust == pytest.approx(off.thrust, rel=2e-3)      # the redistribution averages out to first order


def test_yaw_either_way_gives_the_same_mean_loads(rotor):
    """Without tilt or shear a yaw of +gamma and -gamma are the same flow seen half a turn later."""
    flat = variant(rotor, shaft_tilt=0.0)
    plus = rotor_performance(flat, 11.4, 12.1, 0.0, yaw_deg=15.0, azimuths=16)
    minus = rotor_performance(flat, 11.4, 12.1, 0.0, yaw_deg=-15.0, azimuths=16)
    assert plus.thrust == pytest.approx(minus.thrust, rel=1e-12)
    assert plus.torque == pytest.approx(minus.torque, rel=1e-12)


def test_power_and_coefficients(rotor):
    result = rotor_performance(rotor, 8.0, 9.156, 0.0)
    assert result.power == pytest.approx(result.torque * 9.156 * math.pi / 30, rel=1e-14)
    q = 0.5 * rotor.air_density * result.area * result.disk_velocity ** 2
    assert result.ct == pytest.approx(result.thrust / q, rel=1e-14)
    assert result.cp == pytest.approx(result.power / (q * result.disk_velocity), rel=1e-14)
    assert result.area == pytest.approx(math.pi * (63 * math.cos(math.radians(2.5)) - 1e-4) ** 2, rel=1e-6)
    assert 0.45 < result.cp < 0.5 and result.valid.all()


def test_line_load_resultant_is_exact_for_linear_loads():
    """The moment of a load varying linearly between nodes along a polyline equals the integral computed on a fine
    subdivision (error of the fine trapezoid ~ (h/L)^2 = 1e-8); the force is the trapezoid; distributed moments add."""
    from bladefem.aero.performance import line_load_resultant
    rng = np.random.default_rng(11)
    position = np.cumsum(rng.uniform(0.5, 2.0, (6, 3)), axis=0)
    force, moment = rng.normal(size=(6, 3)), rng.normal(size=(6, 3))
    z = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(position, axis=0), axis=1))]
    total_force, total_moment = line_load_resultant(position, force, moment, z)
    fine = np.linspace(0, z[-1], 200001)
    p = np.column_stack([np.interp(fine, z, position[:, i]) for i in range(3)])
    f = np.column_stack([np.interp(fine, z, force[:, i]) for i in range(3)])
    m = np.column_stack([np.interp(fine, z, moment[:, i]) for i in range(3)])
    assert np.allclose(total_force, np.trapezoid(f, fine, axis=0), rtol=1e-12)
    assert np.allclose(total_moment, np.trapezoid(np.cross(p, f) + m, fine, axis=0), rtol=1e-8, atol=1e-8)


def test_pitching_moment_counts_through_the_cone(rotor):
    """The rotor torque contains the blades' pitching moments times sin(precone) (AeroDyn's hub moment): switching
    UseBlCm off changes the torque by exactly that."""
    with_cm = rotor_performance(rotor, 11.4, 12.1, 0.0, azimuths=1)
    without = rotor_performance(variant(rotor, options=BEMOptions(**{**rotor.options.__dict__,
                                                                      "pitching_moment": False})), 11.4, 12.1, 0.0,
                                azimuths=1)
    expected = np.trapezoid(with_cm.m[0], with_cm.z[0], axis=-1).sum() * math.sin(rotor.precone)
    assert with_cm.torque - without.torque == pytest.approx(expected, rel=1e-9)
    assert with_cm.thrust == without.thrust and abs(expected) > 1e-3 * with_cm.torque
