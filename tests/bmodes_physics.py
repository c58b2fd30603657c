"""BModes' physics in bladefem, one named difference at a time (a test helper: bladefem itself keeps the right
physics and says so in its notes).

Each entry of :data:`DIFFERENCES` is something BModes (and pybmodes, its port) leaves out or does differently,
with how to make bladefem do the same. All of them together turn bladefem into BModes' model, which
tests/test_pybmodes_decks.py compares with pybmodes to 1e-4; one at a time they measure each difference.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, replace
from unittest import mock

import numpy as np
import scipy.sparse as sp

import bladefem.assembly.blade as assembly_blade
import bladefem.assembly.parameters as assembly_parameters
import bladefem.assembly.tower as assembly_tower
from bladefem.formats.bmodes import BModesInput
from bladefem.builders.bmodes_model import blade_from_bmodes
from bladefem.builders.bmodes_tower import tower_from_bmodes
from bladefem.modal import modes
from bladefem.models.tower import tower_modes
from bladefem.sections.tower import Wires

#: rows of the section kinematic vector (u, v, w, phi, -w', v') that are bending slopes
SLOPES = [4, 5]


@dataclass(frozen=True)
class Difference:
    """A named difference: what BModes does, and how bladefem is made to do it (a patch of its assembly, a change of
    the deck, a change of the model)."""

    name: str
    what: str
    patches: Callable[[], list] = list
    deck: Callable[[BModesInput], BModesInput] = lambda deck: deck
    model: Callable[[object], object] = lambda model: model


def _without_rotary_inertia(parameters, rotating: bool):
    inertia = parameters.inertia.copy()
    inertia[SLOPES, :] = inertia[:, SLOPES] = 0.0
    changes = {"inertia": inertia}
    if rotating:
        spin = parameters.spin.copy()
        spin[SLOPES, :] = spin[:, SLOPES] = 0.0
        rotation = parameters.rotation.copy()
        rotation[1:, 1:] = 0.0                       # the slopes' share of the centrifugal second-order terms
        changes.update(spin=spin, rotation=rotation)
    return replace(parameters, **changes)


def _rotary_patches() -> list:
    blade, tower = assembly_blade.section_parameters, assembly_tower.section_parameters
    return [mock.patch.object(assembly_blade, "section_parameters",
                              lambda b, x: _without_rotary_inertia(blade(b, x), True)),
            mock.patch.object(assembly_tower, "section_parameters",
                              lambda t, x: _without_rotary_inertia(tower(t, x), False))]


def _axial_softening_patches() -> list:
    blade = assembly_blade.section_parameters

    def no_axial(b, x):
        parameters = blade(b, x)
        spin = parameters.spin.copy()
        spin[0, :] = spin[:, 0] = 0.0
        return replace(parameters, spin=spin)
    return [mock.patch.object(assembly_blade, "section_parameters", no_axial)]


def _tip_patches() -> list:
    tip = assembly_blade.tip_body_matrices

    def no_centrifugal(blade, dofs):
        M, K2 = tip(blade, dofs)
        return M, sp.csr_matrix(K2.shape)
    return [mock.patch.object(assembly_parameters, "tip_tension", lambda blade: 0.0),
            mock.patch.object(assembly_blade, "tip_body_matrices", no_centrifugal)]


def _wire_patches() -> list:
    def bmodes_wires(self: Wires) -> np.ndarray:
        lateral = self.count * self.stiffness * np.sin(self.angle) ** 2     # n k cos^2 of the angle from the ground
        return np.diag([0.0, lateral, lateral])
    return [mock.patch.object(Wires, "stiffness_matrix", bmodes_wires)]


def _cm_axial_read_into_cm_loc(deck: BModesInput) -> BModesInput:
    if deck.beam_type == 2 and deck.hub_conn != 1:          # pybmodes reads these decks' tip offsets as written
        return deck
    return replace(deck, tip={**deck.tip, "cm_loc": deck.tip["cm_axial"], "cm_axial": 0.0})


DIFFERENCES = (
    Difference("gravity", "BModes has no gravity (towers: axial load and top-mass pendulum)",
               model=lambda model: model.with_(gravity=0.0) if isinstance(getattr(model, "gravity", None), float)
               else model),                              # a tower's g; a blade's weight is off by default
    Difference("rotary inertia", "BModes' sections have no rotary inertia in bending (nor its first-moment and "
               "centrifugal share)", patches=_rotary_patches),
    Difference("axial softening", "BModes leaves out the centrifugal softening of axial motion",
               patches=_axial_softening_patches),
    Difference("tip mass", "BModes' tip mass adds no centrifugal tension or softening", patches=_tip_patches),
    Difference("precone", "BModes' stiffness leaves out the precone",
               model=lambda model: model.with_(precone=0.0) if hasattr(model, "precone") else model),
    Difference("cm_axial", "BModes v3.00 reads the cm_axial line into cm_loc", deck=_cm_axial_read_into_cm_loc),
    Difference("wires", "BModes puts n k cos^2 on each lateral axis of the attachment node", patches=_wire_patches),
)
NAMES = tuple(d.name for d in DIFFERENCES)


@contextmanager
def bmodes_like(names: tuple[str, ...] = NAMES) -> Iterator[Callable[[BModesInput], object]]:
    """Within the block, bladefem's assembly does what BModes does for each named difference; yields the function
    that builds the model of a deck accordingly."""
    chosen = [d for d in DIFFERENCES if d.name in names]
    with ExitStack() as stack:
        for difference in chosen:
            for patch in difference.patches():
                stack.enter_context(patch)

        def build(deck: BModesInput):
            for difference in chosen:
                deck = difference.deck(deck)
            model = blade_from_bmodes(deck) if deck.beam_type == 1 else tower_from_bmodes(deck)
            for difference in chosen:
                model = difference.model(model)
            return model
        yield build


def frequencies(deck: BModesInput, count: int, elements: int, names: tuple[str, ...] = ()) -> np.ndarray:
    """bladefem's lowest ``count`` frequencies (Hz) of ``deck`` on a mesh of about ``elements`` elements, with the
    named differences switched to BModes'."""
    with bmodes_like(names) as build:
        model = build(deck)
        if deck.beam_type == 1:
            result = modes(model, deck.rotor_speed_rpm, count, elements=elements)
        else:
            result = tower_modes(model, count, elements=elements)
    return np.array([m.frequency_hz for m in result.modes])
