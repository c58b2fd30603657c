"""The table ``bladefem turbine --simulate -o FILE`` writes, read back by channel name (units cut off)."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def table(path: Path) -> dict[str, np.ndarray]:
    """Each column of the CSV table at ``path`` under its channel name without the unit suffix (``GenPwr_kW`` ->
    ``GenPwr``)."""
    lines = path.read_text().splitlines()
    names = [name.rsplit("_", 1)[0] for name in lines[0].split(",")]
    data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    return {name: data[:, i] for i, name in enumerate(names)}
