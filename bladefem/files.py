"""Input files read with clear errors; outputs written whole or not at all.

Inputs (:func:`read_input`): a missing file, a folder, a broken link, a link loop, a device or pipe, an unreadable
or oversized file each give an :class:`~bladefem.errors.InputError` that says which.

Inputs are recorded while :func:`recording_inputs` is active (the command line records each command's inputs):
an output that names one of them, by any path (a symbolic or hard link included), is refused by
:func:`check_writable` and so by every write, unless the write is an explicit in-place update of that input
(``replaces_input=True``).

Outputs (:func:`atomic_path`, :func:`write_atomic`): the data goes to a temporary file beside the target and is
renamed over it once complete. Replacing an existing file keeps its permission bits (a new file gets the ones the
umask allows); a symbolic link is written through (the link stays, the file it points to gets the new content); a
file with several hard links is rewritten in place once the new content is complete, so every name sees it (the
one case where an interruption can leave the target partial); a read-only target is refused. Temporaries are named
``.<target>.<pid>.<random>.part<suffix>``; one left behind by a killed process is removed by the next write of the
same target. :func:`check_writable` tells, before a long computation, whether a target can be written.
"""

from __future__ import annotations

import errno
import os
import shutil
import stat
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path

from .errors import InputError

#: Largest input file read, bytes (the biggest windIO turbine files are a few MB)
MAX_INPUT_BYTES = 64 * 2**20
#: Marks a temporary file (before the target's own suffix, which writers that go by extension need)
PART = ".part"
#: The inputs read so far while recording: (device, inode) -> the path as the reader named it
_INPUTS: ContextVar[dict[tuple[int, int], str] | None] = ContextVar("bladefem_inputs", default=None)


# -- inputs -------------------------------------------------------------------------------------------------------

def _input_error(path: Path, error: OSError | ValueError) -> InputError:
    reason = {errno.ENOENT: "file not found", errno.ELOOP: "symbolic link loop (the link points back to itself)",
              errno.ENOTDIR: "a folder in this path is a file", errno.EACCES: "permission denied",
              errno.EPERM: "permission denied", errno.ENAMETOOLONG: "file name too long",
              errno.EISDIR: "is a folder, not a file"}
    if isinstance(error, ValueError):
        return InputError(f"invalid file name ({error})", file=str(path))
    if error.errno == errno.ENOENT and path.is_symlink():
        return InputError(f"broken symbolic link (it points to {os.readlink(path)}, which does not exist)",
                          file=str(path))
    return InputError(reason.get(error.errno, f"cannot read file ({error.strerror or error})"), file=str(path))


@contextmanager
def recording_inputs() -> Iterator[None]:
    """Within the block, every input checked or read is recorded, and writes that name one are refused."""
    token = _INPUTS.set({})
    try:
        yield
    finally:
        _INPUTS.reset(token)


def note_input(path: str | os.PathLike) -> None:
    """Record ``path`` as an input (when recording; a file that does not exist is not recorded)."""
    record = _INPUTS.get()
    if record is None:
        return
    try:
        info = os.stat(path)
    except (OSError, ValueError):
        return
    record.setdefault((info.st_dev, info.st_ino), str(path))


def recorded_input(path: str | os.PathLike) -> str | None:
    """The recorded input that ``path`` names (the same file by any link), or None."""
    record = _INPUTS.get()
    if not record:
        return None
    try:
        info = os.stat(path)
    except (OSError, ValueError):
        return None
    return record.get((info.st_dev, info.st_ino))


def input_problem(path: str | os.PathLike) -> str | None:
    """Why ``path`` cannot be read as an input file ("file not found", "is a folder, not a file", "symbolic link
    loop ...", "not a regular file ..."), or None when it can. Never opens the file (a pipe does not block)."""
    try:
        check_input(path)
    except InputError as error:
        return error.message
    return None


def check_input(path: str | os.PathLike) -> Path:
    """``path`` if it names a readable regular file of at most :data:`MAX_INPUT_BYTES`; else an InputError saying
    what it is instead."""
    path = Path(path)
    try:
        info = path.stat()
    except (OSError, ValueError) as error:
        raise _input_error(path, error) from None
    if stat.S_ISDIR(info.st_mode):
        raise InputError("is a folder, not a file", file=str(path))
    if not stat.S_ISREG(info.st_mode):
        raise InputError("not a regular file (a device, pipe or socket)", file=str(path))
    if info.st_size > MAX_INPUT_BYTES:
        raise InputError(f"file too large ({info.st_size / 2**20:.0f} MB; inputs are at most "
                         f"{MAX_INPUT_BYTES // 2**20} MB)", file=str(path))
    note_input(path)
    return path


def read_input(path: str | os.PathLike) -> bytes:
    """The bytes of an input file (see :func:`check_input`); an empty file is an InputError."""
    path = check_input(path)
    try:
        data = path.read_bytes()
    except OSError as error:
        raise _input_error(path, error) from None
    if not data:
        raise InputError("file is empty", file=str(path))
    return data


def decode_utf8(data: bytes, path: str | os.PathLike) -> str:
    """UTF-8 text (a leading byte-order mark dropped); an InputError naming the line and column of the first byte
    that is not UTF-8."""
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        before = data[:error.start]
        line = before.count(b"\n") + 1
        column = error.start - (before.rfind(b"\n") + 1) + 1
        raise InputError(f"not UTF-8 text: byte 0x{data[error.start]:02x} at column {column} (save the file as "
                         "UTF-8)", file=str(path), line=line) from None


# -- outputs ------------------------------------------------------------------------------------------------------

def _target(path: str | os.PathLike) -> Path:
    """The file a write to ``path`` replaces: the end of a chain of symbolic links (which stay as they are)."""
    path = Path(path)
    return Path(os.path.realpath(path)) if path.is_symlink() else path


def check_writable(path: str | os.PathLike, *, field: str | None = None, replaces_input: bool = False) -> None:
    """An InputError naming ``path`` (and the option ``field``) when it cannot be written: an input of the command
    (while recording, unless ``replaces_input``), a read-only file, a folder or device in its place, a folder that
    cannot be created or written into. Call it before a long computation."""
    shown = str(path)
    source = None if replaces_input else recorded_input(path)
    if source is not None:
        same = "" if os.path.abspath(source) == os.path.abspath(shown) else f" (the same file as {source})"
        raise InputError(f"is an input of this command{same}: refusing to overwrite it, write the output elsewhere",
                         file=shown, field=field)
    target = _target(path)
    try:
        info = target.stat()
    except FileNotFoundError:
        info = None
    except (OSError, ValueError) as error:
        raise _input_error(Path(path), error) from None
    if info is not None:
        if stat.S_ISDIR(info.st_mode):
            raise InputError("is a folder, not a file", file=shown)
        if not stat.S_ISREG(info.st_mode):
            raise InputError("not a regular file (a device, pipe or socket): refusing to replace it", file=shown)
        if not info.st_mode & 0o222 or not os.access(target, os.W_OK):
            raise InputError(f"file is read-only (mode {stat.S_IMODE(info.st_mode):04o}): make it writable or "
                             "write elsewhere", file=shown)
    folder = target.parent
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    if not folder.is_dir():
        raise InputError(f"cannot create the folder: {folder} is a file", file=shown)
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(f"cannot write into the folder {folder} (permission denied)", file=shown)


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _remove_stale_temporaries(target: Path) -> None:
    """Delete temporaries of ``target`` left by processes that no longer run (killed mid-write)."""
    prefix = f".{target.name}."
    for leftover in target.parent.glob(f"{prefix}*{PART}{target.suffix}"):
        pid = leftover.name[len(prefix):].split(".")[0]
        if not pid.isdigit() or int(pid) == os.getpid():
            continue
        try:
            os.kill(int(pid), 0)
        except ProcessLookupError:
            leftover.unlink(missing_ok=True)
        except OSError:             # alive (another user's process): leave it
            pass


def _write_in_place(source: Path, target: Path) -> None:
    """Copy the complete ``source`` into ``target``'s own inode (keeps its hard links)."""
    data = source.read_bytes()
    with open(target, "r+b") as stream:
        stream.write(data)
        stream.truncate()
        stream.flush()
        os.fsync(stream.fileno())


def _temporary(target: Path) -> Path:
    handle, name = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.{os.getpid()}.",
                                    suffix=PART + target.suffix)
    os.close(handle)
    return Path(name)


def _backup(target: Path, copy: Path) -> None:
    """Copy ``target`` (content, mode, times) to ``copy`` whole or not at all."""
    temporary = _temporary(target)
    try:
        shutil.copy2(target, temporary)
        os.replace(temporary, copy)
    finally:
        temporary.unlink(missing_ok=True)


@contextmanager
def atomic_path(path: str | os.PathLike, *, backup: bool = False, replaces_input: bool = False) -> Iterator[Path]:
    """A temporary path beside the target (same suffix, so writers that go by extension pick the right format).
    It replaces ``path`` when the block succeeds and is removed when it fails. Missing folders are created.
    ``backup``: an existing target is first copied to ``<path>.bak`` (replacing an older one). ``replaces_input``:
    an in-place update of an input (see :func:`check_writable`). An OSError while writing names ``path``, not the
    temporary."""
    shown = Path(path)
    check_writable(shown, replaces_input=replaces_input)
    target = _target(shown)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        _remove_stale_temporaries(target)
        existing = target.stat() if target.exists() else None
        temporary = _temporary(target)
    except OSError as error:
        raise OSError(error.errno, error.strerror or str(error), str(shown)) from None
    try:
        try:
            yield temporary
            os.chmod(temporary, stat.S_IMODE(existing.st_mode) if existing else 0o666 & ~_umask())
            if backup and existing:
                _backup(target, shown.with_name(shown.name + ".bak"))
            if existing and existing.st_nlink > 1:
                _write_in_place(temporary, target)
            else:
                os.replace(temporary, target)
        except OSError as error:
            raise OSError(error.errno, error.strerror or str(error), str(shown)) from None
    finally:
        temporary.unlink(missing_ok=True)


def write_atomic(path: str | os.PathLike, data: bytes | str, *, encoding: str = "utf-8",
                 backup: bool = False, replaces_input: bool = False) -> None:
    """Write text (in ``encoding``, newlines kept as given) or bytes to ``path`` whole or not at all (see
    :func:`atomic_path`)."""
    with atomic_path(path, backup=backup, replaces_input=replaces_input) as temporary:
        temporary.write_bytes(data.encode(encoding) if isinstance(data, str) else data)
