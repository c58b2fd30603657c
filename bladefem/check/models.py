"""The models of a spec, solved once each: modes at single speeds and the Campbell sweep over the operating range,
with every mode and family named by kind and number ('flap 1', 'edge 1', 'flap 2', 'fore-aft 1', ...)."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..builders.detect import Geometry, detect_format, read_model
from ..builders.tower_case import is_tower_case, read_tower_case
from ..builders.tower_elastodyn import elastodyn_tower
from ..modal.results import ModalResult, Mode
from ..sections import Blade
from .spec import ModelSpec


def read_structure(path: Path, elastodyn_main: Path | None = None, geometry: dict[str, float] | None = None):
    """The blade or tower an input file describes, with geometry overrides (SI: tip_radius, hub_radius, precone,
    pitch, tip_mass)."""
    kind = detect_format(path)
    if kind == "case" and is_tower_case(path):
        return read_tower_case(path)
    if kind == "elastodyn-tower" and elastodyn_main is not None:
        return elastodyn_tower(elastodyn_main)
    return read_model(path, None, Geometry(elastodyn_main=elastodyn_main, **(geometry or {})))


def ordinal_names(kinds: list[str]) -> list[str]:
    """'flap 1', 'edge 1', 'flap 2', ... for kinds listed in frequency order."""
    counts: dict[str, int] = {}
    names = []
    for kind in kinds:
        counts[kind] = counts.get(kind, 0) + 1
        names.append(f"{kind} {counts[kind]}")
    return names


@dataclass(frozen=True)
class Curve:
    """A named mode family over rotor speed: frequency (Hz) at each speed (rpm)."""

    name: str
    rpm: NDArray[np.float64]
    frequency_hz: NDArray[np.float64]


@dataclass
class ModelRun:
    """A spec model, read once, with its solutions computed on first use and kept."""

    spec: ModelSpec
    _modes: dict[float, ModalResult] = field(default_factory=dict)

    @cached_property
    def structure(self) -> object:
        """The blade or tower the model's input describes (with the spec's geometry overrides)."""
        return read_structure(self.spec.input, self.spec.elastodyn_main, self.spec.geometry)

    @property
    def is_blade(self) -> bool:
        return isinstance(self.structure, Blade)

    def modes(self, rpm: float = 0.0, n_modes: int | None = None) -> ModalResult:
        """Modes at rotor speed ``rpm`` (rpm); a tower's modes do not depend on it."""
        key = float(rpm) if self.is_blade else 0.0
        if key not in self._modes:
            count = max(n_modes or 0, self.spec.n_modes)
            if self.is_blade:
                from ..modal import modes
                self._modes[key] = modes(self.structure, key, count, self.spec.elements)
            else:
                from ..models.tower import tower_modes
                self._modes[key] = tower_modes(self.structure, count, self.spec.elements)
        return self._modes[key]

    def named_modes(self, rpm: float = 0.0, n_modes: int | None = None) -> dict[str, Mode]:
        result = self.modes(rpm, n_modes)
        return dict(zip(ordinal_names(result.kinds), result.modes))

    @cached_property
    def operating_speeds(self) -> NDArray[np.float64]:
        low, high = self.spec.operating_rpm  # type: ignore[misc]
        return np.linspace(low, high, self.spec.rpm_points)

    @cached_property
    def curves(self) -> dict[str, Curve]:
        """Mode families over the operating range, tracked by MAC (blades) or constant (towers)."""
        speeds = self.operating_speeds
        if not self.is_blade:
            result = self.modes()
            return {name: Curve(name, speeds, np.full(len(speeds), mode.frequency_hz))
                    for name, mode in zip(ordinal_names(result.kinds), result.modes)}
        from ..modal import campbell
        sweep = campbell(self.structure, speeds, self.spec.n_modes, self.spec.elements)
        names = ordinal_names([family.kind for family in sweep.families])
        return {name: Curve(name, speeds, family.frequencies_hz) for name, family in zip(names, sweep.families)}

    def curve(self, name: str) -> Curve:
        """The family ``name`` over the operating range; LookupError names the families there are."""
        if name not in self.curves:
            raise LookupError(f"no mode '{name}' among the {len(self.curves)} families of model "
                              f"'{self.spec.name}' ({', '.join(self.curves)}); raise its n_modes")
        return self.curves[name]

    def mode(self, name: str, rpm: float) -> Mode:
        """The mode ``name`` at ``rpm`` (rpm); LookupError names the modes there are."""
        named = self.named_modes(rpm)
        if name not in named:
            raise LookupError(f"no mode '{name}' among the {len(named)} modes of model '{self.spec.name}' at "
                              f"{rpm:g} rpm ({', '.join(named)}); raise its n_modes")
        return named[name]
