"""A Bladed-style controller library (ROSCO's ``libdiscon.so``, or any library with the ``DISCON`` entry point)
called through its ``avrSWAP`` record array, as OpenFAST's ServoDyn calls it.

The records (1-based, Bladed's numbering) are filled as ServoDyn's ``Fill_avrSWAP`` fills them
(OpenFAST ``modules/servodyn/src/BladedInterface.f90``); the commands are read back as its ``Retrieve_avrSWAP``
reads them: pitch demands 42-44 (individual) or 45 (collective), generator torque 47, yaw rate 48, generator
contactor 35, brake 36, and the overrides 55, 56 that ServoDyn refuses too. The array has ServoDyn's extended size
(3300 records): ROSCO with ``Ext_Interface`` 1 reads and writes records past 1000 (1000: the extended interface's
version, 1; 1001-1018: the platform's motion, zero on a fixed foundation).

Each simulation has its own library instance (a private copy loaded into the process, or a process of its own:
:class:`DisconController`). SI throughout (rad, rad/s, N m, W, m/s, s).
"""

from __future__ import annotations

import ctypes
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...errors import InputError
from .discon_worker import MESSAGE, OUTNAME, Library

#: records in the array (ServoDyn's EXavrSWAP_Size)
RECORDS = 3300
#: ServoDyn's 'R': the record where the (empty) torque-speed table starts, and the largest logging count
TABLE_START, LOGGING_CHANNELS = 85, 300
#: the original libraries loaded once per process (their dependencies serve the private copies)
_ORIGINALS: dict[str, ctypes.CDLL] = {}


def flush_prints(library: ctypes.CDLL) -> None:
    """What a loaded library printed and its runtime still buffers, written out now (while fd 1 is stderr): a
    gfortran runtime's units (``_gfortran_flush_i4(NULL)``, Fortran's FLUSH of every unit; ROSCO's) and every C
    stdio stream (``fflush(NULL)``). Otherwise they are written when the process ends, to the program's own output
    (a table written to stdout would end with them)."""
    for flush in (lambda: library._gfortran_flush_i4(None), lambda: ctypes.CDLL(None).fflush(None)):
        try:
            flush()
        except (OSError, AttributeError):             # not a gfortran library, or no C library to ask
            pass


class ControllerError(RuntimeError):
    """The controller library failed (aviFAIL < 0, a crash, or a command bladefem does not model) at ``time``."""

    def __init__(self, message: str, time: float) -> None:
        super().__init__(message)
        self.time = time


@dataclass(frozen=True)
class ControllerSetup:
    """What the deck's ServoDyn gives the controller (SI).

    library : the controller library; infile : DLL_InFile (DISCON.IN); time_step : DLL_DT, s; blades : NumBl
    individual : Ptch_Cntrl 1 (the library returns one pitch per blade); servodyn : the ServoDyn file (for messages)
    pitch_limits : Ptch_Min, Ptch_Max, rad; rate_limits : PtchRate_Min, PtchRate_Max, rad/s; air_density : kg/m^3
    hub_height : rotor centre above the ground, m (where the wind speed sent is taken)
    time_step_from : where time_step was set (for messages)
    """

    library: str
    infile: str
    time_step: float
    blades: int
    individual: bool
    servodyn: str
    pitch_limits: tuple[float, float] = (0.0, math.pi / 2)
    rate_limits: tuple[float, float] = (-math.radians(8.0), math.radians(8.0))
    air_density: float = 1.225
    hub_height: float = 0.0
    time_step_from: str = "DLL_DT"


@dataclass(frozen=True)
class Measurements:
    """The turbine's state sent to the controller at one call (SI): blade pitch (B,), rotor and generator (high-
    speed shaft) speed, the hub-height horizontal wind speed, rotor azimuth, the shaft power, the previous call's
    generator torque and electrical power, blade-root out-of-plane and in-plane moments (B,), tower-top fore-aft and
    side-to-side accelerations (m/s^2), the nacelle's roll and nodding angular accelerations from the tower's
    bending (rad/s^2), nacelle yaw angle."""

    pitch: np.ndarray
    rotor_speed: float
    generator_speed: float
    wind_speed: float
    azimuth: float
    shaft_power: float
    generator_torque: float
    electrical_power: float
    root_oop: np.ndarray
    root_ip: np.ndarray
    tower_top_fa: float = 0.0
    tower_top_ss: float = 0.0
    nacelle_roll: float = 0.0
    nacelle_nod: float = 0.0
    yaw: float = 0.0


@dataclass(frozen=True)
class Commands:
    """What the controller asks for: blade pitch (B,), rad; generator torque, N m."""

    pitch: np.ndarray
    torque: float


class DisconController:
    """One controller library instance; :meth:`call` at each controller step, :meth:`close` (the final call,
    iStatus -1) at the end. Use as a context manager.

    ``isolated``: the library runs in a process of its own (:mod:`.discon_worker`), which reports a crash instead
    of dying with it, at the cost of a process switch per call (milliseconds on a loaded machine). Otherwise (the
    default) a private copy of the library is loaded into this process (one instance per simulation: ROSCO's state
    is global to a loaded library), its prints sent to stderr while it is loaded, and its first call is made
    first in an isolated twin, so that a library or input file that crashes it (a Fortran runtime error reading
    DISCON.IN) is reported; that twin's prints (ROSCO's banner and warnings, which the run's own instance prints
    again) are shown only when it fails (``echo`` False)."""

    def __init__(self, setup: ControllerSetup, root_name: str = "bladefem", isolated: bool = False,
                 echo: bool = True) -> None:
        self.setup, self.root_name, self.isolated = setup, root_name, isolated
        self.captured = None if echo else tempfile.TemporaryFile()
        self.status = 0
        self.pitch_command = np.zeros(setup.blades)
        self.folder = tempfile.TemporaryDirectory(prefix="bladefem-discon-")
        infile = str(Path(setup.infile).resolve()).encode() + b"\0"
        # ServoDyn's RootName (ROSCO names its debug files from it, cutting at the last dot)
        outname = str(Path(self.folder.name) / f"{root_name}.SrvD").encode() + b"\0"
        self.lengths = (len(infile), len(outname))
        self.process = self.library = self.stdout = None
        if isolated:
            self.records = np.zeros(RECORDS, dtype=np.float32)
            self.start_worker(infile, outname)
        else:
            self.load_copy(infile, outname)
            self.records = self.library.records

    def start_worker(self, infile: bytes, outname: bytes) -> None:
        """The library in its own process, told the array size and the two strings."""
        worker = Path(__file__).with_name("discon_worker.py")
        self.process = subprocess.Popen([sys.executable, str(worker), self.setup.library], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, stderr=self.captured, cwd=self.folder.name)
        self.process.stdin.write(struct.pack("<3i", RECORDS, *self.lengths) + infile + outname)
        self.process.stdin.flush()
        if self.process.stdout.readline() != b"ready\n":
            self.process.wait()
            self.replay()
            self.folder.cleanup()
            raise InputError(f"the controller library could not be loaded (its process ended with exit status "
                             f"{self.process.returncode}; the reason is above)", file=self.setup.library)

    def load_copy(self, infile: bytes, outname: bytes) -> None:
        """A private copy of the library in this process (the original loaded first, for its dependencies: a
        wheel's libraries are found next to the original, and the copy's are then already loaded); fd 1 to
        stderr while it is loaded."""
        original = self.setup.library
        copy = Path(self.folder.name) / f"controller-{Path(original).name}"
        try:
            _ORIGINALS.setdefault(original, ctypes.CDLL(original))
            shutil.copyfile(original, copy)
            self.library = Library(str(copy), RECORDS, infile, outname)
        except (OSError, AttributeError) as error:
            self.folder.cleanup()
            raise InputError(f"the controller library could not be loaded: {error}", file=original) from None
        sys.stdout.flush()
        self.stdout = os.dup(1)
        os.dup2(2, 1)

    def __enter__(self) -> DisconController:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def constant_records(self) -> dict[int, float]:
        """The records ServoDyn's ``Fill_avrSWAP`` sets to the same value at every call (1-based numbers)."""
        s = self.setup
        return {3: s.time_step, 6: s.pitch_limits[0], 7: s.pitch_limits[1], 8: s.rate_limits[0],
                9: s.rate_limits[1], 10: 0.0, 24: 0.0, 25: 0.0, 26: 0.0, 28: float(s.individual), 29: 0.0,
                49: MESSAGE, 50: self.lengths[0], 51: self.lengths[1], 61: s.blades, 62: LOGGING_CHANNELS,
                63: TABLE_START, 64: OUTNAME, 66: 1001, 84: 0.0, 95: s.air_density, 98: 0.0, 117: 0.0,
                129: RECORDS, 1000: 1.0}

    def fill(self, time: float, m: Measurements) -> None:
        """The records ServoDyn's ``Fill_avrSWAP`` sets (1-based numbers in the comments): the constant ones and
        those of the turbine's state (:func:`.compiled_control.fill` is the compiled twin)."""
        s, r = self.setup, self.records
        values = self.constant_records()
        values.update({
            1: self.status, 2: time, 4: m.pitch[0], 11: self.pitch_command[0], 14: m.shaft_power,
            15: m.electrical_power, 20: m.generator_speed, 21: m.rotor_speed, 23: m.generator_torque,
            27: m.wind_speed, 35: r[34] if self.status else 1.0, 37: m.yaw, 53: m.tower_top_fa,
            54: m.tower_top_ss, 60: m.azimuth, 82: m.nacelle_roll, 83: m.nacelle_nod})
        for blade in range(min(s.blades, 3)):
            values[30 + blade] = m.root_oop[blade]
            values[69 + blade] = m.root_ip[blade]
        if s.blades > 1:
            values[33] = m.pitch[1]
        if s.blades > 2:
            values[34] = m.pitch[2]
        for record, value in values.items():
            r[record - 1] = value

    def call(self, time: float, measurements: Measurements) -> Commands:
        """Call the library at ``time`` (s) with the turbine's state; its pitch and torque demands."""
        if self.status == 0 and not self.isolated:
            with DisconController(self.setup, self.root_name, isolated=True, echo=False) as probe:
                try:
                    probe.call(time, measurements)
                except ControllerError:
                    probe.replay()
                    raise
        self.fill(time, measurements)
        records, fail, message = self.exchange(time)
        if self.status == 0 and self.library is not None:
            flush_prints(_ORIGINALS[self.setup.library])          # the first call's prints shown now
        if fail < 0:
            raise ControllerError(f"the controller ({Path(self.setup.library).name} with "
                                  f"{self.setup.infile}) failed at t = {time:.4g} s: {message or 'no message'}",
                                  time)
        self.status = 1
        blades = self.setup.blades
        if records[54] != 0 or records[55] != 0:
            raise ControllerError("the controller asks for a built-in pitch or torque override (records 55, 56), "
                                  "which ServoDyn refuses too", time)
        if self.setup.individual:
            pitch = records[41:41 + min(blades, 3)].astype(float)
        else:
            pitch = np.full(blades, float(records[44]))
        self.pitch_command = pitch
        return Commands(pitch=pitch, torque=float(records[46]))

    def replay(self) -> None:
        """What the library printed while its prints were held back (``echo`` False), onto stderr."""
        if self.captured is not None:
            self.captured.seek(0)
            sys.stderr.write(self.captured.read().decode(errors="replace"))
            sys.stderr.flush()

    def exchange(self, time: float) -> tuple[np.ndarray, int, str]:
        """One call of the library on the records; a library that ended its process is a ControllerError."""
        if self.library is not None:
            fail, raw = self.library()
            return self.records, fail, raw.split(b"\0", 1)[0].decode(errors="replace").strip()
        size = 4 * RECORDS + 4 + MESSAGE
        try:
            self.process.stdin.write(self.records.astype("<f4").tobytes())
            self.process.stdin.flush()
            reply = self.process.stdout.read(size)
        except (BrokenPipeError, OSError):
            reply = b""
        if len(reply) != size:
            code = self.process.wait()
            raise ControllerError(f"the controller library {self.setup.library} ended its process (exit status "
                                  f"{code}) at t = {time:.4g} s; its messages are above", time)
        self.records[:] = np.frombuffer(reply[:4 * RECORDS], dtype="<f4")
        fail = struct.unpack("<i", reply[4 * RECORDS:4 * RECORDS + 4])[0]
        message = reply[4 * RECORDS + 4:].split(b"\0", 1)[0].decode(errors="replace").strip()
        return self.records, fail, message

    def close(self, time: float | None = None) -> None:
        """The last call (iStatus -1, when the library was called at all), then the process ends (or this
        process's fd 1 is given back)."""
        if self.library is not None:
            if self.status and time is not None:
                self.records[0], self.records[1] = -1, time
                self.library()
            self.status = 0
            self.library = None
            if self.stdout is not None:
                flush_prints(_ORIGINALS[self.setup.library])
                os.dup2(self.stdout, 1)
                os.close(self.stdout)
                self.stdout = None
        elif self.process is not None and self.process.poll() is None:
            try:
                if self.status and time is not None:
                    self.records[0] = -1
                    self.records[1] = time
                    self.exchange(time)
                self.process.stdin.close()
                self.process.wait(timeout=10)
            except (ControllerError, OSError, subprocess.TimeoutExpired):
                self.process.kill()
                self.process.wait()
        if self.captured is not None:
            self.captured.close()
        self.folder.cleanup()
