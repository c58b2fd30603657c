"""A tower as plain section data, the common product of the tower readers (ElastoDyn, BModes, windIO).

Tower frame: ``x`` up along the tower axis from the top of the rigid base (the flexible length starts there),
``z`` fore-aft (downwind), ``y`` side-side. Fore-aft bending is stored in the section table's ``flap_stiffness``
column (bending in the x-z plane) and side-side bending in ``edge_stiffness``, so a tower is a non-rotating beam in
the same frame as a blade, and ``flap``/``edge`` mode kinds read as fore-aft/side-side.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..sections import Blade, SectionTable, TipMass


@dataclass(frozen=True)
class Tower:
    """Tower section properties and the rigid body at its top.

    sections : span = height above the tower base, m; flap_stiffness = fore-aft EI, edge_stiffness = side-side EI
    base_height : height of the tower base above ground or mean sea level, m
    top_mass : the rotor-nacelle assembly (or any tower-top body) as a rigid body at the top, or None
    name : label for reports
    notes : modelling statements made while reading
    """

    sections: SectionTable
    base_height: float = 0.0
    top_mass: TipMass | None = None
    name: str = "tower"
    notes: tuple[str, ...] = ()

    @property
    def height(self) -> float:
        """Flexible length of the tower, m."""
        return self.sections.length

    def as_beam(self) -> Blade:
        """The tower as a non-rotating cantilever beam (a :class:`Blade` at zero rotor speed, no hub radius), for
        the beam finite elements: flap modes are fore-aft, edge modes side-side."""
        return Blade(sections=self.sections, hub_radius=0.0, tip_mass=self.top_mass, name=self.name,
                     notes=self.notes + ("tower as a clamped non-rotating beam: 'flap' = fore-aft, "
                                         "'edge' = side-side; gravity (axial load) is not included",))
