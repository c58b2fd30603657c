"""A cold first --simulate compiles the aerodynamic loads and the integrator in a helper process
(:mod:`bladefem.models.turbine.parallel_compile`) while this one compiles the structural equations, the output row and
the state rate (the integrator calls them as first-class functions, :mod:`bladefem.models.turbine.compiled_calls`):
this process then loads them from numba's cache instead of compiling them; the output is the same to the bit as with everything
compiled in one process (the helper failing, which falls back to that); a warm run starts no helper; every kernel is
compiled for one argument-type signature (what lets the two processes write the cache without clashing); at the
command's LLVM optimization level (``NUMBA_OPT=1``) the output is the same to the bit as at numba's default."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("numba")

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"
SCRIPT = """
import json, sys
from pathlib import Path
from bladefem.models.turbine import parallel_compile
parallel_compile.spare_core = lambda: True    # whatever the machine's load
if sys.argv[3] == "broken":                   # the helper imports another bladefem than this one: it refuses
    parallel_compile.PACKAGE = Path(sys.argv[1]).parent / "elsewhere"
from bladefem.cli import main
code = main(["turbine", sys.argv[1], "--simulate", "0.05", "--wind-speed", "11.4", "--quiet", "--output", sys.argv[2]])
from numba.core.registry import CPUDispatcher
kernels = [value for name, module in list(sys.modules.items()) if name.startswith("bladefem")
           for value in vars(module).values() if isinstance(value, CPUDispatcher)]
from bladefem.models.turbine.compiled_loads import add_aero
print(json.dumps({"code": code, "helpers": len(parallel_compile.STARTED),
                  "hits": sum(add_aero.stats.cache_hits.values()), "misses": sum(add_aero.stats.cache_misses.values()),
                  "signatures": max(len(kernel.signatures) for kernel in kernels)}))
"""


def simulate(folder: Path, cache: Path, mode: str = "", optimization: str = "3") -> tuple[dict, bytes, str]:
    """One ``--simulate 0.05`` in a subprocess with numba's cache in ``cache`` at LLVM's ``optimization`` level
    (``NUMBA_OPT``): its report, output file, stderr."""
    env = {**os.environ, "PYTHONPATH": str(ROOT), "NUMBA_CACHE_DIR": str(cache), "NUMBA_OPT": optimization}
    for name in ("BLADEFEM_NO_NUMBA", "BLADEFEM_COMPILE_HELPER"):
        env.pop(name, None)
    output = folder / f"out{len(list(folder.glob('out*')))}.csv"
    run = subprocess.run([sys.executable, "-c", SCRIPT, str(DECK), str(output), mode], cwd=folder, env=env,
                         capture_output=True, text=True, timeout=900)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout.splitlines()[-1]), output.read_bytes(), run.stderr


@pytest.mark.slow
def test_cold_run_compiles_on_two_processes_with_the_same_result(tmp_path):
    cold, parallel, stderr = simulate(tmp_path, tmp_path / "cache")
    assert "compiling the turbine simulation kernels" in stderr
    # the helper compiled the aerodynamic loads; this process loaded them from the cache
    assert (cold["code"], cold["helpers"], cold["hits"], cold["misses"]) == (0, 1, 1, 0)
    assert cold["signatures"] == 1
    warm, again, stderr = simulate(tmp_path, tmp_path / "cache")
    assert "compiling" not in stderr
    # loaded from the cache on its own: the integrator calls it as a first-class function (compiled_calls)
    assert (warm["code"], warm["helpers"], warm["hits"], warm["misses"]) == (0, 0, 1, 0)
    assert again == parallel
    # a helper that fails: this process compiles the aerodynamic loads itself, with the same result
    alone, serial, stderr = simulate(tmp_path, tmp_path / "other", "broken")
    assert (alone["code"], alone["helpers"], alone["hits"], alone["misses"]) == (0, 1, 0, 1)
    assert alone["signatures"] == 1
    assert serial == parallel
    # compiled at the command's optimization level (bladefem.cli.NUMBA_OPTIMIZATION): the same table to the bit
    from bladefem.cli import NUMBA_OPTIMIZATION
    _, optimized, _ = simulate(tmp_path, tmp_path / "level", optimization=NUMBA_OPTIMIZATION)
    assert optimized == parallel


def test_helper_only_where_a_core_looks_free(monkeypatch, tmp_path):
    from bladefem.models.turbine import parallel_compile
    monkeypatch.setenv("BLADEFEM_COMPILE_HELPER", "0")
    assert not parallel_compile.spare_core()
    monkeypatch.setenv("BLADEFEM_COMPILE_HELPER", "1")
    assert parallel_compile.spare_core()
    monkeypatch.delenv("BLADEFEM_COMPILE_HELPER")
    monkeypatch.setattr(parallel_compile.os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    # where the idle time cannot be read: the last minute's load average
    monkeypatch.setattr(parallel_compile, "PROC_STAT", str(tmp_path / "missing"))
    monkeypatch.setattr(parallel_compile.os, "getloadavg", lambda: (1.5, 0.0, 0.0))
    assert not parallel_compile.spare_core()
    monkeypatch.setattr(parallel_compile.os, "getloadavg", lambda: (0.9, 0.0, 0.0))
    assert parallel_compile.spare_core()
    monkeypatch.setattr(parallel_compile.os, "sched_getaffinity", lambda pid: {0}, raising=False)
    assert not parallel_compile.spare_core()


def proc_stat(idle0: float, idle1: float, busy0: float, busy1: float) -> str:
    """A /proc/stat with cpu0 and cpu1 (and a cpu2 outside this process's cores, always busy)."""
    def line(name, idle, busy):
        return f"{name} {busy:.0f} 0 0 {idle:.0f} 0 0 0 0 0 0"
    return "\n".join([line("cpu", idle0 + idle1, busy0 + busy1 + 1e6), line("cpu0", idle0, busy0),
                      line("cpu1", idle1, busy1), line("cpu2", 0, 1e6), "intr 1 2 3"])


@pytest.mark.parametrize("idle_share, spare", [((1.0, 1.0), True), ((1.0, 0.1), True), ((0.7, 0.3), True),
                                                 ((0.5, 0.3), False),
                                                 ((0.0, 0.0), False)])
def test_the_idle_time_now_decides_not_the_load_average(monkeypatch, tmp_path, idle_share, spare):
    """A load average of 1.5 (a previous run's, say) but both cores idle now: the helper starts; the idle time of
    this process's own cores (cpu0 and cpu1 of three) over the sample, one core's worth or more, decides."""
    from bladefem.models.turbine import parallel_compile
    monkeypatch.delenv("BLADEFEM_COMPILE_HELPER", raising=False)
    monkeypatch.setattr(parallel_compile.os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    monkeypatch.setattr(parallel_compile.os, "getloadavg", lambda: (0.0 if not spare else 1.5, 0.0, 0.0))
    stat = tmp_path / "stat"
    stat.write_text(proc_stat(1000, 1000, 5000, 5000))
    monkeypatch.setattr(parallel_compile, "PROC_STAT", str(stat))
    later = proc_stat(1000 + 20 * idle_share[0], 1000 + 20 * idle_share[1], 5000 + 20 * (1 - idle_share[0]),
                      5000 + 20 * (1 - idle_share[1]))
    monkeypatch.setattr(parallel_compile.time, "sleep", lambda seconds: stat.write_text(later))
    assert parallel_compile.idle_cores([0, 1]) == pytest.approx(sum(idle_share))
    stat.write_text(proc_stat(1000, 1000, 5000, 5000))
    assert parallel_compile.spare_core() is spare


def test_a_kernel_failing_ahead_is_left_to_the_call(monkeypatch):
    """Compiling ahead only saves time: a kernel that fails there (or types it cannot name) raises nothing; the call
    that follows compiles it and reports its error as it would without the helper."""
    from bladefem.models.turbine import parallel_compile

    def fail(jobs):
        raise TypeError("cannot type")

    monkeypatch.setattr(parallel_compile, "spare_core", lambda: True)
    monkeypatch.setattr(parallel_compile, "start_helper", lambda jobs: None)
    monkeypatch.setattr(parallel_compile, "signatures", lambda loaded, work: dict.fromkeys(("aero", "structure",
                                                                                            "state", "row", "rate"),
                                                                                           ()))
    monkeypatch.setattr(parallel_compile, "compile_kernels", fail)
    assert parallel_compile.compile_in_parallel("integrator", (), ()) is None
    monkeypatch.setattr(parallel_compile, "signatures", fail)
    assert parallel_compile.compile_in_parallel("integrator", (), ()) is None


def test_no_second_helper_for_kernels_this_process_holds(monkeypatch):
    """A later entry point (the outputs after the integrator, the derivative after the outputs) starts no helper
    for kernels an earlier one already compiled or loaded in this process."""
    from bladefem.models.turbine import parallel_compile
    started = []
    monkeypatch.setattr(parallel_compile, "spare_core", lambda: True)
    monkeypatch.setattr(parallel_compile, "start_helper", lambda jobs: started.append(jobs))
    monkeypatch.setattr(parallel_compile, "signatures", lambda loaded, work: dict.fromkeys(("aero", "structure",
                                                                                            "state", "row", "rate"),
                                                                                           ()))
    monkeypatch.setattr(parallel_compile, "compile_kernels", lambda jobs: None)
    monkeypatch.setattr(parallel_compile, "ready", lambda module, name, types: True)
    parallel_compile.compile_in_parallel("derivative", (), ())
    assert started == []
    monkeypatch.setattr(parallel_compile, "ready", lambda module, name, types: False)
    parallel_compile.compile_in_parallel("derivative", (), ())
    assert [[name for _, name, _ in jobs] for jobs in started] == [["add_aero"]]


@pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="the compiled path needs numba")
@pytest.mark.parametrize("refusal", ["types", "compile"])
def test_without_first_class_functions_the_kernels_are_linked(monkeypatch, tmp_path, capsys, refusal):
    """numba marks its first-class function types experimental: where a numba cannot make them (``types``) or
    compile a kernel taking them (``compile``), the integrator is compiled with its kernels linked in, as before
    them, and the run's table is the same to the last digit."""
    from numba.core.errors import TypingError

    from bladefem.cli import main
    from bladefem.models.turbine import compiled_calls

    deck = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"

    def table(name: str) -> str:
        out = tmp_path / f"{name}.csv"
        assert main(["turbine", str(deck), "--simulate", "0.5", "--wind-speed", "11.4", "--quiet", "-o",
                     str(out)]) == 0
        return out.read_text()

    joined = table("joined")

    def refuse(*args, **kwargs):
        raise TypingError("this numba has no first-class function types")

    monkeypatch.setattr(compiled_calls, "integrator_types" if refusal == "types" else "integrator", refuse)
    used = []
    original = compiled_calls.linked
    monkeypatch.setattr(compiled_calls, "linked",
                        lambda kernel, *rest: used.append(kernel) or original(kernel, *rest))
    assert table("linked") == joined
    assert "dp54_chunk" in {kernel.py_func.__name__ for kernel in used}          # the integrator, linked


@pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="the compiled path needs numba")
def test_the_controlled_loop_falls_back_to_linked_kernels(monkeypatch, tmp_path):
    """The same fallback for the controlled loop (ROSCO's library called from the kernel) and the output rows and
    derivative it starts with: where numba cannot compile a kernel taking the function types, each is compiled with
    its kernels linked in, and the table is the same to the last digit."""
    from numba.core.errors import TypingError

    from bladefem.cli import main
    from bladefem.models.turbine import compiled_calls

    deck = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ROSCO.fst"

    def table(name: str) -> str:
        out = tmp_path / f"{name}.csv"
        assert main(["turbine", str(deck), "--simulate", "0.2", "--wind-speed", "16", "--pitch-deg", "10", "--quiet",
                     "-o", str(out)]) == 0
        return out.read_text()

    joined = table("joined")

    def refuse(*args, **kwargs):
        raise TypingError("this numba cannot compile kernels taking first-class functions")

    monkeypatch.setattr(compiled_calls, "integrator", refuse)
    used = []
    original = compiled_calls.linked
    monkeypatch.setattr(compiled_calls, "linked",
                        lambda kernel, *rest: used.append(kernel) or original(kernel, *rest))
    assert table("linked") == joined
    assert {"controlled_chunk", "load_outputs", "rate_function"} <= {kernel.py_func.__name__ for kernel in used}


def test_prestart_only_for_a_cold_cache_and_once(monkeypatch):
    """``turbine --simulate`` starts the helper before it builds the model only when the aerodynamic loads have
    nothing in numba's cache and a core looks free, once; the first compiled call then gives that helper its jobs
    instead of starting another."""
    from bladefem.models.turbine import parallel_compile
    launched, sent = [], []
    monkeypatch.setattr(parallel_compile, "EARLY", [])
    monkeypatch.setattr(parallel_compile, "launch", lambda: launched.append("helper") or "helper")
    monkeypatch.setattr(parallel_compile, "send", lambda helper, jobs: sent.append((helper, jobs)) or None)
    monkeypatch.setattr(parallel_compile.atexit, "register", lambda *args: None)
    monkeypatch.setattr(parallel_compile, "spare_core", lambda: True)
    monkeypatch.setattr(parallel_compile, "cold", lambda: False)
    parallel_compile.prestart()
    assert launched == [] and parallel_compile.EARLY == []
    monkeypatch.setattr(parallel_compile, "cold", lambda: True)
    monkeypatch.setattr(parallel_compile, "spare_core", lambda: False)
    parallel_compile.prestart()
    assert launched == []
    monkeypatch.setattr(parallel_compile, "spare_core", lambda: True)
    parallel_compile.prestart()
    parallel_compile.prestart()
    assert launched == ["helper"] and parallel_compile.EARLY == ["helper"]
    monkeypatch.setattr(parallel_compile, "spare_core", lambda: False)    # busy now: the helper is there already
    monkeypatch.setattr(parallel_compile, "signatures", lambda loaded, work: dict.fromkeys(("aero", "structure",
                                                                                            "state", "row", "rate"),
                                                                                           ()))
    monkeypatch.setattr(parallel_compile, "compile_kernels", lambda jobs: None)
    monkeypatch.setattr(parallel_compile, "ready", lambda module, name, types: False)
    parallel_compile.compile_in_parallel("integrator", (), ())
    assert launched == ["helper"] and [(helper, [name for _, name, _ in jobs]) for helper, jobs in sent] == [
        ("helper", ["add_aero"])]
    assert parallel_compile.EARLY == []


def test_a_helper_given_no_jobs_exits():
    """A helper whose caller sends nothing (it needed no compilation, or failed before) warms up, reads the end of
    its stdin and exits cleanly."""
    from bladefem.models.turbine import parallel_compile
    helper = parallel_compile.launch()
    assert helper is not None
    helper.stdin.close()
    assert helper.wait(timeout=120) == 0
