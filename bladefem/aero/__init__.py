"""Blade aerodynamics: airfoil polars and quasi-steady blade-element momentum theory (BEM).

Layer: above :mod:`bladefem.sections`, below the models; nothing here imports a model or a reader. The node solver
(:func:`bladefem.aero.bem.node_loads`, Ning's guaranteed-convergence method in the inflow angle) is compiled with
numba when it is installed; :func:`rotor_performance` evaluates a rigid rotor in steady, optionally sheared wind.
SI units inside; rpm and degrees only in :func:`rotor_performance`'s arguments.
"""

from .options import BEMOptions
from .performance import RotorPerformance, rotor_performance
from .polars import Polar, PolarTable, pack_polars
from .rotor import Inflow, Rotor

__all__ = ["BEMOptions", "Inflow", "Polar", "PolarTable", "Rotor", "RotorPerformance", "pack_polars",
           "rotor_performance"]
