"""Assemble the blade's matrices K0, K2 (per Omega^2) and M once: K(Omega) = K0 + Omega^2 K2; and, when the
quadratic eigenproblem asks for it, the gyroscopic matrix G (per Omega)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray
from skfem import Basis

from ..elements import (
    FIELD_KINDS,
    SHEAR_FIELDS,
    SectionMotion,
    beam_element,
    gyroscopic_inertia,
    interpolated_components,
    projected_inertia,
    rotation_second_order,
)
from ..errors import InputError
from ..sections import Blade
from ..sections.table import OPTIONAL_STIFFNESS, POSITIVE, ZERO_DEFAULT
from . import terms
from .dofs import DofMap
from .forms import Quadrature, Term, assemble_operator, assemble_terms, gram_matrix, pointwise_operator
from .mesh import graded_nodes, mesh_stations, span_mesh, span_nodes
from .loads import centrifugal_load, gravity_load, tip_geometry
from .parameters import SectionParameters, section_parameters

#: Gauss rule degree: cubic x cubic x linear property x smooth twist
QUADRATURE_ORDER = 9
#: the terms of K2 (per Omega^2) and of M
CENTRIFUGAL_TERMS: tuple[Term, ...] = (terms.axial_force_stiffness, terms.spin_softening, terms.rotation_second_order)
INERTIA_TERMS: tuple[Term, ...] = (terms.inertia,)


@dataclass(frozen=True)
class BladeMatrices:
    """Global matrices over all DOFs (before root conditions) and the DOF map.

    K0 : elastic stiffness, N/m-type units
    K2 : stiffness per Omega^2 (centrifugal tension, spin softening, rotation second order), kg-type units
    M : mass matrix
    free : DOFs left free by the root condition
    quadrature, parameters : the mesh's quadrature and the section parameters there
    elastic_operator : K0's form at the quadrature points (:func:`~bladefem.assembly.forms.pointwise_operator`),
        which K0 is assembled from and :meth:`stiffness_gram` evaluates on given vectors
    notes : statements about the mesh (e.g. refinement stopped before convergence)
    eigenpairs : rotor speed (rpm) -> lowest eigenpairs (omega^2, M-normalised vectors) already solved on these
        matrices, kept for re-use
    stiffness : rotor speed (rad/s) -> the free-DOF K(Omega) last formed by :meth:`reduced`
    G (property) : gyroscopic (Coriolis) matrix per Omega, for the quadratic eigenproblem
    """

    K0: sp.csr_matrix
    K2: sp.csr_matrix
    M: sp.csr_matrix
    dofs: DofMap
    free: NDArray[np.int64]
    blade: Blade
    quadrature: Quadrature
    parameters: SectionParameters
    elastic_operator: NDArray = field(compare=False, repr=False)
    notes: tuple[str, ...] = ()
    eigenpairs: dict[float, tuple[NDArray, NDArray]] = field(default_factory=dict, compare=False, repr=False)
    stiffness: dict[float, sp.csc_matrix] = field(default_factory=dict, compare=False, repr=False)

    @cached_property
    def free_parts(self) -> tuple[sp.csc_matrix, sp.csc_matrix, sp.csc_matrix]:
        """(K0, K2, M) restricted to the free DOFs (computed once)."""
        return tuple(A[self.free][:, self.free].tocsc() for A in (self.K0, self.K2, self.M))  # type: ignore[return-value]

    def reduced(self, rotor_speed: float) -> tuple[sp.csc_matrix, sp.csc_matrix]:
        """(K, M) on the free DOFs at rotor speed ``rotor_speed`` (rad/s); K of the last speed asked for is kept
        (the solve and its round-off estimate ask for the same one)."""
        K0, K2, M = self.free_parts
        if rotor_speed not in self.stiffness:
            self.stiffness.clear()
            self.stiffness[rotor_speed] = (K0 + rotor_speed**2 * K2).tocsc()
        return self.stiffness[rotor_speed], M

    def stiffness_gram(self, vectors: NDArray) -> NDArray:
        """``V^T K0 V`` of free-DOF vectors (columns), summed at the quadrature points
        (:func:`~bladefem.assembly.forms.gram_matrix`): accurate where the assembled product cancels. (K2 and M
        hold values and slopes only, whose products lose at most (L / h)^2 digits.)"""
        full = np.zeros((self.dofs.size, np.shape(vectors)[1]))
        full[self.free] = vectors
        return gram_matrix(self.quadrature, self.elastic_operator, full)

    @cached_property
    def G(self) -> sp.csr_matrix:
        """Gyroscopic (Coriolis) matrix per Omega over all DOFs, skew-symmetric, kg (:func:`terms.coriolis` and the
        tip body), assembled on first use: only the quadratic eigenproblem needs it."""
        G = assemble_terms(self.quadrature, self.parameters, (terms.coriolis,)) + tip_body_gyroscopic(self.blade,
                                                                                                    self.dofs)
        return (0.5 * (G - G.T)).tocsr()          # skew to the last bit (quadrature sums differ in round-off)

    @cached_property
    def free_gyroscopic(self) -> sp.csc_matrix:
        """G restricted to the free DOFs."""
        return self.G[self.free][:, self.free].tocsc()

    @cached_property
    def free_field_dofs(self) -> dict[str, NDArray[np.int64]]:
        """Field -> positions of its DOFs among the free DOFs."""
        position = np.full(self.dofs.size, -1)
        position[self.free] = np.arange(len(self.free))
        return {name: position[dofs][position[dofs] >= 0] for name, dofs in self.dofs.field_dofs.items()}

    @cached_property
    def free_kind_dofs(self) -> dict[str, NDArray[np.int64]]:
        """Kind of motion (flap, edge, torsion, axial: :data:`~bladefem.elements.FIELD_KINDS`) -> positions of the
        DOFs of its fields among the free DOFs (flap: the bending and the shear deflection together)."""
        kinds: dict[str, list[NDArray[np.int64]]] = {}
        for name, local in self.free_field_dofs.items():
            kinds.setdefault(FIELD_KINDS[name], []).append(local)
        return {kind: np.sort(np.concatenate(parts)) if len(parts) > 1 else parts[0] for kind, parts in kinds.items()}

    @cached_property
    def kind_mass_blocks(self) -> dict[str, sp.csc_matrix]:
        """Kind of motion -> its diagonal block of the free mass matrix (for kinetic-energy shares)."""
        M = self.free_parts[2]
        return {kind: M[local][:, local] for kind, local in self.free_kind_dofs.items()}


def model_fields(blade: Blade) -> tuple[str, ...]:
    """Fields present in the model: bending always, twist if GJ is given, axial if EA is given, the shear
    deflections for shear-flexible six-by-six sections (:attr:`~bladefem.sections.FullSections.shear_flexible`)."""
    fields = ["v", "w"]
    if blade.sections.torsion_stiffness is not None:
        fields.append("phi")
    if blade.sections.axial_stiffness is not None:
        fields.append("u")
    elif blade.curved:
        raise InputError("a curved reference axis needs the axial stiffness (its bending stretches the axis): give "
                         "EA, or straighten the axis (--straight-axis)", field="axial_stiffness")
    if blade.sections.full is not None and blade.sections.full.shear_flexible:
        fields.extend(SHEAR_FIELDS)
    return tuple(fields)


def elastic_terms(fields: tuple[str, ...], parameters: SectionParameters) -> list[Term]:
    """K0's terms: the whole six-by-six section of a shear-flexible beam; otherwise bending (with extension when the
    axial field is present), torsion, and the twist couplings of six-by-six sections where they have any; and the
    weight's geometric stiffness when gravity is on."""
    return _section_terms(fields, parameters) + gravity_terms(fields, parameters)


def _section_terms(fields: tuple[str, ...], parameters: SectionParameters) -> list[Term]:
    if parameters.section is not None:
        return [terms.section_stiffness]
    parts: list[Term] = [terms.extension_bending_stiffness if "u" in fields else terms.bending_stiffness]
    if "phi" in fields:
        parts.append(terms.torsion_stiffness)
    if parameters.twist_coupling is not None:
        parts.append(terms.twist_coupling_stiffness)
    return parts


def gravity_terms(fields: tuple[str, ...], parameters: SectionParameters) -> list[Term]:
    """The weight's geometric stiffness (in K0): its axial force (with the tension on the shear slopes of a
    shear-flexible beam) and, on a prestressed blade, its static moments; nothing without gravity."""
    if parameters.gravity_tension is None:
        return []
    return ([terms.gravity_axial_force_stiffness]
            + ([terms.gravity_axial_force_shear_stiffness] if SHEAR_FIELDS[0] in fields else [])
            + ([terms.gravity_moment_prestress_stiffness] if parameters.gravity_static is not None else []))


def centrifugal_terms(fields: tuple[str, ...]) -> tuple[Term, ...]:
    """K2's terms, with the tension on the shear slopes for a shear-flexible beam."""
    return CENTRIFUGAL_TERMS + ((terms.axial_force_shear_stiffness,) if SHEAR_FIELDS[0] in fields else ())


def tip_body_matrices(blade: Blade, dofs: DofMap) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Mass matrix and K2 share of the tip mass: the rigid-body terms at the tip node (its centrifugal force is in
    the tension)."""
    tip = blade.tip_mass
    T = dofs.kinematic_selector(len(dofs.nodes) - 1)
    if tip is None or tip.mass == 0.0 and not tip.inertia.any():
        zero = sp.csr_matrix((dofs.size, dofs.size))
        return zero, zero
    S, J = tip.mass * tip.offset, tip.second_moment
    P, position = tip_geometry(blade)
    inertia = projected_inertia(np.eye(3), np.float64(tip.mass), S, J)
    K2 = -projected_inertia(P, np.float64(tip.mass), S, J)
    K2[3:, 3:] -= rotation_second_order(P, position, S, J)
    return (T.T @ sp.csr_matrix(inertia) @ T).tocsr(), (T.T @ sp.csr_matrix(K2) @ T).tocsr()


def static_deflection(K0: sp.csr_matrix, quadrature: Quadrature, blade: Blade, dofs: DofMap,
                      free: NDArray[np.int64], load: NDArray | None = None) -> SectionMotion:
    """The deflection under the centrifugal load per Omega^2, ``K0 q1 = b`` (m s^2), or under the given ``load``
    (the weight's, m), as motions at the quadrature points: whose static moments a prestressed blade's stiffness
    holds (:func:`~bladefem.assembly.terms.moment_prestress_stiffness`, to first order in Omega^2)."""
    q = np.zeros(dofs.size)
    b = centrifugal_load(quadrature, blade, dofs) if load is None else load
    q[free] = spla.spsolve(K0[free][:, free].tocsc(), b[free])
    names = tuple(SectionMotion.__dataclass_fields__)
    values = interpolated_components(quadrature.functions, quadrature.element_dofs, q[:, None], names)
    return SectionMotion(**{name: values[k, 0] for k, name in enumerate(names)})


def tip_body_gyroscopic(blade: Blade, dofs: DofMap) -> sp.csr_matrix:
    """Gyroscopic matrix (per Omega) of the tip mass on the tip node."""
    tip = blade.tip_mass
    if tip is None:
        return sp.csr_matrix((dofs.size, dofs.size))
    T = dofs.kinematic_selector(len(dofs.nodes) - 1)
    frame = blade.axis_frame(np.array(blade.length))
    shaft = blade.shaft_axis if frame is None else frame.to_local(blade.shaft_axis)
    G = gyroscopic_inertia(shaft, np.float64(tip.mass), tip.mass * tip.offset, tip.second_moment)
    return (T.T @ sp.csr_matrix(G) @ T).tocsr()


#: an axis knot closer than this fraction of the length to a section station is not made a node
AXIS_KNOT_GAP = 1e-4


def with_axis_knots(blade: Blade, stations: NDArray) -> NDArray:
    """``stations`` with the knots of a curved reference axis's splines added (where its curvature's slope jumps,
    so that no element straddles one), except those within :data:`AXIS_KNOT_GAP` of the length of a station."""
    if not blade.curved:
        return stations
    knots = blade.axis.span
    gap = np.min(np.abs(knots[:, None] - np.asarray(stations)[None, :]), axis=1)
    return np.sort(np.concatenate([stations, knots[gap > AXIS_KNOT_GAP * blade.length]]))


def blade_graded_nodes(blade: Blade, elements: int) -> NDArray:
    """Nodes graded by every section property the model uses (:func:`~bladefem.assembly.mesh.graded_nodes`) over
    the stations that matter (:func:`~bladefem.assembly.mesh.mesh_stations`)."""
    s = blade.sections
    names = POSITIVE + OPTIONAL_STIFFNESS + ZERO_DEFAULT
    present = [getattr(s, name) for name in names if getattr(s, name) is not None]
    stations = with_axis_knots(blade, mesh_stations(s.span, present))
    graded = [s.at(stations, name) for name in ("mass", "flap_stiffness", "edge_stiffness", "torsion_stiffness",
                                                "axial_stiffness", "flap_inertia", "edge_inertia")
              if getattr(s, name) is not None and np.max(getattr(s, name)) > 0]
    return graded_nodes(stations, graded, s.at(stations, "twist"), elements)


def assemble_blade(blade: Blade, elements: int = 60, nodes: NDArray | None = None) -> BladeMatrices:
    """Assemble K0, K2 and M for ``blade`` on a mesh with about ``elements`` elements (stations are nodes), or on
    the given ``nodes`` (m, increasing, from root to tip)."""
    fields = model_fields(blade)
    mesh = span_mesh(span_nodes(with_axis_knots(blade, blade.sections.span), elements) if nodes is None else nodes)
    basis = Basis(mesh, beam_element(fields), intorder=QUADRATURE_ORDER)
    parameters = section_parameters(blade, np.asarray(basis.global_coordinates())[0])
    quadrature = Quadrature.from_basis(basis, fields, parameters.curvature)
    dofs = DofMap.from_basis(basis, fields)
    M_tip, K2_tip = tip_body_matrices(blade, dofs)
    elastic = pointwise_operator(quadrature, parameters, elastic_terms(fields, parameters))
    K0 = assemble_operator(quadrature, elastic)
    free = np.setdiff1d(np.arange(dofs.size), dofs.root_dofs(blade.root))
    centrifugal = centrifugal_terms(fields)
    if blade.prestressed and blade.root == "cantilever":
        parameters = replace(parameters, static=static_deflection(K0, quadrature, blade, dofs, free))
        centrifugal = centrifugal + (terms.moment_prestress_stiffness,)
        if blade.gravity is not None:
            weight = static_deflection(K0, quadrature, blade, dofs, free, gravity_load(quadrature, blade, dofs))
            parameters = replace(parameters, gravity_static=weight)
            elastic = pointwise_operator(quadrature, parameters, elastic_terms(fields, parameters))
            K0 = assemble_operator(quadrature, elastic)        # with the weight's moments, as stiffness_gram sees it
    K2 = assemble_terms(quadrature, parameters, centrifugal) + K2_tip
    M = assemble_terms(quadrature, parameters, INERTIA_TERMS) + M_tip
    return BladeMatrices(K0=K0, K2=K2.tocsr(), M=M.tocsr(), dofs=dofs, free=free, blade=blade,
                         quadrature=quadrature, parameters=parameters, elastic_operator=elastic)
