"""The generator: ServoDyn's simple variable-speed torque law (``VSContrl`` 1) and its efficiency.

The torque acts between the generator (high-speed shaft, turning ``GBRatio`` times the generator azimuth) and the
nacelle; in Kane's equations the pair's generalized force is ``-GBRatio T`` on ``generator_azimuth`` alone (the
nacelle's share cancels the generator's on every other coordinate). ServoDyn's law, with the high-speed-shaft speed
``w`` (rad/s):

    region 3     w >= VS_RtGnSp:                T = VS_RtTq
    region 2     w <  w_t:                      T = VS_Rgn2K w^2
    region 2.5   in between (the slip line):    T = s (w - w_sync),  w_sync = VS_RtGnSp / (1 + VS_SlPc),
                                                s = VS_RtTq / (VS_RtGnSp - w_sync)

with ``w_t`` where the slip line meets the region-2 parabola (``w_sync`` when ``VS_Rgn2K`` is 0, ``VS_RtGnSp`` when
the slip is below sqrt(machine epsilon)). Region 1 (below cut-in) does not exist in this law: the torque follows the
parabola down to zero speed. ServoDyn refuses a negative speed (motoring); here the torque is zero there. The
electrical power is ``GenPwr = T w GenEff``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: below this slip (fraction) ServoDyn has no region 2.5 (sqrt of single-precision epsilon)
MIN_SLIP = math.sqrt(np.finfo(np.float32).eps)


@dataclass(frozen=True)
class Generator:
    """Generator torque law and efficiency (SI: rad/s and N m on the high-speed shaft).

    torque_law : True for ServoDyn's simple variable-speed law (VSContrl 1); False: no torque (a free generator
        spins up; a locked one is held at its speed by whatever torque that takes)
    rated_speed : VS_RtGnSp, rad/s; rated_torque : VS_RtTq, N m; region2_constant : VS_Rgn2K, N m s^2/rad^2;
    slip : VS_SlPc as a fraction; efficiency : GenEff as a fraction
    """

    torque_law: bool = False
    rated_speed: float = math.inf
    rated_torque: float = 0.0
    region2_constant: float = 0.0
    slip: float = 0.1
    efficiency: float = 1.0

    @classmethod
    def from_servodyn(cls, servo) -> Generator:
        """The generator of a ServoDyn file (:class:`bladefem.builders.servodyn.ServoDyn`)."""
        if servo.torque_control != 1:
            return cls(efficiency=servo.efficiency)
        return cls(True, servo.rated_generator_speed, servo.rated_torque, servo.region2_constant, servo.slip,
                   servo.efficiency)

    @property
    def synchronous_speed(self) -> float:
        """w_sync of the slip line, rad/s."""
        return self.rated_speed / (1.0 + self.slip)

    @property
    def slope(self) -> float:
        """Slope of the slip line, N m s/rad."""
        return self.rated_torque / (self.rated_speed - self.synchronous_speed)

    @property
    def transition_speed(self) -> float:
        """Speed where region 2 ends and the slip line begins, rad/s (ServoDyn's VS_TrGnSp)."""
        if self.slip < MIN_SLIP:
            return self.rated_speed
        if self.region2_constant == 0.0:
            return self.synchronous_speed
        s = self.slope
        return (s - math.sqrt(s * (s - 4.0 * self.region2_constant * self.synchronous_speed))) / (
            2.0 * self.region2_constant)

    def vector(self) -> np.ndarray:
        """(law on, rated speed, rated torque, K, slope, synchronous speed, transition speed) for the kernels."""
        if not self.torque_law:
            return np.zeros(7)
        return np.array([1.0, self.rated_speed, self.rated_torque, self.region2_constant,
                         self.slope if self.slip >= MIN_SLIP else 0.0, self.synchronous_speed,
                         self.transition_speed])

    def torque(self, speed: float) -> float:
        """Generator torque (N m) at the high-speed-shaft speed ``speed`` (rad/s)."""
        return law_torque(self.vector(), speed)


def law_torque(law: np.ndarray, speed: float) -> float:
    """The torque law of :meth:`Generator.vector` at the high-speed-shaft speed (rad/s), N m."""
    if law[0] == 0.0 or speed <= 0.0:
        return 0.0
    if speed >= law[1]:
        return law[2]
    if speed < law[6]:
        return law[3] * speed * speed
    return law[4] * (speed - law[5])
