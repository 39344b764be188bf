"""The rest phase of a PyBullet run (`Settings.phased`, docs/bullet.md "Phased stepping"):
while the block rests on its base and the base's absolute acceleration stays below the
uplift threshold, Bullet is not stepped (the shared rules: `isorock.analytic.rest_phase`).

- fixed base: the block rides the ground, its state is constant;
- isolated base: block and base move as one body of mass M = m + m_b under the isolator
  force and the ground motion, as the stepping loop drives Bullet: the force
  −(k(u + l·u̇) + c(u̇ + l·ü)) held over a control step (l the sub-steps' mean lead, ü
  from the last step) and Bullet's semi-implicit Euler sub-steps (v += h·a, then
  x += h·v, n times: u' = u + dt·u̇ + dt²·a·(n+1)/(2n), u̇' = u̇ + dt·a). One control
  step is a linear map of (u, u̇, u̇ one step back), run through `rest_states`.
"""
from __future__ import annotations

import numpy as np

from ..analytic.rest_phase import (F_LOW, LEAD_TIME, REST_RATE, REST_SPEED, REST_TILT, SETTLE_TIME,
                                         first_hot, rest_states, takeover)
from ..analytic import kinematics
from ..analytic.system import System


#: s between two looks for rest while the contact scene is stepped.
CHECK_TIME = 0.02


class Rest:
    """When a run may rest, and its rest phases' states."""

    def __init__(self, system: System, dt: float, substeps: int, lead: float, xg: np.ndarray):
        self.system, self.dt, self.xg = system, dt, np.asarray(xg, dtype=float)
        self.threshold = system.uplift_acceleration
        self.lead_steps = int(round(LEAD_TIME / dt))
        self.settle_rows = max(2, int(round(SETTLE_TIME / dt)))
        #: control steps between two looks for rest (a look reads SETTLE_TIME of rows)
        self.check_every = max(1, int(round(CHECK_TIME / dt)))
        self.tilt, self.rate = REST_TILT * system.alpha, REST_RATE * system.alpha * system.p
        self.speed = REST_SPEED * system.gravity / system.p
        if not system.fixed_base:
            m, k, c = system.total_mass, system.stiffness, system.damping
            q = dt * dt * (substeps + 1) / (2 * substeps)
            au, av, ap = -k / m, -(k * lead + c + c * lead / dt) / m, c * lead / (dt * m)
            self.a = np.array([[1 + q * au, dt + q * av, q * ap], [dt * au, 1 + dt * av, dt * ap], [0.0, 1.0, 0.0]])
            self.b = np.array([-q, -dt, 0.0])

    def acceleration(self, u, ud) -> np.ndarray:
        """|ü + ẍg| of a base carrying the resting block: the isolator's force over M."""
        return np.abs(self.system.stiffness * np.asarray(u) + self.system.damping * np.asarray(ud)) / self.system.total_mass

    def may_rest(self, rows: list, i: int) -> bool:
        """Whether the block has rested over the last SETTLE_TIME of rows (one per control
        step: (t, u, u̇, x, y, z, qx, qy, qz, qw, ω_y, ẋ)) and the base's acceleration at step i
        is below F_LOW of the threshold."""
        if len(rows) < self.settle_rows:
            return False
        a_now = abs(self.xg[min(i, self.xg.size - 1)]) if self.system.fixed_base else self.acceleration(rows[-1][1], rows[-1][2])
        if a_now >= F_LOW * self.threshold:
            return False
        r = np.array(rows[-self.settle_rows:], dtype=float)
        qx, qy, qz, qw = r[:, 6:10].T
        theta = kinematics.tilts_from_quaternion(qw, qx, qy, qz)[0]
        dt = np.diff(r[:, 0])
        slide = np.abs(np.diff(r[:, 3] - r[:, 1])) / dt  # the block's x relative to the base
        lift = np.abs(np.diff(r[:, 5])) / dt
        return bool(np.all(np.abs(theta) < self.tilt) and np.all(np.abs(r[:, 10]) < self.rate)
                    and np.all(slide < self.speed) and np.all(lift < self.speed))

    def phase(self, i: int, end: int, u: float, ud: float, ud_prev: float):
        """The rest phase from control step i (state u, u̇, u̇ one step back) up to at most
        step `end`: (steps, states) — the number of steps skipped (the contact scene takes
        over at step i + steps, LEAD_TIME before |a| first reaches F_HIGH·threshold) and
        the (u, u̇, u̇ one step back) after each of them (zeros on a fixed base)."""
        if self.system.fixed_base:
            hot = takeover(self.xg[i:end], self.threshold, self.lead_steps)
            steps = end - i if hot is None else hot
            return steps, np.zeros((steps, 3))
        states, hot = rest_states(self.a, self.b, (u, ud, ud_prev), self.xg[i:end],
                                  lambda x: self.acceleration(x[0], x[1]) / self.threshold)
        if states is None:  # a repeated mode: step the map itself
            states, x = np.zeros((3, end - i)), np.array([u, ud, ud_prev])
            for j, f in enumerate(self.xg[i:end]):
                x = self.a @ x + self.b * f
                states[:, j] = x
            hot = first_hot(self.acceleration(states[0], states[1]), self.threshold)
        # states[:, j] is after step i + j, one step past the record's index
        steps = states.shape[1] if hot is None else max(0, hot + 1 - self.lead_steps)
        return steps, states[:, :steps].T
