"""Builders: records read from files onto bladefem's models (:class:`~bladefem.sections.Blade`,
:class:`~bladefem.sections.tower.Tower`, the turbine's parameters, the rotor's aerodynamics). This is the one place
where axes, units, reductions and defaults are decided.

:func:`bladefem.builders.detect.read_model` chooses the reader by extension and content;
:func:`bladefem.builders.openfast_fst.read_openfast_deck` reads a whole OpenFAST deck (AeroDyn, airfoil polars,
InflowWind, ServoDyn onto the aerodynamic and control records). :mod:`.section6x6` reduces a six-by-six section
(BeamDyn's axes) to bladefem's diagonal section and names what it drops; :mod:`.beamdyn` and :mod:`.hawc2` map those
formats' records onto a :class:`~bladefem.sections.Blade`; :mod:`.section_axes` maps six-by-six sections in
BeamDyn's axes onto bladefem's :class:`~bladefem.sections.FullSections` (the whole section in the FE).
"""

__all__: list[str] = []
