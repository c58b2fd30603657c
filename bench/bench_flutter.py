"""Benchmark: a 30-speed flutter sweep of the IEA-15MW blade (BeamDyn six-by-six sections, full), 6 tracked modes,
rotor speed 3 to 20 rpm in still air, with the IEA-15MW deck's AeroDyn blade and the polars of tests/deck_copies.py
(all 50 polars stored).

    python bench/bench_flutter.py

Prints the wall time of the sweep alone (mesh and matrices assembled once before it) and of the whole command.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")        # as the other benchmarks: BLAS on one thread
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from deck_copies import deck_copy  # noqa: E402

from bladefem.builders.aerodyn_rotor import aerodyn_rotor  # noqa: E402
from bladefem.builders.detect import Geometry, read_model  # noqa: E402
from bladefem.builders.flutter_inputs import REPLACED  # noqa: E402
from bladefem.modal import blade_matrices  # noqa: E402
from bladefem.models.flutter import OperatingCondition, flutter_sweep  # noqa: E402


def main() -> None:
    with tempfile.TemporaryDirectory() as folder:
        deck = deck_copy("iea15", Path(folder))
        aerodyn = deck / "IEA-15-240-RWT-Monopile" / "IEA-15-240-RWT-Monopile_AeroDyn15.dat"
        blade = read_model(ROOT / "tests/data/iea15/beamdyn/IEA-15-240-RWT_BeamDyn.dat", None,
                           Geometry(hub_radius=3.97))
        rotor = aerodyn_rotor(aerodyn, blade, 3, replaced=REPLACED)
        from dataclasses import replace
        rotor = replace(rotor, options=replace(rotor.options, induction=False))
        start, cpu_start = time.perf_counter(), time.process_time()
        matrices = blade_matrices(blade, None, 6, 20.0)
        assembled, cpu_assembled = time.perf_counter(), time.process_time()
        sweep = [OperatingCondition(0.0, rpm * np.pi / 30, blade.pitch) for rpm in np.linspace(3, 20, int(sys.argv[1]) if len(sys.argv) > 1 else 30)]
        result = flutter_sweep(matrices, rotor, sweep, 6)
        done, cpu_done = time.perf_counter(), time.process_time()
    print(f"IEA-15MW blade, {len(matrices.free)} free DOFs, {len(sweep)} speeds x 6 modes: sweep "
          f"{done - assembled:.2f} s wall, {cpu_done - cpu_assembled:.2f} s CPU; with mesh and matrices "
          f"{done - start:.2f} s wall, {cpu_done - cpu_start:.2f} s CPU; onset "
          f"{'none' if result.onset is None else f'{result.onset.rpm:.2f} rpm'}")


if __name__ == "__main__":
    main()
