"""Builders: records read from files onto bladefem's models (:class:`~bladefem.sections.Blade`,
:class:`~bladefem.sections.tower.Tower`, the turbine's parameters, the rotor's aerodynamics). This is the one place
where axes, units, reductions and defaults are decided.

:func:`bladefem.builders.detect.read_model` chooses the reader by extension and content;
:func:`bladefem.builders.openfast_fst.read_openfast_deck` reads a whole OpenFAST deck (AeroDyn, airfoil polars,
InflowWind, ServoDyn onto the aerodynamic and control records). :mod:`.section6x6` holds every six-by-six blade
(BeamDyn's axes) and gives the FE its sections: whole by default, through the one mapping of :mod:`.section_axes`
onto bladefem's :class:`~bladefem.sections.FullSections`, or reduced to bladefem's diagonal section with the notes
on what that drops (``sections="reduced"``); :mod:`.beamdyn`, :mod:`.hawc2` and :mod:`.windio_model` map those
formats' records onto a :class:`~bladefem.sections.Blade`.
"""

__all__: list[str] = []
