"""Builders: records read from files onto bladefem's models (:class:`~bladefem.sections.Blade`,
:class:`~bladefem.sections.tower.Tower`, the turbine's parameters, the rotor's aerodynamics). This is the one place
where axes, units, reductions and defaults are decided.

:func:`bladefem.builders.detect.read_model` chooses the reader by extension and content;
:func:`bladefem.builders.openfast_fst.read_openfast_deck` reads a whole OpenFAST deck (AeroDyn, airfoil polars,
InflowWind, ServoDyn onto the aerodynamic and control records).
"""

__all__: list[str] = []
