"""The arrays the compiled load kernels (:mod:`.compiled_loads`) unpack: the aerodynamic model's (``aero``, built
once per model) and the per-call aerodynamic state (``state``), in the order the kernels index them.
"""

from __future__ import annotations

import numpy as np


#: columns of the rotor summary a call leaves in the state (``state[9]``)
HUB = ("thrust", "torque", "power", "tsr", "cp", "ct", "disk_velocity", "skew")


def aero_data(model) -> tuple:
    """The aerodynamic arrays of ``model`` in the order :func:`add_aero` unpacks them (empty arrays without
    aerodynamics, so that the kernels compile once for both); the last, (1,), the blades' pitch (rad) that the
    offsets, the sections' angles and their cant are set at (:mod:`.pitching` moves them together)."""
    from ...aero.rotor import Inflow
    from .aero import TurbineAero
    aero: TurbineAero | None = model.aero
    k = model.params.blade.n_modes
    if aero is None:
        empty = np.zeros(0)
        return (np.zeros((k, 0, 3)), np.zeros((k, k, 0)), empty, np.zeros((0, 3)), np.zeros((k, 0, 2)),
                np.zeros((0, 0)), empty, empty, empty, empty, empty, np.zeros(0, dtype=np.int64), np.zeros(1),
                np.zeros((1, 3)), np.zeros((1, 3, 4)), np.zeros(1, dtype=np.int64), np.ones(1, dtype=np.int64),
                np.zeros(13), np.zeros(2), *Inflow(0.0, 1.0).arrays(), np.zeros(3), empty, empty, np.zeros((0, 2)),
                np.zeros(1))
    across = np.zeros((k, aero.n_nodes, 3))
    across[:, :, 0] = aero.along
    across[:, :, 1:] = aero.value
    inflow, rotor = aero.inflow, aero.rotor
    knots, values, coefs, start, count = aero.polar_arrays
    return (across, aero.shortening.copy(), aero.axial.copy(), aero.offset.copy(),
            np.ascontiguousarray(aero.slope, dtype=float), aero.force_lumping(), aero.moment_weights(),
            rotor.chord.copy(), np.ascontiguousarray(aero.theta, dtype=float), aero.tip_constant.copy(),
            aero.hub_constant.copy(), rotor.airfoil.astype(np.int64), knots, values, coefs, start, count,
            aero.options.copy(), np.array([rotor.air_density, float(rotor.n_blades)]), *inflow.arrays(),
            *wake_data(aero, model.params.n_blades),
            np.column_stack([np.cos(rotor.curve_angle), np.sin(rotor.curve_angle)]), np.array([aero.pitch]))


def wake_data(aero, blades: int) -> tuple:
    """The dynamic wake's (model, tau1_const, k) (model 0: none), the nodes' weights in the disk-averaged induction
    (Na,) (one blade's, over the number of blades) and their undeflected r / R (Na,)."""
    from ...aero.dynamic_wake import disk_weights
    radius = aero.undeflected_radius
    weights = disk_weights(np.broadcast_to(radius, (blades, len(radius))))[0].copy()
    settings = aero.rotor.dynamic_wake if aero.wake_states else None
    return (np.zeros(3) if settings is None else settings.vector(), weights, radius / radius.max())


#: rows of the 3-vector scratch (``state[15]``) of the load kernels, which allocate nothing (compiled without
#: reference counting: the atomic increments and decrements of each per-node array view took about a sixth of a
#: right-hand side): the wind, the apex's velocity, the rotor's angular velocity, a beam node's offset, rate and
#: bias, the node's motion in earth axes, omega x rho; the disk-averaged relative wind and its in-plane direction,
#: a node force's arm x force, its moment, a blade's radial direction
(WIND, APEX_VELOCITY, OMEGA, OFFSET, RATE, BIAS, MOVING, SPUN, MEAN, IN_PLANE, ARM, LOAD, RADIAL) = range(13)
#: rows of the modal scratch (``state[17]``, 6 + k long): a blade's coordinates and rates, its lumped loads
(BLADE_Q, BLADE_U, SHARED) = range(3)


def aero_state(blades: int, nodes: int, modes: int) -> tuple:
    """Per node: offset from the apex rho, absolute velocity (B, Na, 3), R D (B, Na, 3, k), the bent section's
    normal and span axis (B, Na, 3; after the node solve the axes its loads act along), the relative wind
    (B, Na, 3), the node solutions (B, Na, 13), lumped forces and moments (B, Na, 3); the rotor summary
    (:data:`HUB`); the dynamic wake's states and their rates (B, Na, 4), the quasi-steady induced velocities
    (B, Na, 2; without the dynamic wake those of the last BEM solve) and (states given: 1 or 0, tau1 in s, the
    induction held: 1 or 0); the bent section's direction of rotation (B, Na, 3; after the solve the tangential
    load's axis); scratch: 3-vectors (13, 3, rows named above), a node's partials D (3, k), modal rows
    (3, 6 + k), the nodes' distances from the shaft (B, Na) and the blades' largest (B,)."""
    shape = (blades, nodes, 3)
    return (np.zeros(shape), np.zeros(shape), np.zeros((blades, nodes, 3, modes)), np.zeros(shape),
            np.zeros(shape), np.zeros(shape), np.zeros((blades, nodes, 13)), np.zeros(shape), np.zeros(shape),
            np.zeros(len(HUB)), np.zeros((blades, nodes, 4)), np.zeros((blades, nodes, 4)),
            np.zeros((blades, nodes, 2)), np.zeros(3), np.zeros(shape), np.zeros((13, 3)), np.zeros((3, modes)),
            np.zeros((3, 6 + modes)), np.zeros((blades, nodes)), np.zeros(blades))
