"""The input files of a case, carried to the worker that runs it.

A worker of a real cluster runs in another folder, often on another machine: the paths of the plan mean nothing
there. So the client reads each distinct input once (the base model, a deck with every file it references, a check
spec) while recording which files the readers open, and ships their bytes as a :class:`Bundle`; the worker writes
them into a private mirror of the client's absolute paths (so relative references between the files resolve as
they did on the client) and runs the case on those copies. A case thus runs on exactly the bytes its hash names.
"""

from __future__ import annotations

import hashlib
import os
import sys
import tempfile
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..files import check_input

#: files the readers opened while recording (None when not recording)
_opened: ContextVar[list[str] | None] = ContextVar("bladefem_batch_opened", default=None)
_CODE_SUFFIXES = (".py", ".pyc", ".so", ".pyd")


def _audit(event: str, args: tuple) -> None:
    if event != "open":
        return
    opened = _opened.get()
    if opened is None:
        return
    path, mode = args[0], args[1]
    if isinstance(mode, str) and "r" in mode and "+" not in mode and isinstance(path, str | bytes | os.PathLike):
        opened.append(os.fsdecode(path))


_hook_installed = False


@contextmanager
def recording() -> Iterator[list[str]]:
    """The paths of the files opened for reading inside the block (Python's 'open' audit event)."""
    global _hook_installed
    if not _hook_installed:
        sys.addaudithook(_audit)
        _hook_installed = True
    opened: list[str] = []
    token = _opened.set(opened)
    try:
        yield opened
    finally:
        _opened.reset(token)


def _code_folders() -> tuple[str, ...]:
    """Where Python's own files live: the standard library, installed packages, bladefem itself."""
    import sysconfig
    folders = {path for name, path in sysconfig.get_paths().items() if name in ("stdlib", "platstdlib", "purelib",
                                                                               "platlib")}
    folders |= {path for path in sys.path if path.endswith(("site-packages", "dist-packages"))}
    folders.add(str(Path(__file__).resolve().parents[1]))
    return tuple(folder.rstrip(os.sep) + os.sep for folder in folders if folder)


def _is_code(path: str) -> bool:
    """A module or package data file opened while reading (an import, a packaged schema), not an input."""
    return path.endswith(_CODE_SUFFIXES) or path.startswith(_code_folders())


@dataclass(frozen=True)
class Bundle:
    """Input files by absolute path on the client, with their bytes; ``digest`` names the whole set; ``error``: the
    message of the client's reader when it failed (the files it had opened by then are all the bundle holds, so a
    case that fails on the worker reports this message, not what the missing files made of it)."""

    files: tuple[tuple[str, bytes], ...]
    digest: str
    error: str | None = None

    @classmethod
    def of(cls, paths: Iterable[str | os.PathLike], error: str | None = None,
           opened: Iterable[str | os.PathLike] = ()) -> Bundle:
        """The bundle of the files ``paths`` (each one) and ``opened`` (less Python's own files, see
        :func:`_is_code`)."""
        files = {}
        named = [os.path.abspath(path) for path in paths]
        for absolute in [*named, *(a for a in map(os.path.abspath, opened) if not _is_code(a))]:
            if absolute in files:
                continue
            try:                         # as the reader saw it (an empty file too: the case reports it)
                files[absolute] = check_input(absolute).read_bytes()
            except (InputError, OSError):  # the reader could not read it either: the case reports that
                continue
        items = tuple(sorted(files.items()))
        key = hashlib.sha256()
        for path, data in items:
            key.update(path.encode() + b"\0" + hashlib.sha256(data).digest())
        return cls(items, key.hexdigest(), error)

    @property
    def content(self) -> str:
        """Digest of the files' bytes alone (not their paths): the same inputs in another folder are the same."""
        return hashlib.sha256(b"".join(sorted(hashlib.sha256(data).digest() for _, data in self.files))).hexdigest()

    @property
    def paths(self) -> list[Path]:
        return [Path(path) for path, _ in self.files]


def bundle_of(read: Callable[[], Any], named: Iterable[Path]) -> Bundle:
    """The files ``read()`` opens (a reader of the case's inputs, run once here), and the ``named`` ones. A reader
    that fails keeps what it opened and its message: a case that then fails on the worker reports it."""
    error = None
    with recording() as opened:
        try:
            read()
        except Exception as failure:             # reported by the cases, on the worker
            error = f"{type(failure).__name__}: {failure}"
    return Bundle.of(named, error, opened)


#: environment variable of a worker: the folder for its copies of the cases' input files (default: a folder
#: ``bladefem-batch-<uid>`` in the temporary folder); each set of files is written once per machine
INPUTS_FOLDER = "BLADEFEM_BATCH_INPUTS"


def mirror_root(bundle: Bundle) -> Path:
    """Where this worker keeps its copy of ``bundle`` (written once per worker machine and bundle)."""
    folder = os.environ.get(INPUTS_FOLDER)
    if not folder:
        user = os.getuid() if hasattr(os, "getuid") else "user"
        folder = os.path.join(tempfile.gettempdir(), f"bladefem-batch-{user}")
    return Path(folder) / bundle.digest


def mirrored(root: Path, path: str | os.PathLike) -> Path:
    """The copy under ``root`` of the client's ``path``."""
    path = Path(os.path.abspath(path))
    return root / path.anchor.strip("/\\:") / path.relative_to(path.anchor)


def materialize(bundle: Bundle) -> Path:
    """Write the bundle's files under :func:`mirror_root` (each whole: temporary file, then rename) unless a
    complete copy is there already (every file present: a cleaner of temporary folders may have removed some);
    returns the root."""
    root = mirror_root(bundle)
    complete = root / ".complete"
    if complete.exists() and all(mirrored(root, path).is_file() for path, _ in bundle.files):
        return root
    try:
        for path, data in bundle.files:
            target = mirrored(root, path)
            target.parent.mkdir(parents=True, exist_ok=True)
            handle, temporary = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".part")
            with os.fdopen(handle, "wb") as stream:
                stream.write(data)
            os.replace(temporary, target)
        complete.touch()
    except OSError as error:
        import socket
        raise OSError(f"cannot write the case's input files on the worker {socket.gethostname()} under {root} "
                      f"({error.strerror or error}): set {INPUTS_FOLDER} to a writable folder there") from None
    return root


def check_results_folder(results: str | os.PathLike, inputs: Iterable[str | os.PathLike]) -> None:
    """An InputError when the results folder is, or holds, one of the ``inputs`` (the plan, a model, a file a
    deck references): its part files and temporaries would sit among (and could replace) the inputs."""
    folder = Path(os.path.realpath(results))
    for path in inputs:
        real = Path(os.path.realpath(path))
        if real == folder or folder in real.parents:
            what = "is" if real == folder else "holds"
            raise InputError(f"the results folder {what} an input of the batch ({path}): give a folder of its own",
                             file=str(results), field="-o")


__all__ = ["INPUTS_FOLDER", "Bundle", "bundle_of", "check_results_folder", "materialize", "mirror_root", "mirrored",
           "recording"]
