"""Records onto models: the one place where axes, units and reductions are decided.

:mod:`.section6x6` reduces a six-by-six section (BeamDyn's axes) to bladefem's diagonal section and names what it
drops; :mod:`.beamdyn` and :mod:`.hawc2` map those formats' records onto a :class:`~bladefem.sections.Blade`.
"""
