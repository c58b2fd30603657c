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


def main(library: str) -> int:
    reply = os.fdopen(os.dup(1), "wb", buffering=0)
    os.dup2(2, 1)                                    # the library's own prints go to stderr
    source = sys.stdin.buffer
    size, infile_length, outname_length = struct.unpack("<3i", read_exactly(source, 12))
    infile = ctypes.create_string_buffer(read_exactly(source, infile_length))
    outname = ctypes.create_string_buffer(read_exactly(source, outname_length))
    function = ctypes.CDLL(library).DISCON
    function.argtypes = [ctypes.POINTER(ctypes.c_float), ctypes.POINTER(ctypes.c_int32), ctypes.c_char_p,
                         ctypes.c_char_p, ctypes.c_char_p]
    function.restype = None
    records = np.zeros(size, dtype=np.float32)
    fail = ctypes.c_int32(0)
    message = ctypes.create_string_buffer(MESSAGE)
    pointer = records.ctypes.data_as(ctypes.POINTER(ctypes.c_float))
    reply.write(b"ready\n")
    while True:
        data = read_exactly(source, 4 * size)
        if not data:
            return 0
        records[:] = np.frombuffer(data, dtype="<f4")
        fail.value = 0
        ctypes.memset(message, 0, MESSAGE)
        function(pointer, ctypes.byref(fail), infile, outname, message)
        reply.write(records.astype("<f4").tobytes() + struct.pack("<i", fail.value) + message.raw)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
