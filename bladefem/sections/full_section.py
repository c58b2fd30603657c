"""The whole cross-section: a six-by-six stiffness and a six-by-six mass matrix per station.

Axes: bladefem's section frame, turned with the section by the structural twist (plus pitch) about the span axis:
``x`` along the reference axis from root to tip, ``eta`` along the chord toward the leading edge, ``zeta = x cross
eta`` through the thickness (at zero twist and pitch ``eta`` and ``zeta`` are the blade frame's ``y`` and ``z``,
``zeta`` downwind). A section point sits at ``s = eta e_eta + zeta e_zeta`` from the reference axis.

Ordering (both matrices, index 0..5):

- stiffness: generalised strains ``(epsilon, gamma_eta, gamma_zeta, kappa_x, kappa_eta, kappa_zeta)`` (extension,
  the two transverse shears, twist rate, the curvatures about ``eta`` and ``zeta``) to the section forces
  ``(N, V_eta, V_zeta, T, M_eta, M_zeta)``; the axial strain of a fibre is ``epsilon + zeta kappa_eta - eta
  kappa_zeta``;
- mass: velocities ``(u_x, u_eta, u_zeta, omega_x, omega_eta, omega_zeta)`` of the reference point to the momenta,
  ``[[m I, -m [c]x], [m [c]x, I_rot]]`` with ``c`` the centre of mass and ``I_rot`` the rotary inertia per length
  about the reference axis, both in the section frame.

This is BeamDyn's section model (docs/source/user/beamdyn/input_files.rst, "Distributed Properties", and theory.rst,
"Blade Reference Coordinate System") in other axes: BeamDyn orders ``(X, Y, Z)`` with ``Z`` along the span, ``X``
toward the suction side (downwind) and ``Y`` toward the trailing edge; the mapping lives in
:mod:`bladefem.builders.section_axes`.

Two beams carry these sections. Shear-flexible (:attr:`FullSections.shear_flexible`, what the six-by-six readers
give by default): the finite elements add the transverse-shear deflections (a Timoshenko beam) and take the whole
6x6. Condensed: Euler-Bernoulli kinematics, the shear forces set free (zero) and the shear strains following the
other strains, exact in the slender limit; the classical stiffness is the Schur complement of the shear block,
``C = K_cc - K_cs K_ss^-1 K_sc`` over ``(epsilon, kappa_x, kappa_eta, kappa_zeta)``: the inverse of the classical
block of the section compliance. Every other coupling stays in both: tension-centre offsets (extension-bending),
principal axes turned from the chord (bending-bending), extension-twist and bend-twist.

Between stations every matrix entry is linear in the span position (as in BeamDyn); two stations at one position
mark a step (the value above it is taken there).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError

if TYPE_CHECKING:
    from .moments import MassMoments
    from .table import SectionTable

#: indices of the classical strains (extension, twist rate, the two curvatures) and of the transverse shears
CLASSICAL = (0, 3, 4, 5)
SHEAR = (1, 2)
#: relative asymmetry accepted in a stiffness matrix (files carry six or seven digits)
SYMMETRY_TOLERANCE = 1e-6


def frame_rotation(angle: NDArray | float) -> NDArray:
    """3x3 (trailing axes: those of ``angle``) whose columns are the axes ``(x, eta, zeta)`` of a frame turned by
    ``angle`` (rad, in the sense of the structural twist: positive turns the leading edge toward ``-zeta``), in the
    frame it was turned from."""
    c, s = np.cos(angle), np.sin(angle)
    one, zero = np.ones_like(c), np.zeros_like(c)
    return np.array([[one, zero, zero], [zero, c, s], [zero, -s, c]])


def _rotation6(angle: NDArray | float) -> NDArray:
    Q = frame_rotation(angle)
    R = np.zeros((6, 6) + np.shape(Q)[2:])
    R[:3, :3] = R[3:, 3:] = Q
    return R


def _transfer(eta: float, zeta: float) -> NDArray:
    """A with ``strains at (eta, zeta) = A strains at the reference axis``: ``gamma_p = gamma - [s]x kappa``."""
    A = np.eye(6)
    A[0, 4], A[0, 5] = zeta, -eta
    A[1, 3] = -zeta
    A[2, 3] = eta
    return A


def about_reference(matrix: NDArray, point: tuple[float, float] = (0.0, 0.0), angle: float = 0.0) -> NDArray:
    """A 6x6 section matrix given about ``point`` ``(eta, zeta)`` (m) in axes turned by ``angle`` (rad, like the
    twist) from the section axes, taken to the reference axis in the section axes: ``A^T R K R^T A`` (``R`` turns
    force and moment components, ``A`` moves the strains, :func:`_transfer`)."""
    turned, A = _rotation6(angle), _transfer(*point)
    return A.T @ turned @ np.asarray(matrix, dtype=float) @ turned.T @ A


def stiffness_matrix(axial: float, torsion: float, flap: float, edge: float, shear_chord: float,
                     shear_normal: float, tension_centre: tuple[float, float] = (0.0, 0.0),
                     principal_angle: float = 0.0, shear_centre: tuple[float, float] = (0.0, 0.0),
                     extension_twist: float = 0.0, flap_twist: float = 0.0, edge_twist: float = 0.0,
                     shear_angle: float = 0.0) -> NDArray:
    """The 6x6 section stiffness about the reference axis from engineering constants.

    axial : EA, N; torsion : GJ about the shear centre, N m^2
    flap, edge : EI about the principal axes through the tension centre, N m^2 (flap: about the principal chordwise
        axis, edge: about the principal thickness axis)
    shear_chord, shear_normal : shear stiffnesses k GA along ``eta`` and ``zeta`` at the shear centre, N
    tension_centre, shear_centre : ``(eta, zeta)`` positions, m
    principal_angle : the principal axes turned from the section axes, rad (positive like the twist)
    shear_angle : the axes of the two shear stiffnesses turned from the section axes, rad (HAWC2 gives them in the
        principal axes)
    extension_twist : K[0, 3], N m; flap_twist, edge_twist : K[3, 4], K[3, 5], N m^2 (about the reference axis)
    """
    K = (about_reference(np.diag([axial, 0.0, 0.0, 0.0, flap, edge]), tension_centre, principal_angle)
         + about_reference(np.diag([0.0, shear_chord, shear_normal, torsion, 0.0, 0.0]), shear_centre, shear_angle))
    K[0, 3] += extension_twist
    K[3, 4] += flap_twist
    K[3, 5] += edge_twist
    return np.triu(K) + np.triu(K, 1).T


def mass_matrix(mass: float, centre_of_mass: tuple[float, float] = (0.0, 0.0), flap_inertia: float = 0.0,
                edge_inertia: float = 0.0, product_of_inertia: float = 0.0) -> NDArray:
    """The 6x6 section mass from the mass per length (kg/m), the centre of mass ``(eta, zeta)`` (m) and the
    inertias per length about it in the section axes (kg m): ``flap_inertia = int rho (zeta - zeta_c)^2``,
    ``edge_inertia = int rho (eta - eta_c)^2``, ``product_of_inertia = int rho (eta - eta_c)(zeta - zeta_c)``.
    The polar inertia is their sum (a thin slice)."""
    c = np.array([0.0, *centre_of_mass])
    J = np.zeros((3, 3))
    J[1:, 1:] = [[edge_inertia, product_of_inertia], [product_of_inertia, flap_inertia]]
    J += mass * np.outer(c, c)
    return _assembled_mass(np.float64(mass), mass * c, J)


def _assembled_mass(m: NDArray, S: NDArray, J: NDArray) -> NDArray:
    """6x6 mass from m, first moment S (3, ...) and second moment J = int rho s s^T (3, 3, ...)."""
    zero = np.zeros_like(S[0])
    cross = np.array([[zero, -S[2], S[1]], [S[2], zero, -S[0]], [-S[1], S[0], zero]])      # [S]x
    M = np.zeros((6, 6) + np.shape(m))
    M[0, 0] = M[1, 1] = M[2, 2] = m
    M[3:, :3] = cross
    M[:3, 3:] = -cross
    M[3:, 3:] = np.einsum("ii...->...", J) * np.eye(3).reshape((3, 3) + (1,) * np.ndim(m)) - J
    return M


def condensed(K: NDArray) -> NDArray:
    """The classical 4x4 over ``(epsilon, kappa_x, kappa_eta, kappa_zeta)``: the Schur complement of the shear
    block of the 6x6 ``K`` (leading axes (6, 6), any trailing axes). A section without shear stiffness (a zero or
    singular shear block: files that give none mean the beam is rigid in shear) keeps its classical block."""
    K = np.moveaxis(np.asarray(K, dtype=float), (0, 1), (-2, -1))
    c, s = np.ix_(CLASSICAL, CLASSICAL), np.ix_(SHEAR, SHEAR)
    shear = K[(...,) + s]
    has = np.linalg.det(shear) > 0
    Kcs = K[..., list(CLASSICAL), :][..., list(SHEAR)] * has[..., None, None]
    shear = np.where(has[..., None, None], shear, np.eye(2))
    C = K[(...,) + c] - Kcs @ np.linalg.solve(shear, np.swapaxes(Kcs, -1, -2))
    return np.moveaxis(C, (-2, -1), (0, 1))


#: the entries of a 6x6 mass that the mass and its moments are read from (:func:`first_moment`, :func:`second_moment`)
MOMENT_ENTRIES: tuple[tuple[int, int], ...] = ((0, 0), (5, 1), (3, 2), (4, 0),
                                               *((i, j) for i in range(3, 6) for j in range(3, 6)))


def first_moment(M: NDArray) -> NDArray:
    """S = m c (3, ...) from a 6x6 mass: ``M[3:, :3] = [S]x``."""
    return np.stack([M[5, 1], M[3, 2], M[4, 0]])


def second_moment(M: NDArray) -> NDArray:
    """J = int rho s s^T (3, 3, ...) from a 6x6 mass: ``I_rot = tr(J) I - J``, so ``J = tr(I_rot) / 2 I - I_rot``
    (``J_xx = (I_xx - I_etaeta - I_zetazeta) / 2``, zero for a thin slice whose polar inertia is the sum of the
    other two)."""
    I_rot = M[3:, 3:]
    return 0.5 * np.einsum("ii...->...", I_rot) * np.eye(3).reshape((3, 3) + (1,) * (np.ndim(M) - 2)) - I_rot


def _bad(message: str, source: str, station: int, name: str) -> InputError:
    return InputError(f"{message} (station {station + 1})", file=source or None, field=name)


@dataclass(frozen=True)
class FullSections:
    """Six-by-six section stiffness and mass at span stations (see the module text for axes and ordering).

    Attributes
    ----------
    span : station positions along the reference axis from the root, m (increasing, first 0; an interior position
        given twice is a step)
    stiffness : (stations, 6, 6) section stiffness about the reference axis, N, N m, N m^2
    mass : (stations, 6, 6) section mass about the reference axis, kg/m, kg, kg m
    twist : structural twist of the section frame, rad (positive turns the leading edge upwind, like pitch to
        feather)
    chord, pitch_axis : planform geometry for drawing (see :class:`~bladefem.sections.table.SectionTable`)
    shear_flexible : the FE keeps the transverse shear (a Timoshenko beam with the whole 6x6); False condenses it
        (Euler-Bernoulli with every other coupling, :func:`condensed`)
    """

    span: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    mass: NDArray[np.float64]
    twist: NDArray[np.float64] | None = None
    chord: NDArray[np.float64] | None = None
    pitch_axis: NDArray[np.float64] | None = None
    source: str = field(default="", compare=False)
    shear_flexible: bool = False

    def __post_init__(self) -> None:
        span = np.asarray(self.span, dtype=float)
        object.__setattr__(self, "span", span)
        for name in ("stiffness", "mass"):
            value = np.asarray(getattr(self, name), dtype=float)
            if value.shape != (len(span), 6, 6):
                raise InputError(f"need one 6x6 matrix per station, got shape {value.shape}",
                                 file=self.source or None, field=name)
            object.__setattr__(self, name, value)
        for name in ("twist", "chord", "pitch_axis"):
            value = getattr(self, name)
            if value is not None or name == "twist":
                array = np.broadcast_to(np.asarray(0.0 if value is None else value, dtype=float), span.shape)
                object.__setattr__(self, name, array.copy())
        self._validate()
        object.__setattr__(self, "stiffness", 0.5 * (self.stiffness + np.swapaxes(self.stiffness, 1, 2)))

    def _validate(self) -> None:
        for name in ("stiffness", "mass"):
            bad = np.flatnonzero(~np.all(np.isfinite(getattr(self, name)), axis=(1, 2)))
            if bad.size:
                raise _bad("a matrix entry is not a finite number", self.source, int(bad[0]), name)
        K, M = self.stiffness, self.mass
        diagonal = np.sqrt(np.abs(np.einsum("nii->ni", K)))
        scale = diagonal[:, :, None] * diagonal[:, None, :]
        asymmetric = np.flatnonzero(np.any(np.abs(K - np.swapaxes(K, 1, 2)) > SYMMETRY_TOLERANCE * scale,
                                           axis=(1, 2)))
        if asymmetric.size:
            raise _bad("the stiffness matrix is not symmetric", self.source, int(asymmetric[0]), "stiffness")
        for i, matrix in enumerate(0.5 * (K + np.swapaxes(K, 1, 2))):
            if np.any(np.linalg.eigvalsh(matrix) <= 0):
                raise _bad("the stiffness matrix is not positive definite", self.source, i, "stiffness")
        m = M[:, 0, 0]
        if np.any(m <= 0):
            raise _bad(f"the mass per length must be positive, got {m[m <= 0][0]}", self.source,
                       int(np.flatnonzero(m <= 0)[0]), "mass")
        translation = M[:, :3, :3] - m[:, None, None] * np.eye(3)
        radius = np.sqrt(np.abs(np.einsum("nii->n", M[:, 3:, 3:])) / m)
        S = first_moment(np.moveaxis(M, 0, -1)).T
        coupling = M[:, 3:, :3]
        skew_part = np.concatenate([coupling + np.swapaxes(coupling, 1, 2),
                                    coupling - np.swapaxes(M[:, :3, 3:], 1, 2)], axis=1)
        wrong = (np.any(np.abs(translation) > SYMMETRY_TOLERANCE * m[:, None, None], axis=(1, 2))
                 | (np.abs(S[:, 0]) > SYMMETRY_TOLERANCE * m * radius)
                 | np.any(np.abs(skew_part) > SYMMETRY_TOLERANCE * (m * radius)[:, None, None], axis=(1, 2)))
        if np.any(wrong):
            raise _bad("not a section mass matrix [[m I, -[S]x], [[S]x, I_rot]] with the centre of mass in the "
                       "section plane", self.source, int(np.flatnonzero(wrong)[0]), "mass")
        for i, matrix in enumerate(M):
            if np.any(np.linalg.eigvalsh(0.5 * (matrix + matrix.T)) < -SYMMETRY_TOLERANCE * m[i] * (1 + radius[i]**2)):
                raise _bad("the mass matrix is not positive semi-definite", self.source, i, "mass")

    def _at(self, x: NDArray, matrices: NDArray, entries: tuple[tuple[int, int], ...] | None = None) -> NDArray:
        """(6, 6, *x.shape) entries linear between stations (only ``entries``, the others zero, when given)."""
        x = np.asarray(x, dtype=float)
        values = np.zeros((6, 6) + x.shape)
        for i, j in entries or np.ndindex(6, 6):
            values[i, j] = np.interp(x, self.span, matrices[:, i, j])
        return values

    def stiffness_at(self, x: NDArray) -> NDArray:
        """6x6 stiffness (6, 6, ...) at span positions ``x`` (m), section frame."""
        return self._at(x, self.stiffness)

    def mass_at(self, x: NDArray) -> NDArray:
        """6x6 mass (6, 6, ...) at span positions ``x`` (m), section frame."""
        return self._at(x, self.mass)

    def classical(self, x: NDArray) -> NDArray:
        """The shear-condensed 4x4 (4, 4, ...) over ``(epsilon, kappa_x, kappa_eta, kappa_zeta)`` at ``x``."""
        return condensed(self.stiffness_at(x))

    def blade_stiffness(self, x: NDArray, pitch: float = 0.0) -> NDArray:
        """The classical stiffness for the blade-frame strains ``(u', phi', v'', w'')`` (4, 4, ...), N .. N m^2.

        The section turned by ``theta`` = twist + pitch has ``e_eta = (cos, -sin)`` and ``e_zeta = (sin, cos)`` in
        the blade's ``(y, z)``; the curvature vector ``(phi', -w'', v'')`` gives ``kappa_eta = -sin v'' - cos w''``
        and ``kappa_zeta = cos v'' - sin w''``: ``D = T^T C T``.
        """
        theta = np.interp(x, self.span, self.twist) + pitch
        c, s = np.cos(theta), np.sin(theta)
        one, zero = np.ones_like(c), np.zeros_like(c)
        T = np.array([[one, zero, zero, zero], [zero, one, zero, zero], [zero, zero, -s, -c],
                      [zero, zero, c, -s]])
        return np.einsum("ai...,ab...,bj...->ij...", T, self.classical(x), T)

    def blade_section_stiffness(self, x: NDArray, pitch: float = 0.0) -> NDArray:
        """The whole 6x6 (6, 6, ...) for the blade-frame strains ``(u', gamma_y, gamma_z, phi', v'', w'')`` of a
        shear-flexible beam: the shear strains turn like the chord axes, ``gamma_eta = cos gamma_y - sin gamma_z``,
        ``gamma_zeta = sin gamma_y + cos gamma_z``, the curvatures as in :meth:`blade_stiffness`: ``T^T K T``."""
        theta = np.interp(x, self.span, self.twist) + pitch
        c, s = np.cos(theta), np.sin(theta)
        one, zero = np.ones_like(c), np.zeros_like(c)
        T = np.array([[one, zero, zero, zero, zero, zero], [zero, c, -s, zero, zero, zero],
                      [zero, s, c, zero, zero, zero], [zero, zero, zero, one, zero, zero],
                      [zero, zero, zero, zero, -s, -c], [zero, zero, zero, zero, c, -s]])
        return np.einsum("ai...,ab...,bj...->ij...", T, self.stiffness_at(x), T)

    def with_shear(self, flexible: bool) -> FullSections:
        """A copy whose FE beam is shear-flexible (``True``) or has the shear condensed (``False``)."""
        return replace(self, shear_flexible=flexible)

    def mass_moments(self, x: NDArray, pitch: float = 0.0) -> MassMoments:
        """Mass per length, first and second moments about the reference axis in the blade frame at ``x``."""
        from .moments import MassMoments

        M = self._at(x, self.mass, MOMENT_ENTRIES)
        Q = frame_rotation(np.interp(x, self.span, self.twist) + pitch)
        S = np.einsum("ij...,j...->i...", Q, first_moment(M))
        J = np.einsum("ia...,ab...,jb...->ij...", Q, second_moment(M), Q)
        return MassMoments(m=M[0, 0], S=S, J=J)

    def summary(self) -> dict[str, NDArray]:
        """The columns of :class:`~bladefem.sections.table.SectionTable` that summarise these sections (for the
        paths that read columns: reports, mesh grading): EA, GJ (classical), the bending stiffnesses about the
        tension centre with extension and twist free in the section axes (their product term, turned principal
        axes, is in the matrices only), the chordwise tension-centre and centre-of-mass offsets, the inertias about
        the centre of mass in the section axes."""
        C = np.moveaxis(condensed(np.moveaxis(self.stiffness, 0, -1)), -1, 0)         # (n, 4, 4)
        bending = self.bending()
        M = np.moveaxis(self.mass, 0, -1)
        m = M[0, 0]
        c = first_moment(M) / m
        J = second_moment(M) - m * np.einsum("i...,j...->ij...", c, c)
        return dict(mass=m, axial_stiffness=C[:, 0, 0], torsion_stiffness=C[:, 1, 1],
                    flap_stiffness=bending[:, 0, 0], edge_stiffness=bending[:, 1, 1],
                    tension_centre_offset=-C[:, 0, 3] / C[:, 0, 0], cm_offset=c[1],
                    flap_inertia=np.maximum(J[2, 2], 0.0), edge_inertia=np.maximum(J[1, 1], 0.0),  # round-off of m c^2
                    twist=self.twist)

    def bending(self) -> NDArray:
        """(stations, 2, 2) bending stiffness over the curvatures ``(kappa_eta, kappa_zeta)`` about the tension
        centre, extension and twist free (axial force and torque zero), in the section axes, N m^2."""
        C = np.moveaxis(condensed(np.moveaxis(self.stiffness, 0, -1)), -1, 0)
        return C[:, 2:, 2:] - C[:, 2:, :2] @ np.linalg.solve(C[:, :2, :2], C[:, :2, 2:])

    def table(self) -> SectionTable:
        """A :class:`~bladefem.sections.table.SectionTable` that carries these sections (the FE takes stiffness
        and mass from them) with the summary columns (:meth:`summary`)."""
        from .table import SectionTable

        return SectionTable(span=self.span, chord=self.chord, pitch_axis=self.pitch_axis, full=self,
                            source=self.source, **self.summary())

    def with_stiffness_scaled(self, strain: int, factor: float | NDArray) -> FullSections:
        """A copy whose stiffness for generalised strain ``strain`` (0 extension, 3 twist rate, 4 and 5 the
        curvatures about ``eta`` and ``zeta``) is multiplied by ``factor`` (one number or one per station): the
        diagonal entry by ``factor``, its couplings by ``sqrt(factor)``, so every coupling coefficient
        ``K_ij / sqrt(K_ii K_jj)`` and the positive definiteness are kept (``K' = D K D``)."""
        root = np.broadcast_to(np.sqrt(np.asarray(factor, dtype=float)), self.span.shape)
        D = np.ones((len(self.span), 6))
        D[:, strain] = root
        return replace(self, stiffness=D[:, :, None] * self.stiffness * D[:, None, :])

    def scaled(self, mass: float = 1.0, stiffness: float = 1.0) -> FullSections:
        """A copy with the mass and stiffness matrices multiplied by the given factors."""
        return FullSections(span=self.span, stiffness=self.stiffness * stiffness, mass=self.mass * mass,
                            twist=self.twist, chord=self.chord, pitch_axis=self.pitch_axis, source=self.source,
                            shear_flexible=self.shear_flexible)


def full_sections_from_table(table: SectionTable, shear_stiffness: float | NDArray | None = None) -> FullSections:
    """The six-by-six sections of a column table (needs EA and GJ): EA and the flap and edge EI about the tension
    centre on the chord, GJ, the centre of mass on the chord, the inertias about it. A column table has no shear
    stiffness; nothing couples to it, so the condensed section (the beam these sections make: not shear-flexible)
    does not depend on it: ``shear_stiffness`` (N) defaults to EA. Between stations the columns' own
    interpolation (offsets linear, inertias per
    :attr:`~bladefem.sections.table.SectionTable.inertia_per_mass`) and the matrices' (entries linear) agree where
    the offsets are constant and the inertias are interpolated per length."""
    if table.axial_stiffness is None or table.torsion_stiffness is None:
        raise InputError("six-by-six sections need the axial (EA) and torsion (GJ) stiffness", field="sections")
    shear = table.axial_stiffness if shear_stiffness is None else np.broadcast_to(shear_stiffness, table.span.shape)
    K = np.array([stiffness_matrix(table.axial_stiffness[i], table.torsion_stiffness[i], table.flap_stiffness[i],
                                   table.edge_stiffness[i], shear[i], shear[i],
                                   tension_centre=(table.tension_centre_offset[i], 0.0))
                  for i in range(table.stations)])
    M = np.array([mass_matrix(table.mass[i], (table.cm_offset[i], 0.0), table.flap_inertia[i],
                              table.edge_inertia[i]) for i in range(table.stations)])
    return FullSections(span=table.span, stiffness=K, mass=M, twist=table.twist, chord=table.chord,
                        pitch_axis=table.pitch_axis, source=table.source)
