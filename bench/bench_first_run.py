"""Benchmark: the first ``--simulate`` of a fresh install (numba compiles the simulation kernels) and a warm one.

Run from the repository root::

    python bench/bench_first_run.py [--repeat 3] [--seconds 20]

Each repeat starts ``bladefem turbine cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst --simulate 20 --wind-speed
11.4`` in a subprocess with an empty numba cache (``NUMBA_CACHE_DIR`` a fresh temporary folder: a cold first run,
compilation included), then again with that cache filled (a warm run: the machine code loaded from disk). Wall
time and the child's CPU time (user + system) are printed, with the load average: on a shared machine the wall
time of the cold run follows the load, the CPU time much less. Prints a Markdown table. The CPU time includes the
helper process that compiles the aerodynamic loads on the second core (``parallel_compile``).

``--compare`` instead alternates, per repeat, a cold run compiling on two processes and one compiling everything in
its process (``BLADEFEM_COMPILE_HELPER=1`` and ``0``; unset, a helper starts only where a core looks free), and with
``--against PATH`` a cold run of another checkout (say the main branch's) as a user runs it, their order rotated every
repeat, so that all see the same load.

``--profile`` instead runs one cold run in a subprocess that listens to numba's compile events and prints, per
compiled function, the compile time spent in it but not in the functions it calls (numba typing and lowering, and
LLVM for its library with the callees linked in), and how many functions (signatures) were compiled.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"


def run(cache: str, seconds: float, output: str, helper: str | None = None, root: Path = ROOT
        ) -> tuple[float, float]:
    """(wall, CPU) seconds of one ``--simulate`` in a subprocess with the numba cache in ``cache`` (its helper
    process included), the bladefem of the checkout ``root``; ``helper``: BLADEFEM_COMPILE_HELPER ("0": every
    kernel compiled in that process, "1": a helper always started, None: as a user's run, a helper where a core
    looks free)."""
    env = {**os.environ, "NUMBA_CACHE_DIR": cache, "PYTHONPATH": str(root)}
    env.pop("BLADEFEM_NO_NUMBA", None)
    env.pop("BLADEFEM_COMPILE_HELPER", None)
    if helper is not None:
        env["BLADEFEM_COMPILE_HELPER"] = helper
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "bladefem", "turbine", str(DECK), "--simulate", f"{seconds:g}",
                    "--wind-speed", "11.4", "--quiet", "--output", output], cwd=root, env=env, check=True,
                   capture_output=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


PROFILE = """
import collections, sys, time
from numba.core import event
stack, own, count = [], collections.Counter(), collections.Counter()

class Listener(event.Listener):
    def on_start(self, ev):
        stack.append([time.process_time(), 0.0])

    def on_end(self, ev):
        start, inner = stack.pop()
        spent = time.process_time() - start
        name = ev.data["dispatcher"].py_func.__qualname__
        own[name] += spent - inner
        count[name] += 1
        if stack:
            stack[-1][1] += spent

event.register("numba:compile", Listener())
from bladefem.cli import main
main(sys.argv[1:])
for name, spent in own.most_common(12):
    print(f"| {name} | {count[name]} | {spent:.1f} |")
print(f"\\n{sum(count.values())} functions compiled ({len(count)} distinct), {sum(own.values()):.1f} s CPU")
"""


def profile(seconds: float) -> None:
    """One cold run with numba's compile events: CPU seconds per compiled function (its own share)."""
    with tempfile.TemporaryDirectory() as folder:
        env = {**os.environ, "NUMBA_CACHE_DIR": os.path.join(folder, "numba"), "PYTHONPATH": str(ROOT)}
        env.pop("BLADEFEM_NO_NUMBA", None)
        print("| function | signatures | compile CPU [s], callees excluded |\n|---|---|---|", flush=True)
        child = subprocess.run([sys.executable, "-c", PROFILE, "turbine", str(DECK), "--simulate", f"{seconds:g}",
                                "--wind-speed", "11.4", "--quiet", "--output", os.path.join(folder, "out.csv")],
                               cwd=ROOT, env=env, check=True, capture_output=True, text=True)
        print("\n".join(line for line in child.stdout.splitlines() if not line.startswith("#")))


def compare(repeat: int, seconds: float, against: Path | None) -> None:
    """Cold runs with the helper process and without (and of the checkout ``against``, if given), their order
    rotated every repeat: wall and CPU of each, with the load average."""
    variants = [("two processes", "1", ROOT), ("one process", "0", ROOT)]
    if against is not None:
        variants.append((f"{against}", None, against))
    print(f"`--simulate {seconds:g} --wind-speed 11.4`, NREL 5MW deck, {os.cpu_count()} CPUs, cold runs\n")
    print("| run | compiled | wall [s] | CPU [s] | load average |\n|---|---|---|---|---|")
    for i in range(repeat):
        for name, helper, root in variants[i % len(variants):] + variants[:i % len(variants)]:
            with tempfile.TemporaryDirectory() as folder:
                load = os.getloadavg()[0]
                wall, cpu = run(os.path.join(folder, "numba"), seconds, os.path.join(folder, "out.csv"), helper,
                                root)
            print(f"| {i + 1} | {name} | {wall:.1f} | {cpu:.1f} | {load:.1f} |", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=20.0, help="simulated time, s")
    parser.add_argument("--profile", action="store_true", help="compile time per function of one cold run")
    parser.add_argument("--compare", action="store_true", help="cold runs on two processes and in one, alternated")
    parser.add_argument("--against", type=Path, help="with --compare: also cold runs of this other checkout")
    args = parser.parse_args()
    if args.compare:
        compare(args.repeat, args.seconds, args.against)
        return
    if args.profile:
        profile(args.seconds)
        return
    print(f"`--simulate {args.seconds:g} --wind-speed 11.4`, NREL 5MW deck, {os.cpu_count()} CPUs\n")
    print("| run | cold: wall [s] | cold: CPU [s] | warm: wall [s] | warm: CPU [s] | load average |")
    print("|---|---|---|---|---|---|")
    for i in range(args.repeat):
        with tempfile.TemporaryDirectory() as folder:
            cache, output = os.path.join(folder, "numba"), os.path.join(folder, "out.csv")
            load = os.getloadavg()[0]
            cold = run(cache, args.seconds, output)
            warm = run(cache, args.seconds, output)
        print(f"| {i + 1} | {cold[0]:.1f} | {cold[1]:.1f} | {warm[0]:.1f} | {warm[1]:.1f} | {load:.1f} |",
              flush=True)


if __name__ == "__main__":
    main()
