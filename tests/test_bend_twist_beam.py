"""A bend-twist coupled cantilever against the exact solution in Banerjee's form (Int. J. Solids Struct. 38 (2001)
2415-2426, tests/bend_twist_exact.py), the sections given as a user gives them: a BeamDyn primary and blade file
with the flap-twist coupling K56 in the 6x6 stiffness, read by bladefem's readers into the FE.

The beam has the Goland wing's bending and torsion stiffness, mass and pitch inertia (Goland 1945; the wing of
cases/goland_wing, its centre of mass put on the axis) with a material coupling K = 0.6 sqrt(EI GJ), as a composite
box beam's ply angle makes it (the ratio below 1 for a positive-definite section); the edgewise stiffness is
100 EI, EA and the shear stiffnesses 1e4 EI / L^2, so that the edge, axial and shear motions stay out of the way.
The paper's own numerical table is not reproduced here: its frequency equation is solved for this beam, and a
second exact solution (tests/uniform_beam_exact.py) checks that solution.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from bend_twist_exact import CoupledBeam, natural_frequencies
from uniform_beam_exact import natural_frequencies as general_frequencies
from uniform_beam_exact import timoshenko_frequencies

from bladefem.builders.beamdyn import blade_from_beamdyn
from bladefem.cli import main
from bladefem.formats.beamdyn import (
    BeamDynBlade,
    read_beamdyn_blade,
    read_beamdyn_primary,
    write_beamdyn_blade,
    write_beamdyn_primary,
)
from bladefem.modal import modes

TEMPLATE = Path(__file__).resolve().parent / "data" / "nrel5mw_beamdyn" / "bd_primary_nrel_5mw.inp"
EI, GJ, MASS, I_A, L = 9.77e6, 0.987e6, 35.71, 8.64, 6.096
RATIO = 0.6
BEAM = CoupledBeam(EI, GJ, RATIO * np.sqrt(EI * GJ), MASS, I_A, L)
#: flap 1, torsion 1, flap 2, the coupled pair, rad/s (measured: 37.198, 90.090, 186.771, 298.695, 397.791)
COUNT, UPPER = 5, 450.0


def beamdyn_files(folder: Path, sign: float = 1.0) -> Path:
    """The uniform coupled beam as a BeamDyn primary (straight key points along z, no twist) and blade file in
    BeamDyn's axes: rows (shear x, shear y, extension, bending about x = edgewise, about y = flapwise, torsion)."""
    stiffness = np.diag([1e4 * EI / L**2, 1e4 * EI / L**2, 1e4 * EI / L**2, 100 * EI, EI, GJ])
    stiffness[4, 5] = stiffness[5, 4] = sign * BEAM.K
    mass = np.diag([MASS, MASS, MASS, 0.0, 0.0, I_A])
    blade = BeamDynBlade(title="bend-twist coupled beam", eta=np.array([0.0, 1.0]),
                         stiffness=np.array([stiffness, stiffness]), mass=np.array([mass, mass]))
    write_beamdyn_blade(blade, folder / "coupled_blade.dat")
    template = read_beamdyn_primary(TEMPLATE)
    settings = tuple((key, '"coupled_blade.dat"' if key.lower() == "bldfile" else value)
                     for key, value in template.settings_after)
    primary = replace(template, title="bend-twist coupled beam", members=(3,), settings_after=settings,
                      key_points=np.array([[0.0, 0.0, 0.0, 0.0], [0.0, 0.0, L / 2, 0.0], [0.0, 0.0, L, 0.0]]))
    path = folder / "coupled_primary.dat"
    write_beamdyn_primary(primary, path)
    return path


def test_the_two_exact_solutions_agree():
    """Banerjee's real 6x6 frequency determinant and the general 12x12 solution of tests/uniform_beam_exact.py
    (the same beam as a bladefem-ordered 6x6 section) give the same frequencies to 1e-12; without coupling they
    are the cantilever's 1.8751^2 sqrt(EI / m) / L^2 and the rod's pi / 2 sqrt(GJ / I_a) / L."""
    exact = natural_frequencies(BEAM, COUNT, UPPER)
    K = np.diag([1e12, 1e12, 1e12, GJ, EI, 1e3 * EI])
    K[3, 4] = K[4, 3] = BEAM.K
    general = general_frequencies(K, np.diag([MASS, MASS, MASS, I_A, 0.0, 0.0]), L, COUNT, UPPER, samples=1500)
    assert exact == pytest.approx(general, rel=1e-12)
    plain = natural_frequencies(replace(BEAM, K=1e-6 * BEAM.K), 2, 100.0)
    assert plain == pytest.approx([1.8751040687119611**2 * np.sqrt(EI / MASS) / L**2,
                                   np.pi / 2 * np.sqrt(GJ / I_A) / L], rel=1e-9)
    assert exact[0] < 0.8 * plain[0]                    # the coupling lowers flap 1 by a quarter


@pytest.mark.parametrize("sections", ["condensed", "full"])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_beamdyn_coupled_beam_against_the_exact_solution(tmp_path, sections, sign):
    """The FE from the BeamDyn files converges as h^4 from 20 elements and is within 1e-6 at 40 (measured 7.1e-7,
    the fifth frequency): with the shear condensed to Banerjee's Euler-Bernoulli beam, with the shear kept to the
    exact Timoshenko beam of the same 6x6 section (tests/uniform_beam_exact.py; the shear, 3 EI / (k GA L^2) = 3e-4
    of the static flexibility, lowers these five by 1.1e-4 to 8.8e-4). The coupling's sign does not change the
    frequencies (K enters as K^2)."""
    primary = read_beamdyn_primary(beamdyn_files(tmp_path, sign))
    blade = blade_from_beamdyn(primary, read_beamdyn_blade(primary.blade_path()), sections=sections)
    if sections == "condensed":
        exact = natural_frequencies(BEAM, COUNT, UPPER)
    else:
        shear = 1e4 * EI / L**2
        K = np.diag([shear, shear, shear, GJ, EI, 100 * EI])
        K[3, 4] = K[4, 3] = BEAM.K
        exact = timoshenko_frequencies(K, np.diag([MASS, MASS, MASS, I_A, 0.0, 0.0]), L, COUNT, UPPER)
        assert np.all((exact / natural_frequencies(BEAM, COUNT, UPPER) - 1) < -1e-4)

    def fe(elements: int) -> np.ndarray:
        result = modes(blade, 0.0, COUNT + 3, elements=elements)
        kept = [2 * np.pi * m.frequency_hz for m in result.modes if m.kind in ("flap", "torsion")]
        return np.array(kept[:COUNT])

    coarse, fine = (np.abs(fe(n) / exact - 1) for n in (20, 40))
    assert np.log2(coarse / fine) == pytest.approx(np.full(COUNT, 4.0), abs=0.2)
    assert np.max(fine) < 1e-6


def test_the_command_line_reads_the_coupled_beam(tmp_path, capsys):
    """``bladefem modes PRIMARY --sections condensed``: the automatic mesh's frequencies within 2e-6 of the
    exact ones (its tolerance 1e-6), the first mode a coupled flap-torsion one."""
    path = beamdyn_files(tmp_path)
    code = main(["modes", str(path), "--sections", "condensed", "--n-modes", "8", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    kept = [2 * np.pi * m["frequency_hz"] for m in data["modes"] if m["kind"] in ("flap", "torsion")][:COUNT]
    assert np.array(kept) == pytest.approx(natural_frequencies(BEAM, COUNT, UPPER), rel=2e-6)
