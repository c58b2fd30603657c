"""The ``bladefem`` process (:func:`bladefem.cli.entry`, the console script and ``python -m bladefem``): numba's
optimization level set where the user has not, the command's exit code and its outputs whole although the process
ends without the interpreter's teardown, and the usual ending where other threads still run."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path


ROOT = Path(__file__).resolve().parents[1]


def environment(**extra: str) -> dict[str, str]:
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""), MPLBACKEND="Agg")
    env.pop("NUMBA_OPT", None)
    env.update(extra)
    return env


def entry_with(main_body: str, **extra: str) -> subprocess.CompletedProcess:
    """``entry()`` in a fresh interpreter with ``main`` replaced by ``main_body`` (the body of a function)."""
    script = ("import os, sys, threading, time\nimport bladefem.cli as cli\n"
              "def main():\n" + "".join(f"    {line}\n" for line in main_body.splitlines()) +
              "cli.main = main\ncli.entry()\n")
    return subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=environment(**extra),
                          cwd=ROOT, timeout=600)


def bladefem(*argv: str, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "bladefem", *argv], capture_output=True, text=True,
                          env=environment(), cwd=ROOT, timeout=600, **kwargs)


def test_numba_optimizes_at_level_one_unless_the_user_chose():
    done = entry_with("print(os.environ['NUMBA_OPT'])\nreturn 0")
    assert (done.returncode, done.stdout.strip()) == (0, "1")
    done = entry_with("print(os.environ['NUMBA_OPT'])\nreturn 0", NUMBA_OPT="3")
    assert (done.returncode, done.stdout.strip()) == (0, "3")


def test_the_exit_code_is_the_commands():
    assert entry_with("return 2").returncode == 2
    assert bladefem("modes", "cases/uniform_blade.yaml", "--rpm", "fast").returncode == 2


def test_outputs_are_whole_although_the_interpreter_is_not_torn_down(tmp_path):
    """A run's table on stdout and its files are the same as the same command's ended by the interpreter's usual
    teardown (``raise SystemExit(main())``), each in a fresh process."""
    argv = ["campbell", "cases/nrel5mw_blade.yaml", "--rpm", "0:12:4", "--n-modes", "4", "--json", "--plot"]
    here, there = tmp_path / "here.png", tmp_path / "there.png"
    usual = subprocess.run([sys.executable, "-c", "import sys; from bladefem.cli import main; "
                            "raise SystemExit(main(sys.argv[1:]))", *argv, str(here)], capture_output=True,
                           text=True, env=environment(NUMBA_OPT="1"), cwd=ROOT, timeout=600)
    assert usual.returncode == 0, usual.stderr
    done = bladefem(*argv, str(there))
    assert done.returncode == 0, done.stderr
    assert done.stdout == usual.stdout and usual.stdout.rstrip().endswith("}")
    assert there.read_bytes() == here.read_bytes()
    lots = entry_with("sys.stdout.write('x' * 1_000_000)\nreturn 0")     # more than any pipe's buffer
    assert (lots.returncode, len(lots.stdout)) == (0, 1_000_000)


def test_a_closed_pipe_ends_the_process_quietly():
    reader = subprocess.Popen([sys.executable, "-c", "import sys; sys.stdin.readline()"], stdin=subprocess.PIPE)
    writer = subprocess.Popen([sys.executable, "-m", "bladefem", "modes", "cases/nrel5mw_blade.yaml"],
                              stdout=reader.stdin, stderr=subprocess.PIPE, env=environment(), cwd=ROOT)
    reader.stdin.close()
    reader.wait(timeout=600)
    _, error = writer.communicate(timeout=600)
    assert writer.returncode == 0
    assert b"Traceback" not in error


def test_other_threads_are_waited_for(tmp_path):
    """A thread the command left running (a library's writer, say) finishes before the process ends."""
    marker = tmp_path / "written"
    body = (f"threading.Thread(target=lambda: (time.sleep(0.5), open({str(marker)!r}, 'w').write('done')),"
            ").start()\nreturn 0")
    done = entry_with(body)
    assert done.returncode == 0
    assert marker.read_text() == "done"
