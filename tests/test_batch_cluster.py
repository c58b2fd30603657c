"""Batch runs on a real cluster, as a cluster user starts one: a Dask scheduler and a worker as separate processes
in another folder (on 127.0.0.1, a free port, bounded time, always torn down), the batch started from the clone
with the plan's relative path. The cases carry their input files; failures exit non-zero; --resume retries them."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

pytest.importorskip("dask.distributed")
pytest.importorskip("pyarrow")
if not hasattr(os, "killpg"):
    pytest.skip("process groups (POSIX) tear the cluster down", allow_module_level=True)

from cpu_watchdog import wall_limit  # noqa: E402

from bladefem.batch import ResultStore  # noqa: E402
from bladefem.batch.bundle import INPUTS_FOLDER  # noqa: E402
from bladefem.cli import main  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
#: seconds a scheduler or worker may take to start, and a batch of 64 cases to run (a loaded 2-core CI machine)
START_SECONDS = 90
BATCH_SECONDS = 300


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _environment(**extra: str) -> dict[str, str]:
    path = os.pathsep.join(p for p in (str(REPO), os.environ.get("PYTHONPATH", "")) if p)
    return {**os.environ, "PYTHONPATH": path, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", **extra}


def _stop(process: subprocess.Popen) -> None:
    """The process and its children (a worker's nanny starts one): SIGTERM to its group, then SIGKILL to what
    is left of the group after 10 s."""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        try:
            os.killpg(process.pid, sig)
        except ProcessLookupError:
            break
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            pass
    if process.poll() is None:
        process.kill()
        process.wait(10)


@contextmanager
def started(command: list[str], folder: Path, log: Path, **extra: str) -> Iterator[subprocess.Popen]:
    with open(log, "wb") as stream:
        process = subprocess.Popen([sys.executable, "-m", *command], cwd=folder, env=_environment(**extra),
                                   stdout=stream, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        yield process
    finally:
        _stop(process)


def wait_for_workers(address: str, count: int) -> None:
    from dask.distributed import Client
    with Client(address, timeout=f"{START_SECONDS}s") as client:
        client.wait_for_workers(count, timeout=START_SECONDS)
        deadline = time.monotonic() + START_SECONDS         # a stopped worker leaves the scheduler's list
        while len(client.scheduler_info()["workers"]) != count and time.monotonic() < deadline:
            time.sleep(0.2)
        assert len(client.scheduler_info()["workers"]) == count


@contextmanager
def scheduler(folder: Path) -> Iterator[str]:
    port = free_port()
    command = ["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"]
    with started(command, folder, folder / "scheduler.log"):
        yield f"tcp://127.0.0.1:{port}"


def worker(address: str, folder: Path, name: str, **extra: str):
    command = ["distributed.cli.dask_worker", address, "--nthreads", "1", "--nworkers", "1", "--no-dashboard",
               "--host", "127.0.0.1", "--name", name]
    return started(command, folder, folder / f"{name}.log", **extra)


def test_a_worker_in_another_folder_runs_every_case_and_resume_retries_failures(tmp_path, monkeypatch, capsys):
    """First a worker that cannot keep the cases' input files: every case fails, the batch says so and exits 1.
    Then a working worker in another folder: --resume runs all 64 cases of cases/nrel5mw_uq.yaml again, OK."""
    elsewhere = tmp_path / "cluster"
    elsewhere.mkdir()
    blocked = tmp_path / "not-a-folder"
    blocked.write_text("a file where the worker's input copies should go\n")
    monkeypatch.chdir(REPO)
    out = tmp_path / "uq"
    with scheduler(elsewhere) as address:
        with worker(address, elsewhere, "broken", **{INPUTS_FOLDER: str(blocked)}):
            wait_for_workers(address, 1)
            with wall_limit(BATCH_SECONDS, "the batch"):
                assert main(["batch", "cases/nrel5mw_uq.yaml", "-o", str(out), "--scheduler", address]) == 1
        captured = capsys.readouterr()
        assert "64 run (64 failed)" in captured.out
        error = captured.err.strip().splitlines()[-1]
        assert "64 of 64 cases failed" in error and "cannot write the case's input files" in error
        assert "Dask dashboard" not in captured.err                     # the scheduler has none
        with worker(address, elsewhere, "working", **{INPUTS_FOLDER: str(elsewhere / "inputs")}):
            wait_for_workers(address, 1)
            with wall_limit(BATCH_SECONDS, "the batch"):
                assert main(["batch", "cases/nrel5mw_uq.yaml", "-o", str(out), "--scheduler", address, "--resume",
                             "--quiet"]) == 0
    captured = capsys.readouterr()
    assert "64 run (0 failed, 64 failed before and run again)" in captured.out
    rows = ResultStore(out).table().to_pylist()
    assert {row["status"] for row in rows} == {"ok"}                  # the failed rows are gone
    assert sorted(row["case_index"] for row in rows) == sorted(i for i in range(64) for _ in range(6))
    copies = list((elsewhere / "inputs").rglob("nrel5mw_blade.yaml"))
    assert len(copies) == 1 and copies[0].read_bytes() == (REPO / "cases" / "nrel5mw_blade.yaml").read_bytes()
