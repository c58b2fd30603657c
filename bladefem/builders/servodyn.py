"""ServoDyn input file: fixed pitch, the simple variable-speed torque law, the nacelle-yaw spring and damper.

Modelled: ``PCMode`` 0 (pitch held at ElastoDyn's ``BlPitch``), ``VSContrl`` 1 with ``VS_RtGnSp`` (rpm, high-speed
shaft), ``VS_RtTq`` (N m), ``VS_Rgn2K`` (N m/rpm^2), ``VS_SlPc`` (%), ``GenEff`` (%), and ``YawNeut``, ``YawSpr``,
``YawDamp``. Everything else that changes the turbine's behaviour (Bladed-style DLL and other controllers, other
generator models, pitch and yaw manoeuvres, generator switching and brake events inside the simulated time,
structural and flow control) is listed by :meth:`ServoDyn.unmodelled` with its file, line and label.
SI inside: rad, rad/s, N m, N m s^2/rad^2 (the region-2 constant), fractions for percentages.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

from ..formats._labels import Labels
from ..limits import MAX_YAW_DAMPING, MAX_YAW_STIFFNESS
from .aerodyn_primary import Unmodelled

RPM = math.pi / 30.0
CONTROL_NAMES = {3: "user routine", 4: "Simulink/LabVIEW", 5: "Bladed-style DLL"}


@dataclass(frozen=True)
class ServoDyn:
    """The entries of a ServoDyn file bladefem uses (SI).

    pitch_mode : PCMode; torque_control : VSContrl; generator_model : GenModel; efficiency : GenEff / 100
    rated_generator_speed : VS_RtGnSp, rad/s; rated_torque : VS_RtTq, N m; region2_constant : VS_Rgn2K in
    N m / (rad/s)^2; slip : VS_SlPc / 100; yaw_neutral : YawNeut, rad; yaw_spring : YawSpr, N m/rad;
    yaw_damper : YawDamp, N m s/rad; events : label -> time (s) of the timed events; lines : label -> line
    controller : DLL_FileName, the Bladed-style controller library (run with PCMode and VSContrl 5), as written
    dll : the Bladed interface's entries (:class:`BladedInterface`), None without a DLL
    """

    path: str
    pitch_mode: int
    torque_control: int
    generator_model: int
    efficiency: float
    rated_generator_speed: float
    rated_torque: float
    region2_constant: float
    slip: float
    yaw_neutral: float
    yaw_spring: float
    yaw_damper: float
    settings: dict[str, float]
    lines: dict[str, tuple[str, int]]
    controller: str = ""
    dll: BladedInterface | None = None

    def unmodelled(self, end_time: float, controller: bool = False) -> list[Unmodelled]:
        """Settings that ask for behaviour bladefem does not model within a simulation ending at ``end_time``;
        ``controller``: the caller runs the Bladed-style DLL (a simulation), else a DLL deck runs only at --rpm."""
        found = []

        def refuse(label: str, message: str, way: str = "") -> None:
            key, line = self.lines[label]
            found.append(Unmodelled(self.path, line, key, message, way))

        dll = 5 in (self.pitch_mode, self.torque_control)
        if dll and controller and (self.pitch_mode, self.torque_control) != (5, 5):
            refuse("PCMode", f"a Bladed-style DLL for pitch or torque alone (PCMode {self.pitch_mode}, VSContrl "
                             f"{self.torque_control}) is not modelled: set both PCMode and VSContrl 5", "--rpm")
        elif dll and controller and self.dll is None:
            refuse("PCMode", "the Bladed interface's entries (DLL_FileName, DLL_InFile, DLL_DT, DLL_Ramp, BPCutoff, "
                             "Ptch_Cntrl, Ptch_Min, Ptch_Max, PtchRate_Min, PtchRate_Max) are missing", "--rpm")
        elif dll and controller:
            found.extend(self.dll.unmodelled(self.path))
        elif dll:
            label = "PCMode" if self.pitch_mode == 5 else "VSContrl"
            name = f" {self.controller}" if self.controller else ""
            refuse(label, f"the deck's Bladed-style DLL controller (DISCON{name}; PCMode {self.pitch_mode}, VSContrl "
                          f"{self.torque_control}) is not modelled outside a time simulation (--simulate runs it)",
                   "--rpm")
        if self.pitch_mode not in (0, 5):
            refuse("PCMode", f"pitch control PCMode {self.pitch_mode} ({CONTROL_NAMES.get(self.pitch_mode, '?')}) "
                             "is not modelled: set PCMode 0 (pitch fixed at ElastoDyn's BlPitch)")
        if self.torque_control not in (1, 5):
            what = CONTROL_NAMES.get(self.torque_control, "no variable-speed law" if self.torque_control == 0
                                     else "?")
            refuse("VSContrl", f"torque control VSContrl {self.torque_control} ({what}) is not modelled: set "
                               "VSContrl 1 (simple variable-speed law)")
        s = self.settings
        for label, message in (("YCMode", "yaw control"), ("AfCmode", "airfoil flow control"),
                               ("NumBStC", "blade structural control"), ("NumNStC", "nacelle structural control"),
                               ("NumTStC", "tower structural control"),
                               ("NumSStC", "substructure structural control")):
            if s.get(label, 0) != 0:
                refuse(label, f"{message} ({label} {s[label]:g}) is not modelled: set {label} 0")
        timed = [(f"TPitManS({i})", "pitch manoeuvre") for i in (1, 2, 3)] + [("TYawManS", "yaw manoeuvre")]
        if s.get("HSSBrMode", 0) != 0:
            timed.append(("THSSBrDp", "shaft-brake deployment"))
        if s.get("GenTiStp", 1):
            timed.append(("TimGenOf", "generator switch-off"))
        for label, message in timed:
            if label in s and s[label] < end_time:
                refuse(label, f"{message} at {s[label]:g} s is not modelled: move it beyond the end of the run",
                       "--rpm" if label == "TimGenOf" else "")
        # a rotor held at --rpm has its generator torque from the imposed speed: the switching times do not matter
        if not s.get("GenTiStr", 1):
            refuse("GenTiStr", "generator start at a speed (GenTiStr False) is not modelled: set GenTiStr True",
                   "--rpm")
        elif s.get("TimGenOn", 0) > 0:
            refuse("TimGenOn", f"generator switch-on at {s['TimGenOn']:g} s is not modelled: set TimGenOn 0", "--rpm")
        return found


#: Optional entries kept for :meth:`ServoDyn.unmodelled` (float, or 1/0 for flags).
SETTINGS = ("YCMode", "AfCmode", "NumBStC", "NumNStC", "NumTStC", "NumSStC", "TPitManS(1)", "TPitManS(2)",
            "TPitManS(3)", "TYawManS", "HSSBrMode", "THSSBrDp", "TimGenOn", "TimGenOf")
FLAGS = ("GenTiStr", "GenTiStp")


@dataclass(frozen=True)
class BladedInterface:
    """ServoDyn's Bladed-interface entries (SI).

    infile : DLL_InFile as written (relative to the ServoDyn file); time_step : DLL_DT, s (None: "default", the
    glue code's DT); ramp : DLL_Ramp; cutoff : BPCutoff, Hz; individual : Ptch_Cntrl 1; pitch_limits : Ptch_Min,
    Ptch_Max, rad; rate_limits : PtchRate_Min, PtchRate_Max, rad/s; lines : label -> line
    """

    infile: str
    time_step: float | None
    ramp: bool
    cutoff: float
    individual: bool
    pitch_limits: tuple[float, float]
    rate_limits: tuple[float, float]
    lines: dict[str, int]

    def unmodelled(self, path: str) -> list[Unmodelled]:
        """What of the interface bladefem does not model: a ramp between calls, the pitch filter."""
        found = []
        if self.ramp:
            found.append(Unmodelled(path, self.lines["DLL_Ramp"], "DLL_Ramp", "a linear ramp of the DLL's demands "
                                    "between calls is not modelled (they are held): set DLL_Ramp False"))
        if self.cutoff < MIN_CUTOFF:
            found.append(Unmodelled(path, self.lines["BPCutoff"], "BPCutoff", f"ServoDyn's low-pass filter on the "
                                    f"DLL's pitch ({self.cutoff:g} Hz) is not modelled: set BPCutoff 9999.9"))
        return found


#: BPCutoff (Hz) at and above which ServoDyn's pitch filter is absent: its factor exp(-2 pi DT f) is below 1e-17
#: at DT = 0.00625 s
MIN_CUTOFF = 1000.0


#: the Bladed-interface entries read
BLADED = ("DLL_FileName", "DLL_InFile", "DLL_DT", "DLL_Ramp", "BPCutoff", "Ptch_Cntrl", "Ptch_Min", "Ptch_Max",
          "PtchRate_Min", "PtchRate_Max")


def read_bladed(labels: Labels) -> BladedInterface:
    """The Bladed-interface entries of a ServoDyn file with a DLL."""
    names = BLADED[:6]
    return BladedInterface(
        infile=labels.string("DLL_InFile"),
        time_step=None if labels.is_default("DLL_DT") else labels.float("DLL_DT", positive=True),
        ramp=labels.bool("DLL_Ramp"), cutoff=labels.float("BPCutoff", positive=True),
        individual=labels.int("Ptch_Cntrl") == 1,
        pitch_limits=(math.radians(labels.float("Ptch_Min")), math.radians(labels.float("Ptch_Max"))),
        rate_limits=(math.radians(labels.float("PtchRate_Min")), math.radians(labels.float("PtchRate_Max"))),
        lines={name: labels.line(name) for name in names})


def read_servodyn(path: str | os.PathLike) -> ServoDyn:
    """Read a ServoDyn file; malformed entries are :class:`InputError` naming file, line and label. The torque-law
    constants are required only with VSContrl 1."""
    labels = Labels.read(path)
    torque_control = labels.int("VSContrl")
    law = torque_control == 1
    settings = {label: labels.float(label) for label in SETTINGS if labels.has(label)}
    settings.update({label: float(labels.bool(label)) for label in FLAGS if labels.has(label)})
    lines = {label: (labels.which(label), labels.line(label))
             for label in ("PCMode", "VSContrl", *SETTINGS, *FLAGS) if labels.has(label)}
    slip = labels.float("VS_SlPc", positive=True) / 100.0 if law else math.nan
    if law and slip >= 1.0:
        raise labels.error(f"must be below 100 %, got {slip * 100:g}", labels.line("VS_SlPc"), "VS_SlPc")
    return ServoDyn(
        path=labels.path, pitch_mode=labels.int("PCMode"), torque_control=torque_control,
        generator_model=labels.int("GenModel") if labels.has("GenModel") else 1,
        efficiency=labels.float("GenEff", positive=True) / 100.0,
        rated_generator_speed=labels.float("VS_RtGnSp", positive=True) * RPM if law else math.nan,
        rated_torque=labels.float("VS_RtTq", positive=True) if law else math.nan,
        region2_constant=labels.float("VS_Rgn2K", non_negative=True) / RPM ** 2 if law else math.nan,
        slip=slip, yaw_neutral=math.radians(labels.float("YawNeut")),
        yaw_spring=_bounded(labels, "YawSpr", MAX_YAW_STIFFNESS),
        yaw_damper=_bounded(labels, "YawDamp", MAX_YAW_DAMPING),
        settings=settings, lines=lines,
        controller=labels.string("DLL_FileName") if labels.has("DLL_FileName") else "",
        dll=read_bladed(labels) if 5 in (labels.int("PCMode"), torque_control)
        and all(labels.has(name) for name in BLADED) else None)


def _bounded(labels: Labels, label: str, largest: float) -> float:
    """A non-negative value of at most ``largest`` (see :mod:`bladefem.limits`: past it the yaw is locked)."""
    value = labels.float(label, non_negative=True)
    if value > largest:
        raise labels.error(f"must be at most {largest:g} (a stiffer yaw is a locked one: lock it with --dof yaw=off), "
                           f"got {value:g}", labels.line(label), label)
    return value
