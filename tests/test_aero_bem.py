"""Blade-element momentum theory against closed forms: momentum-theory induction, the Betz limit, the momentum
balance at converged nodes, guaranteed convergence of the one-equation solve, and the numba/Python paths."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from bladefem.aero import BEMOptions, Polar, Rotor, pack_polars, rotor_performance
from bladefem.aero.bem import NODE_OUTPUTS, residual, solve_nodes
from bladefem.builders.openfast_fst import read_openfast_deck

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"
#: Momentum theory without loss, drag or wake rotation. Buhl's correction stays on (it only acts above a = 0.4): it
#: keeps the residual finite as phi -> 0+, which Ning's bracket [0+, pi/2] relies on.
IDEAL = BEMOptions(tip_loss=False, hub_loss=False, tangential_induction=False, skew_redistribution=False)


def thin_airfoil() -> Polar:
    """Uniform lift slope 2 pi per rad over the whole table, no drag, no moment."""
    alpha = np.linspace(-np.pi, np.pi, 721)
    return Polar(alpha, 2 * np.pi * alpha, np.zeros_like(alpha), np.zeros_like(alpha))


def designed_rotor(induction: float, tsr: float = 7.0, speed: float = 10.0, radius: float = 63.0,
                   hub: float = 0.063, nodes: int = 41) -> tuple[Rotor, float]:
    """A rotor twisted so that momentum theory gives the axial induction ``induction`` at every node: with
    tan phi = U (1 - a) / (Omega r) and a / (1 - a) = sigma' cl cos phi / (4 sin^2 phi) (no loss, drag or wake
    rotation) the lift coefficient, hence the angle of attack and the twist, follow in closed form."""
    omega = tsr * speed / radius
    r = np.linspace(hub, radius, nodes)
    chord = np.full(nodes, 2.0)
    phi = np.arctan2(speed * (1 - induction), omega * r)
    solidity = 3 * chord / (2 * np.pi * r)
    cl = 4 * np.sin(phi) ** 2 * induction / ((1 - induction) * solidity * np.cos(phi))
    twist = phi - cl / (2 * np.pi)
    rotor = Rotor(3, hub, r - hub, chord, twist, np.zeros(nodes, dtype=int), (thin_airfoil(),), hub_height=90.0,
                  options=IDEAL)
    return rotor, omega * 30 / np.pi


@pytest.mark.parametrize("induction", [0.05, 0.2, 1 / 3, 0.39])
def test_momentum_theory_induction(induction):
    """Uniform lift slope, no loss, no drag, no wake rotation: the BEM returns the momentum-theory induction the
    rotor was designed for, and the thrust per annulus is 4 pi r rho U^2 a (1 - a) exactly. Tolerance: the residual
    tolerance 5e-10 bounds the error in phi, and hence in a, to about 1e-9."""
    rotor, rpm = designed_rotor(induction)
    result = rotor_performance(rotor, 10.0, rpm, 0.0)
    assert np.allclose(result.a, induction, atol=1e-8, rtol=0)
    assert np.allclose(result.ap, 0.0)
    r = result.r_local[0, 0]
    annulus = 4 * np.pi * r * rotor.air_density * 10.0 ** 2 * induction * (1 - induction)
    assert np.allclose(3 * result.fn[0, 0], annulus, rtol=1e-8)


def test_betz_limit():
    """An ideal rotor (momentum theory, no loss, drag or wake rotation) has C_P = 4 a (1 - a)^2 (1 - (r_hub/R)^2):
    16/27 at a = 1/3 (the Betz limit) and less at any other induction. The trapezoidal sum is exact here (the torque
    per length is linear in r); the hub of R/1000 costs 1e-6 of the power."""
    cps = {}
    for a in (0.2, 0.3, 1 / 3, 0.36, 0.39):
        rotor, rpm = designed_rotor(a)
        cps[a] = rotor_performance(rotor, 10.0, rpm, 0.0).cp
        assert cps[a] == pytest.approx(4 * a * (1 - a) ** 2 * (1 - 1e-6), rel=1e-8)
    assert cps[1 / 3] == pytest.approx(16 / 27, abs=1e-6)
    assert max(cps, key=cps.get) == 1 / 3


@pytest.fixture(scope="module")
def deck():
    return read_openfast_deck(DECK)


def test_momentum_balance_at_converged_nodes(deck):
    """The solution satisfies both momentum balances of every annulus, written in the induction factors rather than
    in the inflow angle that was solved for: B q c cn = 4 pi r rho Vx^2 F a (1 - a) and B q c ct = 4 pi r^2 rho Vx
    Omega F a' (1 - a) (drag in both induction equations, so cn and ct are those of the loads), for the NREL 5MW
    polars with tip and hub loss, at the nodes in the momentum region (a < 0.4, Buhl's correction not active)."""
    from bladefem.aero.induction import loss_factor
    options = BEMOptions(axial_drag=True, tangential_drag=True, skew_redistribution=False)
    rotor = Rotor(**{**deck.rotor().__dict__, "options": options, "precone": 0.0, "shaft_tilt": 0.0, "curve": None,
                     "sweep": None})
    for speed, rpm in ((5.0, 7.506), (8.0, 9.156), (11.4, 12.1)):
        result = rotor_performance(rotor, speed, rpm, 0.0)
        omega, rho = rpm * math.pi / 30, rotor.air_density
        a, ap, r = result.a[0, 0], result.ap[0, 0], result.r_local[0, 0]
        inner = (a > 0.01) & (a < 0.4) & result.valid[0, 0]
        assert inner.sum() >= 8
        z = result.z[0, 0]
        tip_c = 3 * (z[-1] - z) / (2 * z)
        hub_c = 3 * (z - rotor.hub_radius) / (2 * rotor.hub_radius)
        opts = options.vector()
        loss = np.array([loss_factor(p, t, h, opts, 1.0) for p, t, h in zip(result.phi[0, 0], tip_c, hub_c)])
        thrust = 4 * np.pi * r * rho * speed ** 2 * loss * a * (1 - a)
        torque = 4 * np.pi * r ** 2 * rho * speed * omega * loss * ap * (1 - a)
        assert np.allclose(3 * result.fn[0, 0][inner], thrust[inner], rtol=1e-7)
        assert np.allclose(3 * result.ft[0, 0][inner], torque[inner], rtol=1e-7)


def test_guaranteed_convergence():
    """Ning's method finds a root wherever the BEM equations have one: 4000 random operating points (both signs of
    the inflow, tiny and large speed ratios, any twist, high solidity, loss on) all return either a valid angle
    with |R(phi)| below the tolerance (or a bracket of 1e-13 rad) or AeroDyn's fallback flagged invalid, never NaN;
    and a previous solution as guess (Brent's first trial in the momentum region) gives the same root: 1e-3 rad
    off, the same angle to 1e-9 rad at every node (this polar's stall leaves no node a second root near its own),
    the root itself kept exactly."""
    rng = np.random.default_rng(7)
    alpha = np.radians(np.linspace(-180, 180, 361))
    polar = Polar(alpha, 1.2 * np.sin(2 * alpha), 0.02 + 1.2 * np.sin(alpha) ** 2, -0.1 * np.sin(alpha))
    table = pack_polars([polar])
    options = BEMOptions(tolerance=1e-12).vector()
    n = 4000
    vx = rng.choice([-1, 1], n) * rng.uniform(0.01, 30, n)
    vy = rng.choice([-1, 1], n, p=[0.1, 0.9]) * rng.uniform(0.01, 100, n)
    r = rng.uniform(2, 60, n)
    chord = rng.uniform(0.5, 6, n)
    theta = rng.uniform(-0.5, 0.8, n)
    tip_c, hub_c = 3 * (63 - r) / (2 * r), 3 * (r - 1.5) / 3.0
    zeros, ones = np.zeros(n), np.ones(n)
    out = np.empty((n, NODE_OUTPUTS))
    args = (vx, vy, r, chord, theta, tip_c, hub_c, 3.0, r / 63, zeros, zeros, 1.0, np.zeros(n, dtype=np.int64),
            *table.arrays, options, 1.225)
    plane = (zeros, zeros, ones)
    solve_nodes(*args, np.full(n, np.nan), *plane, out)
    assert np.all(np.isfinite(out))
    valid = out[:, 12] > 0.5
    assert valid.mean() > 0.95
    for i in np.flatnonzero(valid & (np.abs(vx) > 1e-3) & (np.abs(vy) > 1e-3)):
        f = residual(out[i, 0], vx[i], vy[i], 3 * chord[i] / (2 * np.pi * r[i]), theta[i], tip_c[i], hub_c[i], 0.0,
                     0, *table.arrays, options, (0.0, 0.0, 1.0))
        assert abs(f[0]) < 1e-9 or not f[3], (i, f)
    warm = np.empty_like(out)
    solve_nodes(*args, out[:, 0] + 1e-3 * ones, *plane, warm)          # a previous solution that is no root any more
    np.testing.assert_allclose(warm[:, 0], out[:, 0], rtol=0, atol=1e-9)
    np.testing.assert_array_equal(warm[:, 12], out[:, 12])
    solve_nodes(*args, out[:, 0], *plane, warm)                          # the root itself
    np.testing.assert_array_equal(warm[valid, 0], out[valid, 0])


def test_pure_python_path_matches_compiled(deck):
    """Without numba (BLADEFEM_NO_NUMBA) the same kernels run as Python and give the same rotor loads to
    rounding."""
    code = ("import json; from bladefem.builders.openfast_fst import read_openfast_deck; "
            "from bladefem.aero import rotor_performance; from bladefem.aero._jit import COMPILED; "
            f"r = rotor_performance(read_openfast_deck({str(DECK)!r}), 11.4, 12.1, 0.0, azimuths=2); "
            "print(json.dumps([COMPILED, r.thrust, r.torque]))")
    env = {**os.environ, "BLADEFEM_NO_NUMBA": "1", "PYTHONPATH": str(ROOT)}
    compiled, thrust, torque = json.loads(subprocess.run([sys.executable, "-c", code], env=env, check=True,
                                                         capture_output=True, text=True).stdout)
    assert not compiled
    reference = rotor_performance(deck, 11.4, 12.1, 0.0, azimuths=2)
    assert thrust == pytest.approx(reference.thrust, rel=1e-12)
    assert torque == pytest.approx(reference.torque, rel=1e-12)


@pytest.mark.parametrize("formulation", [1, 2])
def test_first_trial_finds_the_same_root(deck, formulation):
    """Brent's method started at the Betz rotor's inflow angle (the solve's first trial without a guess) and
    from the bracket's ends alone find the same root of every NREL 5MW node, to the residual tolerance, from
    cut-in to cut-out at the pitch of the operating schedule, with the blade moving in and against the flow (vx
    and vy of +-20 %) and canted and toed sections (BEM_Mod 2); and so does the search next to a previous root
    1e-4 and 0.02 rad either side of it (a previous right-hand side's root: where a run's solve starts)."""
    from bladefem.aero.bem import (EDGE, PREDICTED_FACTOR, angle_geometry, brent, framed_residual, local_root,
                                   section_frame)
    rotor = deck.rotor()
    options = BEMOptions(formulation=formulation).vector()
    z = rotor.hub_radius + rotor.span
    tip_c, hub_c = 3 * (z[-1] - z) / (2 * z), 3 * (z - rotor.hub_radius) / (2 * rotor.hub_radius)
    table = pack_polars(rotor.polars).arrays
    checked = 0
    for speed, rpm, pitch in ((4.0, 7.2, 0.0), (8.0, 9.2, 0.0), (11.4, 12.1, 0.0), (16.0, 12.1, 12.06),
                              (25.0, 12.1, 23.47)):
        for scale_x, scale_y, cant, toe in ((1.0, 1.0, 0.0, 0.0), (1.2, 0.8, 0.05, -0.03), (0.8, 1.2, -0.04, 0.02)):
            for i in range(1, len(z) - 1):
                vx, vy = speed * scale_x, rpm * math.pi / 30 * z[i] * scale_y
                theta = rotor.twist[i] + math.radians(pitch)
                frame = section_frame(theta, 0.0, angle_geometry(cant, toe, 1.0) if formulation == 2
                                      else angle_geometry(0.0, 0.0, 1.0))
                args = (vx, vy, 3 * rotor.chord[i] / (2 * math.pi * z[i]), theta, tip_c[i], hub_c[i], 0.0,
                        int(rotor.airfoil[i]), *table, options, frame)
                lo, hi = EDGE, math.pi / 2 - EDGE
                f_lo, f_hi = framed_residual(lo, *args)[0], framed_residual(hi, *args)[0]
                first = math.atan2(vx * frame[0] * PREDICTED_FACTOR, vy)
                assert lo < first < hi
                if (f_lo > 0) == (f_hi > 0):
                    continue
                ends = brent(lo, hi, f_lo, f_hi, *args, math.nan)
                started = brent(lo, hi, f_lo, f_hi, *args, first)
                assert started[0] == pytest.approx(ends[0], abs=1e-8), (speed, i)
                assert abs(framed_residual(started[0], *args)[0]) <= 5e-10
                for step in (-0.02, -1e-4, 1e-4, 0.02):       # a previous solution next to the root
                    guess = min(max(ends[0] + step, 2 * EDGE), hi - EDGE)
                    warm = local_root(guess, lo, hi, 1.0, 5e-10, args)
                    assert warm[3] and warm[0] == pytest.approx(ends[0], abs=1e-8), (speed, i, step)
                    assert abs(framed_residual(warm[0], *args)[0]) <= 5e-10
                checked += 1
    assert checked >= 5 * 3 * 14
