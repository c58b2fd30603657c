"""bladefem: finite-element natural frequencies and mode shapes of rotating wind-turbine blades and towers.

The three calls most scripts need, for blades and towers alike::

    import bladefem
    model = bladefem.read("cases/nrel5mw_tower.yaml")     # any input format: a Blade or a Tower
    result = bladefem.modes(model)                        # ModalResult: frequencies_hz, kinds, modes
    chart = bladefem.campbell(model, rpm=range(16))       # blade: CampbellResult; tower: TowerCampbell

Importing bladefem is light: the numerical modules load when these functions first run.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

__version__ = "0.1.0"
__all__ = ["__version__", "campbell", "modes", "read"]


def read(path: str | Path, part: str | None = None, **geometry: Any) -> Any:
    """The blade (:class:`bladefem.sections.Blade`) or tower (:class:`bladefem.sections.tower.Tower`) described by
    a file in any supported format; ``part`` ('blade' or 'tower') chooses for files holding both (an ElastoDyn main
    file, windIO). ``geometry``: options for files that lack it, SI units (``tip_radius=63.0``,
    ``elastodyn_main="main.dat"``; see :class:`bladefem.builders.detect.Geometry`)."""
    from .builders.detect import read_model
    from .sections import Blade
    from .sections.tower import as_tower

    model = read_model(path, part, **geometry)
    return model if isinstance(model, Blade) else as_tower(model)


def _is_blade(model: Any) -> bool:
    from .sections import Blade
    return isinstance(model, Blade)


def modes(model: Any, rpm: float = 0.0, n_modes: int = 10, elements: int | None = None) -> Any:
    """Natural frequencies and mode shapes (:class:`bladefem.modal.ModalResult`) of a blade at rotor speed ``rpm``
    (rpm), or of a tower (which does not rotate: ``rpm`` must be 0). ``elements``: target number of elements, or
    None for a mesh refined until the frequencies converge to 1e-6."""
    if _is_blade(model):
        from .modal import modes as blade_modes
        return blade_modes(model, rpm, n_modes, elements)
    if rpm != 0:
        raise ValueError(f"a tower does not rotate: rpm must be 0, got {rpm} (bladefem.campbell(tower, rpm) draws "
                         "its frequencies against the rotor's excitation bands)")
    from .limits import check_elements, check_n_modes
    from .models.tower import tower_modes
    return tower_modes(model, check_n_modes(n_modes), check_elements(elements))


def campbell(model: Any, rpm: Sequence[float], n_modes: int = 6, elements: int | None = None,
             operating_rpm: tuple[float, float] | None = None, blades: int = 3) -> Any:
    """Modes over rotor speeds ``rpm`` (rpm). A blade: mode families tracked by MAC
    (:class:`bladefem.modal.CampbellResult`). A tower: its frequencies against the rotor's 1P and blade-passing
    bands over ``operating_rpm`` (low, high; default the swept range) with the soft-stiff classification
    (:class:`bladefem.models.tower_campbell.TowerCampbell`)."""
    if _is_blade(model):
        from .modal import campbell as blade_campbell
        return blade_campbell(model, rpm, n_modes, elements)
    from .limits import check_elements, check_n_modes, check_speeds
    from .models.tower_campbell import tower_campbell
    speeds = check_speeds(rpm, check_n_modes(n_modes), check_elements(elements))
    return tower_campbell(model, speeds, n_modes, elements, operating_rpm, blades)
