"""Stepping that follows the run's phase (`Settings.phased`, docs/mujoco.md "Phased
stepping"): while the block sits on its base and the base's absolute acceleration
|a| = |ü + ẍg| stays well below the uplift threshold g·tanα (= g·b/h), nothing about
contact happens, so the contact scene is not stepped:

- on a fixed base the block moves with the ground: its state is constant;
- on an isolated base block and base move as one body, the 1-DOF oscillator
  M ü + c u̇ + k u = −M ẍg (M = m + m_b), integrated by MuJoCo's own step of a reduced
  scene (one body of mass M on the same slide joint, same stiffness, damping, timestep
  and integrator, no contact), so the history stays MuJoCo's integration of the
  isolator; that step is written out (`isolator_steps`, equal to MuJoCo's to rounding,
  tested), since MuJoCo's fixed cost per step would make the rest phase cost a third of
  the contact scene's.

The full scene takes over LEAD_TIME before |a| first reaches F_HIGH·g·tanα (restored
from the resting block's offsets, recorded when the rest phase began), and the reduced
one again once the block has rested for SETTLE_TIME with |a| < F_LOW·g·tanα (the rules
every engine shares: `isorock.analytic.rest_phase`). Every step of a rest phase gives one
row in the full scene's state layout, so measuring is unchanged. Within the full scene,
`Flight` steps coarse away from impacts. Runs that start tilted (free rocking) are
stepped in full throughout.
"""
from __future__ import annotations

import copy
import functools
import math

import mujoco
import numpy as np
from mujoco import rollout

# the shared rules (thresholds, lead and settle times, "at rest"): one home for every engine
from ..analytic.rest_phase import (F_HIGH, F_LOW, LEAD_TIME, REST_RATE, REST_SPEED, REST_TILT,
                                         SETTLE_TIME, first_hot, linear_steps, rest_states, takeover)
from ..analytic.system import System

from .state import fresh_data

#: Steps per full-scene rollout call while looking for rest (the steps of a call past
#: the row where rest is found are discarded).
FULL_CHUNK = 256


def applies(settings, theta0: float, motion, nstep: int) -> bool:
    """Whether a run is stepped by phases: asked for, starting at rest (free rocking
    starts tilted and is stepped in full), with the planar joints of the default
    stepping scheme, and a record that moves."""
    return (getattr(settings, "phased", False) and theta0 == 0.0 and settings.joint == "planar"
            and settings.impact_timestep is None and nstep > 0 and not motion.is_zero)


@functools.lru_cache(maxsize=32)
def reduced_model(mass: float, stiffness: float, damping: float, timestep: float, integrator: str) -> mujoco.MjModel:
    """Block and base as one body on the isolator's slide joint: no contact, no gravity
    (nothing vertical moves)."""
    xml = f"""<mujoco model="isorock-rest">
  <option timestep="{timestep!r}" integrator="{integrator}" gravity="0 0 0">
    <flag autoreset="disable" island="disable" contact="disable"/>
  </option>
  <worldbody>
    <body name="rigid">
      <joint name="base_slide" type="slide" axis="1 0 0" stiffness="{stiffness!r}" damping="{damping!r}"/>
      <inertial pos="0 0 0" mass="{mass!r}" diaginertia="1 1 1"/>
    </body>
  </worldbody>
</mujoco>"""
    return mujoco.MjModel.from_xml_string(xml)


class Phases:
    """What a phased run needs besides the full scene: the threshold, the rest test over
    state rows, and the rest phase's rows."""

    def __init__(self, model, lay, system: System, settings, xg, dt: float):
        self.lay, self.system, self.xg, self.dt = lay, system, xg, dt
        self.threshold = system.uplift_acceleration
        self.lead = int(round(LEAD_TIME / dt))
        self.settle = max(1, int(round(SETTLE_TIME / dt)))
        scale_v = system.gravity / system.p
        self.tilt, self.rate, self.speed = REST_TILT * system.alpha, REST_RATE * system.alpha * system.p, REST_SPEED * scale_v
        self.integrator = settings.integrator
        #: a rest phase keeps a row every `store` steps (the contact phases' coarse step)
        self.store = coarse_multiple(settings)
        v0 = 1 + lay.nq
        self.v = slice(v0, v0 + lay.nv)

    def absolute_acceleration(self, u, u_dot, steps) -> np.ndarray:
        """|ü + ẍg| of the base at rows after `steps`: on an isolated base (block resting
        on it) the isolator's force over the whole mass; on a fixed base the record."""
        if self.system.fixed_base:
            return np.abs(self.xg[np.minimum(steps, self.xg.size - 1)])
        return np.abs(self.system.stiffness * u + self.system.damping * u_dot) / self.system.total_mass

    def rest_finder(self):
        """until(chunk, steps, hist) for a full phase (`steps`: each row's step index; `hist`: the
        chunk's Layout.histories): the index of the row ending SETTLE_TIME of rest with
        |a| < F_LOW·threshold, or None."""
        lay, broken = self.lay, [None]  # step index of the last row not at rest, carried across calls

        def until(chunk, steps, h):
            vel = chunk[:, self.v]
            rest = ((np.abs(h["theta"]) < self.tilt) & (np.abs(h["theta_dot"]) < self.rate)
                    & (np.abs(vel[:, lay.x_v] - h["u_dot"]) < self.speed) & (np.abs(vel[:, lay.z_v]) < self.speed))
            quiet = self.absolute_acceleration(h["u"], h["u_dot"], steps) < F_LOW * self.threshold
            if broken[0] is None:
                broken[0] = int(steps[0]) - 1
            # steps since the last row not at rest (rows may be coarse: counted in steps)
            i = np.arange(chunk.shape[0])
            last_break = np.maximum.accumulate(np.where(rest, -1, i))
            since = steps - np.where(last_break >= 0, steps[np.maximum(last_break, 0)], broken[0])
            if not rest.all():
                broken[0] = int(steps[np.nonzero(~rest)[0][-1]])
            found = np.nonzero((since >= self.settle) & quiet)[0]
            if found.size:
                return int(found[0])
            return None
        return until

    def rest(self, row: np.ndarray, k: int, nstep: int):
        """The rest phase from step k (the full scene's row `row`, block at rest): the rows
        of steps k+1 … s in the full layout, every `store`-th step and step s (the block
        rests, the base swings slowly: the rows between would add nothing a measure
        reads), the step s where the full scene takes over (nstep: never), and the warm
        start to resume it with."""
        lay, dt = self.lay, self.dt
        template = row.copy()
        template[self.v] = 0.0
        if self.system.fixed_base:
            end = takeover(self.xg, self.threshold, self.lead, start=k)
            s = nstep if end is None else end
            steps = self._stored(k, s)
            rows = np.repeat(template[None, :], steps.size, axis=0)
            rows[:, 0] = steps * dt
            return rows, s, np.zeros(lay.nv)
        u0 = row[1 + lay.base_q]
        dx = row[1 + lay.xq] - u0
        u, v, hot = self._isolator(u0, row[1 + lay.nq + lay.base_v], k, nstep)
        # u[i] is the state after step k + i: one step later than the record's index
        s = nstep if hot is None else k + max(0, hot + 1 - self.lead)
        steps = self._stored(k, s)
        us, vs = u[steps - k - 1], v[steps - k - 1]
        rows = np.repeat(template[None, :], steps.size, axis=0)
        rows[:, 0] = steps * dt
        rows[:, 1 + lay.base_q] = us
        rows[:, 1 + lay.xq] = us + dx
        rows[:, 1 + lay.nq + lay.base_v] = vs
        rows[:, 1 + lay.nq + lay.x_v] = vs
        warm = np.zeros(lay.nv)
        if s - k >= 2:  # block and base accelerate together: qacc of the last step
            warm[lay.base_v] = warm[lay.x_v] = (v[s - k - 1] - v[s - k - 2]) / dt
        return rows, s, warm

    def _stored(self, k: int, s: int) -> np.ndarray:
        """The steps of k+1 … s a rest phase keeps a row of: every `store`-th and s."""
        steps = np.arange(k + self.store, s + 1, self.store)
        if s > k and (steps.size == 0 or steps[-1] != s):
            steps = np.append(steps, s)
        return steps

    def _isolator(self, u0: float, v0: float, k: int, nstep: int):
        """(u, u̇, first hot) after steps k, k+1, … of the 1-DOF oscillator from (u0, v0),
        far enough to hold the first state whose |a| reaches F_HIGH of the threshold (its
        index, or None: then up to nstep)."""
        sy, f = self.system, -self.system.total_mass * self.xg[k:nstep]
        if self.integrator in MATCHED:
            a, b = isolator_map(sy.total_mass, sy.stiffness, sy.damping, self.dt)
            states, hot = rest_states(a, b, (u0, v0), f, lambda x: self.absolute_acceleration(x[0], x[1], None)
                                      / self.threshold)
            if states is not None:
                return states[0], states[1], hot
        u, v = reduced_steps(sy.total_mass, sy.stiffness, sy.damping, self.dt, self.integrator, u0, v0, f)
        return u, v, first_hot(self.absolute_acceleration(u, v, None), self.threshold)


#: Integrators whose step of the reduced scene `isolator_steps` writes out: semi-implicit
#: Euler with the joint damping implicit (MuJoCo's Euler, implicit and implicitfast are
#: the same map for one slide joint with a linear spring and dashpot).
MATCHED = ("Euler", "implicit", "implicitfast")


def isolator_steps(mass, stiffness, damping, dt, u0, v0, f) -> tuple[np.ndarray, np.ndarray]:
    """MuJoCo's step of the reduced scene, written out: with M̃ = M + dt·c,
    v' = v + dt (f − k u − c v)/M̃, u' = u + dt v'. A linear map x' = A x + B f, run
    mode by mode through scipy's lfilter (C speed; a Python loop, or MuJoCo's own step of
    the one-body scene, costs ~2 µs a step, as much as stepping the contact scene): an
    underdamped isolator's two modes are complex conjugates, so one complex filter gives
    both (x = 2·Re of its mode); an overdamped one has two real modes. Modes, not the
    direct-form recursion of u alone, whose poles so near 1 lose ~1e-10 of u over a record
    (measured). Agrees with `reduced_steps` to rounding (tested)."""
    x = linear_steps(*isolator_map(mass, stiffness, damping, dt), np.array([u0, v0]), f)
    if x is None:  # a repeated mode (critical damping): step MuJoCo's scene
        return reduced_steps(mass, stiffness, damping, dt, "implicitfast", u0, v0, f)
    return x[0], x[1]


def isolator_map(mass, stiffness, damping, dt) -> tuple[np.ndarray, np.ndarray]:
    """(A, B) of MuJoCo's step of the reduced scene, x = (u, u̇): x' = A x + B f."""
    mt = mass + dt * damping
    a = np.array([[1 - dt * dt * stiffness / mt, dt * (1 - dt * damping / mt)],
                  [-dt * stiffness / mt, 1 - dt * damping / mt]])
    return a, np.array([dt * dt / mt, dt / mt])


def reduced_steps(mass, stiffness, damping, dt, integrator, u0, v0, f) -> tuple[np.ndarray, np.ndarray]:
    """The reduced scene stepped by MuJoCo (`reduced_model`): u and u̇ after each step."""
    model = reduced_model(mass, stiffness, damping, dt, integrator)
    state = np.zeros(mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS))
    state[1], state[2] = u0, v0
    out, _ = rollout.rollout(model, mujoco.MjData(model), state, np.asarray(f, dtype=float)[None, :, None],
                             control_spec=mujoco.mjtState.mjSTATE_QFRC_APPLIED)
    return out[0][:, 1].copy(), out[0][:, 2].copy()


#: Fine steps start when the block would reach θ = 0 within IMPACT_ZONE coarse steps at its
#: present rate (and |θ̇| > MIN_RATE·α·p: a block at rest stays coarse) ...
IMPACT_ZONE = 2.0
MIN_RATE = 1e-3
#: ... and go on until SETTLE_TAUS contact time constants after the last sign change of θ
#: (the impact's transient, critically damped or slower, is over within a few τ).
SETTLE_TAUS = 20
#: Coarse steps per rollout call at most (a call runs about as far as the next impact zone).
COARSE_CHUNK = 256


def coarse_multiple(settings) -> int:
    """The whole multiple of the timestep taken away from impacts: `settings.coarse`
    (settings.COARSE_STEPS by default: why there), at most
    the contact time constant over two steps (so the coarse step stays within MuJoCo's
    τ ≥ 2·step and the contact is the same), and 1 for the direct solref form (its
    stiffness and damping are tied to the step) and event-resolved stepping."""
    if settings.solref[0] <= 0 or settings.impact_timestep is not None:
        return 1
    fit = int(math.floor(settings.solref[0] / (2 * settings.timestep) + 1e-9))
    return max(1, min(settings.coarse, fit))


def coarse_applies(settings) -> bool:
    """Whether a run steps coarse away from impacts (Flight): its stepping follows the
    run's phase (`phased`), with the planar joints of the default scheme and a coarse
    multiple above 1. Free rocking too: over the atlas's 100 cells it moved the worst β
    error from 0.527% to 0.509% and t₁'s from 0.017% to 0.040%, 1.6× faster
    (docs/mujoco.md, "Coarse steps away from impacts")."""
    return (settings.phased and settings.joint == "planar" and settings.impact_timestep is None
            and coarse_multiple(settings) > 1)


_coarse: dict = {}


def coarse_model(model: mujoco.MjModel, multiple: int) -> mujoco.MjModel:
    """The same scene with a step `multiple` times `model`'s (everything else, the contact
    included, equal), kept for the runs that follow (a copy costs ~0.15 ms). Never changed
    once made, so threads share it."""
    key = (id(model), multiple)
    entry = _coarse.get(key)
    if entry is None or entry[0] is not model:  # the id of a model since freed
        if len(_coarse) >= 64:
            _coarse.clear()
        coarse = copy.copy(model)
        coarse.opt.timestep = model.opt.timestep * multiple
        entry = _coarse[key] = (model, coarse)
    return entry[1]


class Flight:
    """Where a contact phase steps coarse and where fine: fine from IMPACT_ZONE coarse steps
    before θ crosses 0 (an impact) until SETTLE_TAUS·τ after it, coarse elsewhere. The rows
    of a coarse step sit every `multiple` timesteps: the history is not uniform in time
    (RawHistory.t says when each row is)."""

    def __init__(self, model, lay, system: System, settings, dt: float):
        self.lay, self.system, self.dt = lay, system, dt
        self.multiple = coarse_multiple(settings)
        self.model = coarse_model(model, self.multiple)
        self.data = fresh_data(self.model)
        self.rate = MIN_RATE * system.alpha * system.p
        self.reach = IMPACT_ZONE * self.multiple * dt  # s: the zone, as a time to θ = 0
        self.settle = max(1, int(math.ceil(SETTLE_TAUS * settings.solref[0] / dt)))
        self.last_cross = -(10 ** 12)  # step index of the last sign change of θ
        self.refine = False  # a coarse call was cut where θ changed sign: step fine from there
        self.theta = 0.0  # θ at the row the current call started from (plan)

    def in_zone(self, theta, theta_dot):
        return (np.abs(theta_dot) > self.rate) & (np.abs(theta) < self.reach * np.abs(theta_dot))

    def plan(self, theta: float, theta_dot: float, k: int, nstep: int) -> tuple[int, int]:
        """(multiple, steps) of the next rollout call from step k, where the block's tilt is
        θ = `theta`, θ̇ = `theta_dot`: fine (multiple 1) within an impact's zone or its
        settling, else coarse, about as far as the next zone (the call is cut there
        afterwards, by `keep`)."""
        self.theta = theta  # the row the call starts from: `keep` looks for sign changes after it
        coarse = (nstep - k) // self.multiple
        if (self.multiple == 1 or self.refine or k - self.last_cross < self.settle
                or self.in_zone(theta, theta_dot) or coarse < 2):
            self.refine = False
            return 1, min(max(self.settle, 16), nstep - k)
        if abs(theta_dot) > self.rate and theta * theta_dot < 0:  # heading for θ = 0
            ahead = int(abs(theta / theta_dot) / (self.multiple * self.dt))
            return self.multiple, max(2, min(ahead, COARSE_CHUNK, coarse))
        return self.multiple, min(COARSE_CHUNK, coarse)

    def keep(self, th: np.ndarray, thd: np.ndarray, steps: np.ndarray, multiple: int) -> int:
        """How many rows of a call (θ `th`, θ̇ `thd` at each) to keep, noting sign changes of
        θ: all of a fine call; a coarse call up to its first row inside an impact zone, or
        up to the row before θ changed sign outside one (stepped again fine from there)."""
        before = np.concatenate(([self.theta], th))
        crossed = np.sign(before[1:]) * np.sign(before[:-1]) < 0
        if multiple == 1:
            if crossed.any():
                self.last_cross = int(steps[np.nonzero(crossed)[0][-1]])
            return th.size
        stop = np.nonzero(self.in_zone(th, thd) | crossed)[0]
        if stop.size == 0:
            return th.size
        i = int(stop[0])
        if crossed[i]:  # the impact fell within a coarse step: the rows before it stand
            self.refine = True
            return i
        return i + 1
