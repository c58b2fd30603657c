"""Cost growth: time and memory of one modal solve and of a 16-speed Campbell sweep of the NREL 5MW blade against
the element count (50 to 3200 elements), with the fitted exponents against the number of DOFs.

Run: ``python bench/bench_scaling.py [--plot docs/performance.png]``. Each size runs in its own process (its peak
memory is that process's); times are the smallest CPU time of a few repeats, BLAS on one thread. Prints a
Markdown table for docs/performance.md.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse  # noqa: E402
import json  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
ELEMENTS = (50, 100, 200, 400, 800, 1600, 3200)
CHILD = """
import json, resource, sys, time
import numpy as np
from bladefem.builders.case import read_case
from bladefem.assembly import assemble_blade
from bladefem.modal import campbell_sweep, solve_modes
blade = read_case(sys.argv[1]); elements = int(sys.argv[2]); rpm = np.linspace(0, 15, 16)
def best(function, repeats=3):
    times = []
    for _ in range(repeats):
        start = time.process_time(); function(); times.append(time.process_time() - start)
    return min(times)
baseline = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
assembly = best(lambda: assemble_blade(blade, elements))
solve = best(lambda: solve_modes(assemble_blade(blade, elements), 12.1, 10)) - assembly
sweep = best(lambda: campbell_sweep(assemble_blade(blade, elements), rpm, 6)) - assembly
matrices = assemble_blade(blade, elements)
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(json.dumps({"elements": len(matrices.dofs.nodes) - 1, "dofs": len(matrices.free), "assembly": assembly,
                  "solve": solve, "campbell": sweep, "memory_mb": (peak - baseline) / 1024}))
"""


def measure(elements: int) -> dict:
    done = subprocess.run([sys.executable, "-c", CHILD, str(ROOT / "cases" / "nrel5mw_blade.yaml"), str(elements)],
                          check=True, capture_output=True, text=True)
    return json.loads(done.stdout)


def exponent(dofs: np.ndarray, values: np.ndarray) -> float:
    """Slope of log(value) against log(DOFs) over the larger half of the sizes (overheads dominate below)."""
    half = len(dofs) // 2
    return float(np.polyfit(np.log(dofs[half:]), np.log(values[half:]), 1)[0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plot", metavar="FILE.png", help="write the log-log figure")
    args = parser.parse_args()
    rows = [measure(n) for n in ELEMENTS]
    dofs = np.array([row["dofs"] for row in rows], dtype=float)
    print("| elements | free DOFs | assembly (ms) | one solve, 10 modes (ms) | Campbell sweep, 16 speeds (ms) | "
          "peak memory (MB) |")
    print("|---|---|---|---|---|---|")
    for row in rows:
        print(f"| {row['elements']} | {row['dofs']} | {row['assembly'] * 1e3:.1f} | {row['solve'] * 1e3:.1f} | "
              f"{row['campbell'] * 1e3:.1f} | {row['memory_mb']:.1f} |")
    fits = {name: exponent(dofs, np.array([row[name] for row in rows])) for name in ("assembly", "solve", "campbell")}
    print("fitted exponents (time ~ DOFs^p, larger half): " + ", ".join(f"{k} {v:.2f}" for k, v in fits.items()))
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        figure, (times, memory) = plt.subplots(1, 2, figsize=(10, 4))
        for name, label in (("assembly", "assembly"), ("solve", "one solve, 10 modes"),
                            ("campbell", "Campbell sweep, 16 speeds")):
            times.loglog(dofs, [row[name] * 1e3 for row in rows], "o-", label=f"{label} (p = {fits[name]:.2f})")
        times.loglog(dofs, dofs / dofs[0] * rows[0]["solve"] * 1e3, "k:", label="linear in DOFs")
        times.set_xlabel("free DOFs")
        times.set_ylabel("CPU time (ms)")
        times.legend(fontsize=8)
        memory.loglog(dofs, [max(row["memory_mb"], 0.1) for row in rows], "o-")
        memory.set_xlabel("free DOFs")
        memory.set_ylabel("peak memory above start (MB)")
        figure.suptitle("NREL 5MW blade: cost against mesh size")
        figure.tight_layout()
        figure.savefig(args.plot, dpi=100)
        print(f"figure written to {args.plot}")


if __name__ == "__main__":
    main()
