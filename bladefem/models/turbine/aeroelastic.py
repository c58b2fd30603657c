"""Aeroelastic linearization of the turbine about a steady operating point: the structure's Jacobians with the
aerodynamic stiffness and damping of the BEM linearized there, multi-blade coordinates, azimuth averaging, named
modes with frequency and damping ratio.

At each of the operating point's azimuths (:mod:`.operating_point`) the state matrix of the free coordinates is

    A = [[0, I], [M^-1 (df/dq + dQ/dq), M^-1 (df/du + dQ/du)]]

with ``M`` the mass matrix there, ``f`` Kane's forcing of the structure (and the generator torque law when the
generator is free) and ``Q`` the aerodynamic generalized forces: with a frozen wake (the induced velocities held
at their operating-point values at that azimuth, OpenFAST's linearization, :mod:`.frozen_wake`) or with
quasi-steady induction (the BEM re-solved for every perturbation). The mass matrix is frozen at the operating
point, the convention of :func:`~bladefem.models.turbine.linearize.linearize` (exact at an equilibrium; here the
azimuth-averaged one). With three alike blades all free alike the state matrices go to multi-blade coordinates and
are averaged over the azimuths (one blade passage, where the transformed matrix repeats), otherwise the rotor is
linearized in blade coordinates at azimuth 0. A parked rotor is linearized at the azimuth it stands at, its blades
named in multi-blade coordinates there (a constant change of basis), as
:func:`~bladefem.models.turbine.linearize.linearize` does.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .aero import TurbineAero
from .control import Generator
from .frozen_wake import SectionAero, aero_jacobians, held_induction
from .kane import TurbineModel
from .linearize import LinearMode, forcing_jacobians, mbc_state_matrix, mbc_transform, modes_of
from .operating_point import OperatingPoint
from .system import FreeSystem

#: induction treatments of the linearization
INDUCTIONS = ("frozen", "quasi-steady")


@dataclass(frozen=True)
class AeroelasticModel:
    """The linear model at one operating point.

    point : the operating point; induction : 'frozen' or 'quasi-steady'
    A : state matrix (azimuth-averaged multi-blade coordinates, or blade coordinates at azimuth 0)
    coordinates : names of its coordinates; averaged : whether it is the multi-blade average
    modes : named modes by frequency; rigid : rigid-body motions left out of them
    deflections : the operating point's static deflections (:meth:`OperatingPoint.deflections`)
    """

    point: OperatingPoint
    induction: str
    A: NDArray
    coordinates: list[str]
    averaged: bool
    modes: list[LinearMode]
    rigid: list[str]
    deflections: dict[str, float]

    @property
    def rpm(self) -> float:
        return self.point.rpm

    def as_dict(self) -> dict:
        """``{"wind_speed_m_s", "rpm", "pitch_deg", "modes": [{"name", "frequency_hz", "damping_ratio",
        "participation"}], ...}`` with the operating point's rotor loads and static deflections."""
        point = self.point
        return {"wind_speed_m_s": point.wind_speed, "rpm": point.rpm, "pitch_deg": point.pitch_deg,
                "induction": self.induction, "rotor_speed_trimmed": point.trimmed,
                "operating_point": {"thrust_N": point.thrust, "torque_N_m": point.torque, "power_W": point.power,
                                    "generator_torque_N_m": point.generator_torque, **self.deflections},
                "modes": [mode.as_dict() for mode in self.modes]}


def structural_forcing(structure: TurbineModel, generator: Generator | None) -> Callable[[NDArray, NDArray], NDArray]:
    """``f(q, u)`` of the structure (compiled when numba is there) plus the generator torque law."""
    equations = structure.fast_equations()
    gen = structure.dofs.index("generator_azimuth")
    ratio = structure.params.gearbox_ratio

    def forcing(q: NDArray, u: NDArray) -> NDArray:
        f = equations(q, u)[1]
        if generator is not None:
            f = f.copy()
            f[gen] -= ratio * generator.torque(ratio * u[gen])
        return f
    return forcing


def state_matrix_at(structure: TurbineModel, aero: TurbineAero | None, generator: Generator | None,
                    free: NDArray, q: NDArray, u: NDArray, induction: str = "frozen",
                    sections: SectionAero | None = None) -> tuple[NDArray, NDArray]:
    """The state matrix of the free coordinates at (q, u) (states (q_f, u_f)) and the mass matrix M_ff;
    ``sections`` (:class:`~bladefem.models.turbine.frozen_wake.SectionAero` of ``aero``) saves preparing it."""
    system = FreeSystem(structure, free, q, u)
    M, dq, du = forcing_jacobians(system, q, u, forcing=structural_forcing(structure, generator))
    ix = system.index
    if aero is not None:
        held = held_induction(structure, aero, q, u) if induction == "frozen" else None
        aero_q, aero_u = aero_jacobians(structure, aero, q, u, ix, held, sections)
        dq, du = dq + aero_q[ix], du + aero_u[ix]
    m = system.size
    A = np.zeros((2 * m, 2 * m))
    A[:m, m:] = np.eye(m)
    A[m:, :m] = np.linalg.solve(M, dq)
    A[m:, m:] = np.linalg.solve(M, du)
    return A, M


def linearize_at(structure: TurbineModel, aero: TurbineAero | None, point: OperatingPoint, free: NDArray,
                 generator: Generator | None = None, induction: str = "frozen", mbc: bool = True) -> AeroelasticModel:
    """The aeroelastic linear model at ``point`` (module description). ``structure`` carries no loads of its own;
    ``generator`` adds the torque law's damping when the generator azimuth is free."""
    if induction not in INDUCTIONS:
        raise ValueError(f"induction must be one of {INDUCTIONS}, got {induction!r}")
    free = np.asarray(free, dtype=bool)
    sections = SectionAero.of(aero) if aero is not None else None
    ix = np.flatnonzero(free)
    block = np.ix_(ix, ix)
    names = [structure.dofs[i] for i in ix]
    spinning = point.rotor_speed != 0.0
    q0, u0 = point.state(structure, point.azimuths[0])
    transform = mbc_transform(FreeSystem(structure, free, q0, u0), point.azimuths[0]) if mbc else None
    if transform is None or (spinning and not point.symmetric):
        A, M = state_matrix_at(structure, aero, generator, free, q0, u0, induction, sections)
        stiffness, mass = np.diag(structure.K[block]), np.diag(M)
    else:
        azimuths = point.azimuths if spinning else point.azimuths[:1]
        m = len(ix)
        A, stiffness, mass = np.zeros((2 * m, 2 * m)), np.zeros(m), np.zeros(m)
        for psi in azimuths:
            q, u = point.state(structure, psi)
            T, dT, ddT, names = mbc_transform(FreeSystem(structure, free, q, u), psi)
            A_psi, M = state_matrix_at(structure, aero, generator, free, q, u, induction, sections)
            if spinning:
                A += mbc_state_matrix(A_psi, T, dT, ddT, point.rotor_speed) / len(azimuths)
            else:
                Tx = np.kron(np.eye(2), T)
                A += np.linalg.solve(Tx, A_psi @ Tx)
            stiffness += np.diag(T.T @ structure.K[block] @ T) / len(azimuths)
            mass += np.diag(T.T @ M @ T) / len(azimuths)
    averaged = spinning and transform is not None and point.symmetric
    modes, rigid = modes_of(A, names, stiffness, mass, spinning=spinning)
    return AeroelasticModel(point=point, induction=induction, A=A, coordinates=names, averaged=averaged,
                            modes=modes, rigid=rigid, deflections=point.deflections(structure))
