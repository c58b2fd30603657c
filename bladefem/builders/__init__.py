"""Records onto models: the one place where axes, units and reductions are decided.

:mod:`.section_axes` maps six-by-six sections in BeamDyn's axes onto bladefem's
:class:`~bladefem.sections.FullSections`.
"""
