"""The process that holds one Bladed-style controller library (``python -m bladefem.models.turbine.discon_worker
LIBRARY``): it loads the library with ctypes and calls its ``DISCON`` for every record array the simulation sends.

A library's Fortran state is global to the process that loads it (ROSCO keeps its filters and integrators in module
variables), so every simulation runs its controller in a process of its own; a crash of the library (a Fortran
runtime error, a STOP) ends this process, not the simulation's, which then reports it.

The call is the Bladed interface's (as OpenFAST's ServoDyn makes it, ``BladedInterface.f90``; ROSCO's
``rosco/toolbox/control_interface.py`` makes the same call from Python)::

    void DISCON(float *avrSWAP, int *aviFAIL, char *accINFILE, char *avcOUTNAME, char *avcMSG)

Protocol on the pipes (little-endian): first the header ``size (int32), len(infile) (int32), len(outname) (int32)``
and the two NUL-terminated strings; then per call the ``size`` float32 records in, and back the ``size`` float32
records, ``aviFAIL`` (int32) and the message (:data:`MESSAGE` bytes). Whatever the library prints goes to stderr
(the worker's stdout is the reply pipe).
"""

from __future__ import annotations

import ctypes
import os
import struct
import sys

import numpy as np

#: bytes of the controller's message buffer (ServoDyn's ErrMsgSz 1024 plus the NUL)
MESSAGE = 1025
#: bytes of the OUTNAME buffer the library may write logging-channel names into (ServoDyn's avcOUTNAME_LEN:
#: 300 channels of 2 + 20 characters, plus the NUL)
OUTNAME = 6601


def read_exactly(stream, count: int) -> bytes:
    """``count`` bytes from ``stream``, or b'' at the end of the input."""
    chunks, left = [], count
    while left:
        chunk = stream.read(left)
        if not chunk:
            return b""
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


class Library:
    """The ``DISCON`` function of a library (loaded from ``path``) bound to its record array and strings."""

    def __init__(self, path: str, size: int, infile: bytes, outname: bytes) -> None:
        self.function = ctypes.CDLL(path).DISCON
        self.function.argtypes = [ctypes.POINTER(ctypes.c_float), ctypes.POINTER(ctypes.c_int32), ctypes.c_char_p,
                                  ctypes.c_char_p, ctypes.c_char_p]
        self.function.restype = None
        self.records = np.zeros(size, dtype=np.float32)
        self.pointer = self.records.ctypes.data_as(ctypes.POINTER(ctypes.c_float))
        self.infile = ctypes.create_string_buffer(infile)
        self.outname = ctypes.create_string_buffer(outname, max(len(outname), OUTNAME))
        self.fail = ctypes.c_int32(0)
        self.message = ctypes.create_string_buffer(MESSAGE)

    def raw(self) -> tuple:
        """What a compiled kernel calls the library with: ``DISCON`` taking five addresses, and the buffers of
        aviFAIL, accINFILE, avcOUTNAME and avcMSG as numpy arrays over the same memory."""
        address = ctypes.cast(self.function, ctypes.c_void_p).value
        function = ctypes.CFUNCTYPE(None, *[ctypes.c_void_p] * 5)(address)
        return function, tuple(np.frombuffer(buffer, dtype=dtype) for buffer, dtype in (
            (self.fail, np.int32), (self.infile, np.uint8), (self.outname, np.uint8), (self.message, np.uint8)))

    def __call__(self) -> tuple[int, bytes]:
        """One call on :attr:`records` (changed in place): aviFAIL and the raw message buffer."""
        self.fail.value = 0
        ctypes.memset(self.message, 0, MESSAGE)
        self.function(self.pointer, ctypes.byref(self.fail), self.infile, self.outname, self.message)
        return self.fail.value, self.message.raw


def main(library: str) -> int:
    reply = os.fdopen(os.dup(1), "wb", buffering=0)
    os.dup2(2, 1)                                    # the library's own prints go to stderr
    source = sys.stdin.buffer
    size, infile_length, outname_length = struct.unpack("<3i", read_exactly(source, 12))
    infile = read_exactly(source, infile_length)
    outname = read_exactly(source, outname_length)
    call = Library(library, size, infile, outname)
    reply.write(b"ready\n")
    while True:
        data = read_exactly(source, 4 * size)
        if not data:
            return 0
        call.records[:] = np.frombuffer(data, dtype="<f4")
        fail, message = call()
        reply.write(call.records.astype("<f4").tobytes() + struct.pack("<i", fail) + message)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
