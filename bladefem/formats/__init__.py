"""File formats read into plain typed records and written back (no physics, no model building).

One module per format: :mod:`.beamdyn` (BeamDyn primary and blade files), :mod:`.hawc2_st` (HAWC2 structural
``.st`` files, isotropic and fully populated layouts), :mod:`.hawc2_htc` (the ``c2_def`` reference axis and the
``timoschenko_input`` of a HAWC2 main body). Mapping records onto bladefem's models is :mod:`bladefem.builders`.
"""
