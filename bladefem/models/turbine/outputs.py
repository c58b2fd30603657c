"""Output channels of a turbine simulation with OpenFAST's names, definitions, units and signs (ElastoDyn,
AeroDyn, ServoDyn), the numpy version of the load channels (:mod:`.compiled_outputs` is the compiled one), the CSV
table and the figure.

Signs (checked against OpenFAST v4.2.1 runs of the same deck, docs/turbine.md): tip deflections in the coned blade
frame (``OoPDefl1`` along ``xc1`` downwind, ``IPDefl1`` along ``yc1`` toward the trailing edge), tower-top
displacements downwind and to the left looking downwind, root moments ``RootMOoP1 = RootMyc1`` (from downwind
loads) and ``RootMIP1 = RootMxc1`` (from loads toward the leading edge), shaft loads acting from the rotor on the
shaft (``RotThrust`` downwind along the shaft, ``RotTorq`` in the direction of rotation), aerodynamic loads on the
rotor about the hub (``RtAeroFxh`` downwind, ``RtAeroMxh`` in the direction of rotation), tower-base moments of the
turbine above the base about the base's earth axes (``TwrBsMyt`` fore-aft, from downwind loads positive;
``TwrBsMxt`` side-to-side, from loads to the right looking downwind positive).
"""

from __future__ import annotations

import os

import numpy as np
from numpy.typing import NDArray

from ...files import atomic_path, write_atomic

RAD_S_TO_RPM = 30.0 / np.pi

#: output channel -> (unit, description), in table order
CHANNELS = {
    "OoPDefl1": ("m", "blade 1 tip out-of-plane deflection, positive downwind (xc1)"),
    "IPDefl1": ("m", "blade 1 tip in-plane deflection, positive toward the trailing edge (yc1)"),
    "TTDspFA": ("m", "tower-top fore-aft displacement, positive downwind"),
    "TTDspSS": ("m", "tower-top side-to-side displacement, positive to the left looking downwind"),
    "YawPzn": ("deg", "nacelle yaw angle"),
    "Azimuth": ("deg", "rotor azimuth (blade 1 up at 0)"),
    "RotSpeed": ("rpm", "rotor speed (low-speed shaft at the hub)"),
    "LSSGagVxa": ("rpm", "low-speed-shaft speed at the gearbox"),
    "GenSpeed": ("rpm", "generator (high-speed shaft) speed"),
    "RootMOoP1": ("kN m", "blade 1 root out-of-plane bending moment (from downwind loads positive)"),
    "RootMIP1": ("kN m", "blade 1 root in-plane bending moment (from loads toward the leading edge positive)"),
    "TwrBsMxt": ("kN m", ("tower-base side-to-side (roll) moment about the downwind axis xt, from loads to the right "
                          "looking downwind positive")),
    "TwrBsMyt": ("kN m", "tower-base fore-aft (pitch) moment about the lateral axis yt, from downwind loads positive"),
    "RotThrust": ("kN", ("low-speed-shaft thrust: rotor (hub and blades) aerodynamic, gravity and inertial loads "
                         "along the shaft, downwind positive")),
    "RotTorq": ("kN m", "low-speed-shaft torque from the rotor, positive in the direction of rotation"),
    "RotPwr": ("kW", "low-speed-shaft power, RotTorq x RotSpeed"),
    "GenTq": ("kN m", ("generator torque on the high-speed shaft (the law's; with a locked generator the torque "
                       "that holds its speed)")),
    "GenPwr": ("kW", "electrical power, GenTq x GenSpeed x GenEff"),
    "BldPitch1": ("deg", "blade 1 pitch angle"),
    "RtAeroFxh": ("N", "aerodynamic rotor thrust along the shaft (hub x), downwind positive"),
    "RtAeroMxh": ("N m", "aerodynamic rotor torque about the shaft (hub x), in the direction of rotation"),
    "RtAeroPwr": ("W", "aerodynamic rotor power, RtAeroMxh x rotor speed"),
    "RtTSR": ("-", "tip-speed ratio: rotor speed x largest node radius / disk-averaged relative wind"),
    "RtAeroCp": ("-", "power coefficient: RtAeroPwr / (1/2 rho pi R^2 V^3), V the disk-averaged relative wind"),
    "RtAeroCt": ("-", "thrust coefficient: RtAeroFxh / (1/2 rho pi R^2 V^2)"),
}
#: channels that exist only with aerodynamics (AeroDyn's)
AERO_CHANNELS = ("RtAeroFxh", "RtAeroMxh", "RtAeroPwr", "RtTSR", "RtAeroCp", "RtAeroCt")
#: columns of :func:`load_row` (and of the compiled outputs), SI
LOAD_COLUMNS = ("root_oop", "root_ip", "shaft_thrust", "shaft_torque", "generator_torque", "aero_thrust",
                "aero_torque", "aero_power", "tsr", "cp", "ct", "disk_velocity", "skew", "aero_work",
                "damping_power", "tower_base_x", "tower_base_y")


def load_row(model, q: NDArray, u: NDArray, du: NDArray, blade: int = 0, t: float = 0.0,
             wake: NDArray | None = None) -> NDArray:
    """The :data:`LOAD_COLUMNS` at one state with accelerations ``du`` (numpy reference of the compiled kernel):
    root moments of ``blade`` from gravity, d'Alembert and aerodynamic loads; the rotor's (hub and blades) loads
    along and about the shaft; the generator torque of the law plus the generalized force holding a locked
    generator; the aerodynamic summary; the power of the aerodynamic loads and of the damping (wind at time t; the
    dynamic wake's states ``wake``); the tower-base moment about the base's x and y axes (:func:`tower_base_moment`)."""
    from .aero import aero_loads
    p = model.params
    motion = model.motion(q, u)
    M, f = model.equations(q, u, t=t, wake=wake)
    nodes = motion.blades
    a = np.einsum("bpkm,bm->bpk", nodes.G, np.einsum("bmn,n->bm", nodes.Z, du)) + nodes.a
    loads = model.blade_masses[..., None] * (model.gravity - a)
    positions, forces, moments = nodes.r, loads, np.zeros_like(loads)
    summary, aero_work = np.zeros(8), 0.0
    if model.aero is not None:
        aero = aero_loads(model, model.aero, q, u, t, wake=wake)
        positions = np.concatenate([positions, aero.positions], axis=1)
        forces = np.concatenate([forces, aero.forces], axis=1)
        moments = np.concatenate([moments, aero.moments], axis=1)
        summary = np.array([aero.thrust, aero.torque, aero.power, aero.tsr, aero.cp, aero.ct, aero.disk_velocity,
                            aero.skew])
        aero_work = float(u @ aero.generalized)
    R = motion.blade_frames.R[blade]
    root = motion.apex.r + R[:, 0] * p.hub_radius
    own = np.sum(np.cross(positions[blade] - root, forces[blade]) + moments[blade], axis=0)
    rigid = motion.rigid
    hub_load = p.hub_mass * (model.gravity - (rigid.J[2] @ du + rigid.a[2]))
    shaft = motion.rotor.R[:, 0]
    spin = shaft @ (motion.rotor.W @ du + motion.rotor.alpha)
    total_force = forces.sum(axis=(0, 1)) + hub_load
    total_moment = (np.sum(np.cross(positions - motion.apex.r, forces) + moments, axis=(0, 1))
                    + np.cross(rigid.r[2] - motion.apex.r, hub_load))
    g = model.dofs.index("generator_azimuth")
    ratio = p.gearbox_ratio
    law = model.generator.torque(ratio * u[g]) if model.generator is not None else 0.0
    base = tower_base_moment(model, motion, du, positions, forces, moments)
    return np.array([-(own @ R[:, 1]), own @ R[:, 2], total_force @ shaft,
                     total_moment @ shaft - p.hub_inertia * spin, law - (M[g] @ du - f[g]) / ratio, *summary,
                     aero_work, u @ model.C @ u, base[0], base[1]])


def tower_base_moment(model, motion, du: NDArray, positions: NDArray, forces: NDArray, moments: NDArray) -> NDArray:
    """Moment (3,), N m, about the tower base of the loads on the turbine above it, earth components (ElastoDyn's
    ``TwrBsMxt``, ``TwrBsMyt``, ``TwrBsMzt`` of a fixed base): ``sum (r - r_base) x m (g - a)`` over the tower,
    nacelle and hub masses, the blade nodes' gravity, d'Alembert and aerodynamic forces (``forces`` at ``positions``,
    (B, N, 3)) and moments, less the rate of change of the rotary bodies' angular momentum,
    ``I [k (k . alpha) + (k . omega) omega x k]`` (nacelle about the yaw axis, hub and generator about the shaft).
    The springs, dampers and generator torque between these bodies are internal and cancel."""
    tower, rigid = motion.tower, motion.rigid
    tower_a = np.einsum("pkm,m->pk", tower.G, tower.Z @ du) + tower.a
    points = np.concatenate([tower.r, rigid.r, positions.reshape(-1, 3)])
    loads = np.concatenate([model.tower_masses[:, None] * (model.gravity - tower_a),
                            model.rigid_masses[:, None] * (model.gravity - (rigid.J @ du + rigid.a)),
                            forces.reshape(-1, 3)])
    total = np.sum(np.cross(points - model.base.r, loads), axis=0) + moments.sum(axis=(0, 1))
    for frame, axis, inertia in model.rigid_bodies(motion):
        alpha = frame.W @ du + frame.alpha
        total -= inertia * (axis * (axis @ alpha) + (axis @ frame.omega) * np.cross(frame.omega, axis))
    return total


def channels(model, q: NDArray, u: NDArray, loads: NDArray) -> dict[str, NDArray]:
    """The output channels (units of :data:`CHANNELS`) for coordinates and rates (T, n) and the load columns
    (T, len(LOAD_COLUMNS)), SI; the aerodynamic channels only when the model has aerodynamics."""
    p = model.params
    column = {name: loads[:, i] for i, name in enumerate(LOAD_COLUMNS)}
    tip = q[:, model.blade_columns[0]] @ p.blade.tip_value          # (T, 2): in-plane toward the LE, out-of-plane
    top = q[:, model.tower_columns] @ p.tower.tip_value             # (T, 2): fore-aft, side-side
    rotor_speed = u[:, 5] + u[:, 6]
    generator_speed = p.gearbox_ratio * u[:, 5]
    efficiency = model.generator.efficiency if model.generator is not None else 1.0
    pitch = model.aero.pitch if model.aero is not None else p.pitch
    out = {
        "OoPDefl1": tip[:, 1], "IPDefl1": -tip[:, 0], "TTDspFA": top[:, 0], "TTDspSS": top[:, 1],
        "YawPzn": np.degrees(q[:, 4]), "Azimuth": np.degrees(q[:, 5] + q[:, 6]) % 360.0,
        "RotSpeed": rotor_speed * RAD_S_TO_RPM, "LSSGagVxa": u[:, 5] * RAD_S_TO_RPM,
        "GenSpeed": generator_speed * RAD_S_TO_RPM, "RootMOoP1": column["root_oop"] / 1e3,
        "RootMIP1": column["root_ip"] / 1e3, "TwrBsMxt": column["tower_base_x"] / 1e3,
        "TwrBsMyt": column["tower_base_y"] / 1e3, "RotThrust": column["shaft_thrust"] / 1e3,
        "RotTorq": column["shaft_torque"] / 1e3, "RotPwr": column["shaft_torque"] * rotor_speed / 1e3,
        "GenTq": column["generator_torque"] / 1e3,
        "GenPwr": column["generator_torque"] * generator_speed * efficiency / 1e3,
        "BldPitch1": np.full(len(q), np.degrees(pitch)),
    }
    if model.aero is not None:
        out.update({"RtAeroFxh": column["aero_thrust"], "RtAeroMxh": column["aero_torque"],
                    "RtAeroPwr": column["aero_power"], "RtTSR": column["tsr"], "RtAeroCp": column["cp"],
                    "RtAeroCt": column["ct"]})
    return out


def table_text(result) -> str:
    """CSV text: time and every output channel of ``result`` (a SimulationResult), with units in the header."""
    names = [name for name in CHANNELS if name in result.outputs]
    header = "Time_s," + ",".join(f"{name}_{CHANNELS[name][0].replace(' ', '')}" for name in names)
    data = np.column_stack([result.time] + [result.outputs[name] for name in names])
    body = "\n".join(",".join(row) for row in np.char.mod("%.9g", data))
    return header + "\n" + body + "\n"


def write_table(result, path: str | os.PathLike) -> None:
    """Write the output table as CSV, atomically."""
    write_atomic(path, table_text(result))


def plot_outputs(result, path: str | os.PathLike,
                 channels: tuple[str, ...] = ("OoPDefl1", "IPDefl1", "TTDspFA", "TTDspSS", "YawPzn", "RotSpeed",
                                               "GenSpeed", "RootMOoP1", "RootMIP1", "RotThrust", "RotPwr"),
                 title: str = "") -> None:
    """Plot the chosen channels against time into an image file (written atomically), titled with ``title`` (the
    case: deck, wind, rotor speed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    channels = tuple(name for name in channels if name in result.outputs)
    figure, axes = plt.subplots(len(channels), 1, figsize=(8, 1.6 * len(channels)), sharex=True,
                               layout="constrained")
    for axis, name in zip(np.atleast_1d(axes), channels):
        axis.plot(result.time, result.outputs[name], lw=1)
        axis.set_ylabel(f"{name}\n[{CHANNELS[name][0]}]", fontsize=8)
        axis.grid(alpha=0.3)
    np.atleast_1d(axes)[-1].set_xlabel("time [s]")
    if title:
        figure.suptitle(title, fontsize=10)
    try:
        with atomic_path(path) as temporary:
            figure.savefig(temporary, dpi=120)
    finally:
        plt.close(figure)
