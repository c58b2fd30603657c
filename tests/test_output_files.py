"""Outputs are written whole or not at all, and replacing a file keeps what belongs to it: its permission bits, its
symbolic and hard links, every byte outside the fields bladefem changes; a read-only target is refused before any
computation; a temporary left by a killed writer is cleaned up."""

from __future__ import annotations

import contextlib
import errno
import io
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from bladefem.cli import main
from bladefem.errors import InputError
from bladefem.files import PART, atomic_path, check_writable, write_atomic

DATA = Path(__file__).parent / "data"
NAMES = ("NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", "NRELOffshrBsline5MW_Blade.dat",
         "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat")


def mode(path: Path) -> int:
    return path.stat().st_mode & 0o777


def test_replacing_keeps_the_mode_and_new_files_follow_the_umask(tmp_path):
    old = tmp_path / "old.txt"
    old.write_text("old")
    old.chmod(0o640)
    write_atomic(old, "new")
    assert old.read_text() == "new" and mode(old) == 0o640
    previous = os.umask(0o027)
    try:
        write_atomic(tmp_path / "fresh.txt", "x")
    finally:
        os.umask(previous)
    assert mode(tmp_path / "fresh.txt") == 0o640                  # 0666 & ~0027, not mkstemp's 0600


def test_a_symbolic_link_is_written_through(tmp_path):
    real = tmp_path / "real" / "blade.dat"
    real.parent.mkdir()
    real.write_text("old")
    link = tmp_path / "link.dat"
    link.symlink_to(real)
    write_atomic(link, "new")
    assert link.is_symlink() and os.readlink(link) == str(real) and real.read_text() == "new"
    assert not list(real.parent.glob(f"*{PART}*")) and not list(tmp_path.glob(f"*{PART}*"))


def test_hard_links_keep_sharing_the_new_content(tmp_path):
    first = tmp_path / "first.dat"
    first.write_text("old")
    second = tmp_path / "second.dat"
    os.link(first, second)
    inode = first.stat().st_ino
    write_atomic(first, "new content")
    assert second.read_text() == "new content" and first.stat().st_ino == inode == second.stat().st_ino


def test_a_read_only_target_is_refused_and_kept(tmp_path):
    target = tmp_path / "locked.dat"
    target.write_text("keep me")
    target.chmod(0o444)
    with pytest.raises(InputError, match="read-only") as caught:
        write_atomic(target, "new")
    assert caught.value.file == str(target) and target.read_text() == "keep me"
    with pytest.raises(InputError, match="is a folder"):
        check_writable(tmp_path)


def test_a_failing_writer_leaves_the_old_file_whole_and_names_the_target(tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("old, complete\n")
    with pytest.raises(OSError) as caught:
        with atomic_path(target) as temporary:
            temporary.write_text("half")
            raise OSError(errno.ENOSPC, "No space left on device", str(temporary))
    assert caught.value.filename == str(target)                   # not the hidden temporary
    assert target.read_text() == "old, complete\n" and sorted(tmp_path.iterdir()) == [target]


def test_a_killed_writer_leaves_the_old_file_and_its_temporary_is_cleaned_up_next_time(tmp_path):
    target = tmp_path / "out.dat"
    target.write_text("old")
    script = ("import os, sys; from bladefem.files import atomic_path\n"
              "with atomic_path(sys.argv[1]) as t:\n"
              "    t.write_text('half'); os.kill(os.getpid(), 9)\n")
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parent.parent)}
    killed = subprocess.run([sys.executable, "-c", script, str(target)], env=env)
    assert killed.returncode == -9
    leftovers = list(tmp_path.glob(f".out.dat.*{PART}.dat"))
    assert target.read_text() == "old" and len(leftovers) == 1       # the kill left its temporary behind
    alive = tmp_path / f".out.dat.{os.getppid()}.abc{PART}.dat"    # one of a running process is left alone
    alive.write_text("busy")
    write_atomic(target, "new")
    assert target.read_text() == "new" and sorted(tmp_path.iterdir()) == sorted([target, alive])


def test_backup_keeps_the_old_bytes(tmp_path):
    target = tmp_path / "blade.dat"
    target.write_bytes(b"old \xb5 bytes\n")
    write_atomic(target, "new", backup=True)
    assert (tmp_path / "blade.dat.bak").read_bytes() == b"old \xb5 bytes\n" and target.read_text() == "new"


# -- elastodyn --write --------------------------------------------------------------------------------------------

@pytest.fixture()
def model(tmp_path: Path) -> Path:
    for name in NAMES:
        shutil.copy(DATA / name, tmp_path / name)
    return tmp_path


def run(*argv: object) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


def test_elastodyn_write_keeps_latin1_bytes_mode_and_links(model):
    blade = model / NAMES[1]
    original = blade.read_bytes().replace(b"baseline", b"baseline \xb0 \xe9", 1)   # Latin-1 bytes in a comment
    assert original != blade.read_bytes()
    blade.write_bytes(original)
    blade.chmod(0o644)
    link = model / "link_to_blade.dat"
    link.symlink_to(blade)
    code, out, err = run("elastodyn", model / NAMES[0], "--write", link, "--backup", "--elements", "40")
    assert code == 0, err
    new = blade.read_bytes()
    assert link.is_symlink() and mode(blade) == 0o644
    assert b"baseline \xb0 \xe9" in new                             # still Latin-1, not re-encoded as UTF-8
    changed = [(a, b) for a, b in zip(original.splitlines(), new.splitlines()) if a != b]
    assert len(original.splitlines()) == len(new.splitlines()) and len(changed) == 15
    assert all(b"Sh(" in b for _, b in changed)                    # only coefficient lines differ
    assert (model / "link_to_blade.dat.bak").read_bytes() == original


def test_elastodyn_refuses_a_read_only_target_before_computing(model, monkeypatch):
    from bladefem.modal import elastodyn_fit

    def no_computation(*args, **kwargs):
        raise AssertionError("the fit ran before the target was checked")

    monkeypatch.setattr(elastodyn_fit, "blade_coefficients", no_computation)
    blade = model / NAMES[1]
    before = blade.read_bytes()
    blade.chmod(0o444)
    code, _, err = run("elastodyn", model / NAMES[0], "--write", blade)
    assert code == 2 and len(err.strip().splitlines()) == 1 and str(blade) in err and "read-only" in err
    assert blade.read_bytes() == before


def test_backup_needs_write(model):
    code, _, err = run("elastodyn", model / NAMES[0], "--backup")
    assert code == 2 and "--backup" in err
