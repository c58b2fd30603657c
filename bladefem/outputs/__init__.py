"""Written results: JSON of modal results and Campbell sweeps (:mod:`.results`), mode shapes as VTK for ParaView
(:mod:`.vtk`, geometry in :mod:`.vtk_geometry`)."""

__all__: list[str] = []
