"""Benchmark: the NREL 5MW blade's converged 16-speed Campbell diagram (0-15 rpm), in-process and as a whole CLI
process, side by side with pybmodes (its ``campbell_sweep`` at 96 elements on its own NREL 5MW deck) in one run.

Run: ``python bench/bench_blade.py [--compare-pybmodes] [--repeats N]``. Installs nothing: without pybmodes the
comparison is skipped. Each figure is the median wall-clock time of interleaved repeats and the smallest CPU time
(the CPU time is what a busy machine disturbs least). BLAS is limited to one thread for both tools (set before
numpy loads): on these small problems OpenBLAS threads only add overhead, and on a loaded machine a lot of it.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse  # noqa: E402
import resource  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from collections.abc import Callable  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
CASE = ROOT / "cases" / "nrel5mw_blade.yaml"
RPM = np.linspace(0.0, 15.0, 16)
N_MODES = 6
#: pybmodes' mesh in the comparison (the issue's figure): 96 elements
PYBMODES_ELEMENTS = 96
PYBMODES_SCRIPT = """
import json, sys, warnings
import numpy as np
from pybmodes.campbell import campbell_sweep
from pybmodes.models import RotatingBlade
warnings.simplefilter("ignore")
result = campbell_sweep(RotatingBlade(sys.argv[1], n_nodes=int(sys.argv[2]) + 1), np.linspace(0, 15, 16), n_blade_modes=6)
print(json.dumps({"frequencies_hz": result.frequencies.tolist()}))
"""


def pybmodes_deck() -> Path | None:
    """pybmodes' NREL 5MW land-based blade deck, or None without pybmodes."""
    try:
        import pybmodes
    except ImportError:
        return None
    return (Path(pybmodes.__file__).parent / "_examples" / "sample_inputs" / "reference_turbines"
            / "01_nrel5mw_land" / "01_nrel5mw_land_blade.bmi")


def timed(functions: dict[str, Callable[[], object]], repeats: int) -> dict[str, tuple[float, float]]:
    """Median wall-clock and smallest CPU time (s) of each function, the functions interleaved repeat by repeat."""
    walls: dict[str, list[float]] = {name: [] for name in functions}
    cpus: dict[str, list[float]] = {name: [] for name in functions}
    for _ in range(repeats):
        for name, function in functions.items():
            wall, cpu = time.perf_counter(), time.process_time()
            function()
            walls[name].append(time.perf_counter() - wall)
            cpus[name].append(time.process_time() - cpu)
    return {name: (statistics.median(walls[name]), min(cpus[name])) for name in functions}


def timed_processes(commands: dict[str, list[str]], repeats: int) -> dict[str, tuple[float, float]]:
    """Median wall-clock and smallest CPU time (user + system of the child) of whole processes, interleaved."""
    walls: dict[str, list[float]] = {name: [] for name in commands}
    cpus: dict[str, list[float]] = {name: [] for name in commands}
    for _ in range(repeats):
        for name, command in commands.items():
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            wall = time.perf_counter()
            subprocess.run(command, check=True, capture_output=True)
            walls[name].append(time.perf_counter() - wall)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpus[name].append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return {name: (statistics.median(walls[name]), min(cpus[name])) for name in commands}


def report(rows: dict[str, tuple[float, float]]) -> None:
    for label, (wall, cpu) in rows.items():
        print(f"  {label:<62} {wall * 1e3:9.1f} ms wall {cpu * 1e3:9.1f} ms CPU")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--compare-pybmodes", action="store_true", help="time pybmodes too (if installed)")
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()

    from bladefem.builders.case import read_case
    from bladefem.modal import campbell, converged_mesh, solve_modes

    blade = read_case(CASE)
    choice = converged_mesh(blade, N_MODES, rpm=float(RPM.max()))
    matrices = choice.matrices
    print(f"NREL 5MW blade ({CASE.name}): automatic mesh of {len(matrices.dofs.nodes) - 1} elements "
          f"({len(matrices.free)} free DOFs), estimated frequency error {choice.error:.1e}")

    functions: dict[str, Callable[[], object]] = {
        "converged Campbell, 16 speeds, 6 families (mesh choice included)": lambda: campbell(blade, RPM, N_MODES),
        "  of which: automatic mesh choice (assemblies and solves)": lambda: converged_mesh(blade, N_MODES, rpm=15.0),
        "one modal solve, 10 modes, 12.1 rpm (chosen mesh, not cached)": lambda: solve_modes(
            converged_mesh(blade, 10, rpm=12.1).matrices, 12.1, 10),
    }
    deck = pybmodes_deck() if args.compare_pybmodes else None
    if args.compare_pybmodes and deck is None:
        print("pybmodes is not installed: comparison skipped (pip install pybmodes)")
    if deck is not None:
        from pybmodes.campbell import campbell_sweep as pybmodes_sweep
        from pybmodes.models import RotatingBlade

        def pybmodes_campbell() -> object:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                return pybmodes_sweep(RotatingBlade(deck, n_nodes=PYBMODES_ELEMENTS + 1), RPM, n_blade_modes=N_MODES)

        functions[f"pybmodes campbell_sweep, {PYBMODES_ELEMENTS} elements, 16 speeds, 6 modes"] = pybmodes_campbell
    print("In-process:")
    rows = timed(functions, args.repeats)
    report(rows)
    if deck is not None:
        ours = rows["converged Campbell, 16 speeds, 6 families (mesh choice included)"]
        theirs = rows[f"pybmodes campbell_sweep, {PYBMODES_ELEMENTS} elements, 16 speeds, 6 modes"]
        print(f"  bladefem faster by {theirs[0] / ours[0]:.1f}x (wall) and {theirs[1] / ours[1]:.1f}x (CPU)")

    commands = {"bladefem campbell cases/nrel5mw_blade.yaml --rpm 0:15:16 --json": [
        sys.executable, "-m", "bladefem", "campbell", str(CASE), "--rpm", "0:15:16", "--json"]}
    if deck is not None:
        commands[f"python -c 'pybmodes campbell_sweep, {PYBMODES_ELEMENTS} elements, print JSON'"] = [
            sys.executable, "-c", PYBMODES_SCRIPT, str(deck), str(PYBMODES_ELEMENTS)]
    print("Whole process (Python start, imports, reading, solving, printing):")
    processes = timed_processes(commands, max(3, args.repeats // 2))
    report(processes)
    if deck is not None:
        ours, theirs = processes.values()
        print(f"  bladefem faster by {theirs[0] / ours[0]:.1f}x (wall) and {theirs[1] / ours[1]:.1f}x (CPU)")
        accuracy(deck, blade)


def accuracy(deck: Path, blade: object) -> None:
    """How far each answer is from its own model's converged frequencies (first 6 at 15 rpm)."""
    from pybmodes.campbell import campbell_sweep as pybmodes_sweep
    from pybmodes.models import RotatingBlade

    from bladefem.assembly import assemble_blade
    from bladefem.modal import campbell, solve_modes

    def theirs(elements: int) -> np.ndarray:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sweep = pybmodes_sweep(RotatingBlade(deck, n_nodes=elements + 1), RPM[-1:], n_blade_modes=N_MODES)
        return np.sort(sweep.frequencies[-1])

    ours = np.sort([family.frequencies_hz[-1] for family in campbell(blade, RPM, N_MODES).families])
    reference = solve_modes(assemble_blade(blade, 1600), 15.0, N_MODES).frequencies_hz
    print("Accuracy at 15 rpm, largest relative deviation of the first 6 frequencies from the model's converged ones:")
    print(f"  bladefem automatic mesh against 1600 elements: {np.max(np.abs(ours / reference - 1)):.1e}")
    print(f"  pybmodes {PYBMODES_ELEMENTS} elements against its 768 elements: "
          f"{np.max(np.abs(theirs(PYBMODES_ELEMENTS) / theirs(768) - 1)):.1e}")


if __name__ == "__main__":
    main()
