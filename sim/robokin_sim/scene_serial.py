"""A serial arm (any chain: the catalogue's arms, a URDF file) in 3-D: jog, postures, paths.

* Joint jog: ``1`` ... ``9`` (or ``tab``) select a joint, ``plus`` / ``minus`` held move it by
  :data:`JOINT_STEP` per step (rad, or m for a prismatic joint). The value is the selection's start
  value plus a whole number of steps, so ``plus*20`` lands exactly on ``q_i + 20 * 0.01``; a joint
  stops exactly on its limit.
* Cartesian jog: the arrows and ``pageup`` / ``pagedown`` move the tool by :data:`MOVE_STEP` per
  step along the base's x, y and z; with ``shift`` they turn it by :data:`TURN_STEP` about those
  axes (through the tool point). Each step is one resolved-rate step of the core
  (``rk.resolved_rate``: damped least squares, the damping growing near singularities, with the
  RPR study's null-space joint-limit term on redundant arms) followed by the core's Reach loop from
  there to the commanded pose (``rk.reach``, gain 1, to 1e-11), so the tool lands on the commanded
  pose and the rest of the pose does not drift. A step the arm cannot take (a joint limit, the
  workspace boundary, a singularity that would make the joints jump) is refused: the arm stays and
  the panel says why. The rows controlled are the arm's natural task (``chain.natural_task``).
* ``n``: the next closed-form posture (``robokin.closed``) of the current tool pose, reached along a
  joint-space quintic (``rk.traj.quintic``), animated. Keys acting on the arm pressed during such a
  move (or an approach) are queued and applied after it, in order: ``n`` pressed 9 times shows 9
  postures.
* ``o`` / ``p``: a circle / a straight line through the start pose's tool point, in the plane the
  tool moves in most easily there (vertical, facing the robot, for a 3-D arm; the floor plane for a
  planar arm), solved in one call by the core's path IK (``rk.ik_batch(..., path=True)``) and
  traced one point per step. A path leaving the arm's reach is made smaller (PATH_SCALES) until
  every point is reached; points still out of reach are reported (``state`` ``unreachable``, red
  on the path) and the arm holds still there. ``m`` goes back to jogging.
* ``e`` the velocity ellipsoid, ``f1`` - ``f4`` / ``v`` the camera's views (at zoom 1), the mouse
  orbits and zooms (the camera is view state, kept by the scene so that the window and the
  recording agree); ``r`` resets the camera with the arm.
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque
from typing import FrozenSet, Optional, Tuple

import numpy as np
import robokin as rk
from robokin.plots import joint_axes

from . import serial_model as model
from .camera import VIEW_ORDER, Camera
from .scene import DT, Scene, reach_quietly

#: Joint jog per step: rad for revolute joints, m for prismatic ones.
JOINT_STEP = {"R": 0.01, "P": 0.002}
#: Cartesian jog per step: m, rad.
MOVE_STEP, TURN_STEP = 0.002, 0.01
#: Largest joint change one Cartesian step may ask for (rad or m): more means a singularity.
MAX_JOINT_STEP = 0.1
#: Damping of the resolved-rate step: small away from singularities, growing to DAMPING_MAX as the
#: manipulability falls below the "near" level (Nakamura's rule).
DAMPING_MIN, DAMPING_MAX = 1e-4, 0.05
#: The Reach loop's tolerance on the pose error after a jog step, and its iterations.
REACH_TOL, REACH_ITER = 1e-11, 30
#: Path size relative to the arm's size, path points per circle, spacing of the line (relative).
PATH_SIZE, CIRCLE_POINTS, LINE_STEP = 0.12, 360, 0.004
#: The path's sizes tried in turn (times PATH_SIZE): one with points out of the arm's reach at the
#: start's orientation (a 7-joint arm's ready pose) is made smaller until every point is reached;
#: the smallest is kept otherwise, its unreachable points drawn red.
PATH_SCALES = (1.0, 0.5, 0.25)
#: Joint speed (rad/s or m/s) of posture changes and approaches; their shortest duration (s).
MOVE_SPEED, MIN_MOVE = 1.0, 0.5
#: Trail points kept.
TRAIL = 1500

#: Key -> (translation axis) for the arrows and page keys; with shift the same axes are turned about.
AXIS_KEYS = {"right": (0, 1), "left": (0, -1), "up": (1, 1), "down": (1, -1), "pageup": (2, 1), "pagedown": (2, -1)}
#: Which of the 6 directions (vx, vy, vz, wx, wy, wz) each task can command.
TASK_DIRECTIONS = {"pose": (0, 1, 2, 3, 4, 5), "position": (0, 1, 2), "xyphi": (0, 1, 5), "xy": (0, 1)}
#: Keys that act on the arm: pressed during an animated move they wait for its end (at most
#: MAX_QUEUED of them).
QUEUED_KEYS = frozenset({"1", "2", "3", "4", "5", "6", "7", "8", "9", "tab", "m", "o", "p", "n", "s"})
MAX_QUEUED = 64
#: Preset views keyed by f1 .. f4.
VIEW_KEYS = dict(zip(("f1", "f2", "f3", "f4"), VIEW_ORDER))


@dataclasses.dataclass
class SerialState:
    """What the renderer needs."""

    title: str
    q: np.ndarray
    frames: np.ndarray  # (dof + 1, 4, 4)
    joint_types: str
    axes: np.ndarray  # (dof, 2, 3): a point on each joint's axis and its unit direction
    lower: np.ndarray
    upper: np.ndarray
    selected: int
    position: np.ndarray  # tool (3,)
    rpy: np.ndarray  # (3,)
    manipulability: float
    ratio: float  # manipulability / the arm's best (reference)
    state: str  # none | near | singular | limit | unreachable
    mode: str
    posture: str
    ellipsoid: Optional[Tuple[np.ndarray, np.ndarray]]  # (axes (3, 3), lengths (3,)) or None
    path: Optional[np.ndarray]  # (K, 3) path points, or None
    missed: Optional[np.ndarray]  # (K,) bool: points the path IK could not reach
    trail: np.ndarray  # (T, 3)
    camera: Camera
    size: float
    floor: float  # z of the floor (base frame, m); below the base, the base stands on a pedestal
    planar: bool
    task: str
    avoid: bool
    redundant: bool
    message: str


class SerialScene(Scene):
    """The scene of one serial chain.

    Args:
        chain: The arm.
        name: Its catalogue name (selects its start posture and its closed form), or ``"urdf"``.
        title: What the panel calls it (default: ``name``).
        mode: ``"free"``, ``"circle"`` or ``"line"``.
        avoid: Seed 000's null-space joint-limit term on redundant arms (else minimum norm).
        q0: The start posture (default :func:`serial_model.start_posture`).
    """

    def __init__(self, chain: rk.Chain, name: str = "urdf", title: Optional[str] = None, mode: str = "free",
                 avoid: bool = True, q0=None) -> None:
        super().__init__()
        if not isinstance(chain, rk.Chain):
            raise TypeError(f"chain: expected a robokin.Chain, got {type(chain).__name__}")
        if mode not in ("free", "circle", "line"):
            raise ValueError(f"mode: a serial arm has modes free, circle and line, got {mode!r}")
        self.chain = chain
        self.robot = name
        self.title = title or name
        self.dof = chain.dof
        self.columns = ("step", "time", "mode", *(f"q_{i}" for i in range(self.dof)), "x", "y", "z", "roll", "pitch",
                        "yaw", "manipulability", "state")
        self.lower, self.upper = (np.asarray(v, dtype=float) for v in chain.limits)
        self.q_start = model.start_posture(chain) if q0 is None else np.clip(
            np.asarray(q0, dtype=float), self.lower, self.upper)
        self.solver = model.posture_solver(name, chain, self.q_start)
        self.planar = model.is_planar(chain)
        self.task = chain.natural_task
        self.redundant = self.dof > len(TASK_DIRECTIONS[self.task])
        self.size = model.size_of(chain, self.q_start)
        self.w_ref = model.reference_manipulability(chain)
        self.floor_start = self.floor = model.floor_height(chain, self.q_start, self.size)
        # Planar arms: the disc of their reach from above; others: the start posture's frame
        # origins and the pedestal's foot, from the iso view (and fitting every preset view).
        if self.planar:
            self.camera = Camera(np.zeros(3), 1.05 * self.size, "top")
        else:
            origins = self.chain.frames(self.q_start)[:, :3, 3]
            foot = [origins[0, 0], origins[0, 1], self.floor]
            self.camera = Camera.fitting(np.vstack([origins, foot]), "iso")
        self.start_mode = mode
        self.start_avoid = bool(avoid)
        self.trail: deque = deque(maxlen=TRAIL)
        self._paths: dict = {}
        self._queue: deque = deque()  # (key, held) pressed during an animated move
        self.reset()

    # --- the model, through the core ----------------------------------------------------------
    def _set(self, q) -> None:
        """Moves the arm to q and evaluates what the panel and the log show there."""
        self.q = np.asarray(q, dtype=float).copy()
        self.frames = self.chain.frames(self.q)
        lowest = float(np.min(self.frames[:, 2, 3]))
        if lowest < self.floor:  # below the sampled reach (an unlimited slide): the floor goes down
            self.floor = lowest - model.FLOOR_CLEARANCE * self.size
        tool = self.frames[-1]
        self.position = tool[:3, 3].copy()
        self.rpy = rk.pose.rpy(tool)
        self.w = float(self.chain.manipulability(self.q))
        self.ratio = self.w / self.w_ref
        at_limit = bool(np.any((self.q - self.lower <= 1e-9) | (self.upper - self.q <= 1e-9)))
        if self.ratio < model.SINGULAR_RATIO:
            self.sing = "singular"
        elif self.ratio < model.NEAR_RATIO:
            self.sing = "near"
        else:
            self.sing = "limit" if at_limit else "none"

    def _damping(self) -> float:
        if self.ratio >= model.NEAR_RATIO:
            return DAMPING_MIN
        share = 1.0 - (self.ratio / model.NEAR_RATIO) ** 2
        return math.sqrt(DAMPING_MIN ** 2 + share * DAMPING_MAX ** 2)

    # --- keys ---------------------------------------------------------------------------------
    def reset(self) -> None:
        """The start again: the arm at its start posture in the start mode, the camera as it began,
        no key waiting."""
        self.camera.reset()
        self._queue.clear()
        self.avoid = self.start_avoid
        self.selected = 0
        self.trail.clear()
        self.floor = self.floor_start
        self._set(self.q_start)
        self._go_free("joint")
        self.posture = ""
        self._postures = None  # (T, IKSolutions) of the last cycle, while the arm stays on it
        self.show_ellipsoid = False
        self.message = ""
        if self.start_mode != "free":
            self._start_path(self.start_mode)

    def _go_free(self, kind: str) -> None:
        self.mode = kind
        self.path = self.missed = self._path_q = None
        self._index = 0
        self._motion, self._after = None, None
        self._command = self.frames[-1].copy()
        self._jog = None  # (joint, value at selection, whole steps since)

    def press(self, key: str, held: FrozenSet[str] = frozenset()) -> None:
        """A key went down. While the arm makes an animated move (a posture change, an approach)
        the keys that act on the arm (:data:`QUEUED_KEYS`) wait and are applied in order after it
        (those after one that starts a move of its own wait for that move); ``r`` and the view keys
        act at once."""
        if key in QUEUED_KEYS and (self._motion is not None or self._queue):
            if len(self._queue) < MAX_QUEUED:
                self._queue.append((key, held))
                self.message = f"{' '.join(k for k, _ in self._queue)}: after this move"
            return
        self._apply(key, held)

    def _apply(self, key: str, held: FrozenSet[str]) -> None:
        if key in ("1", "2", "3", "4", "5", "6", "7", "8", "9"):
            k = int(key) - 1
            if k < self.dof:
                self.selected, self._jog = k, None
                self.message = f"joint {k + 1} selected: + / - move it"
            else:
                self.message = f"this arm has {self.dof} joints"
        elif key == "tab":
            self.selected, self._jog = (self.selected + 1) % self.dof, None
            self.message = f"joint {self.selected + 1} selected: + / - move it"
        elif key == "m":
            if self.mode in ("circle", "line"):
                self.trail.clear()
                self._go_free("joint")
            self.message = "free mode: + / - jog a joint, arrows and page keys move the tool"
        elif key in ("o", "p"):
            self._start_path("circle" if key == "o" else "line")
        elif key == "n":
            self._next_posture()
        elif key == "e":
            self.show_ellipsoid = not self.show_ellipsoid
            self.message = "velocity ellipsoid (translation) " + ("on" if self.show_ellipsoid else "off")
        elif key == "s":
            self.avoid = not self.avoid
            if self.redundant:
                self.message = "null-space joint-limit avoidance " + ("on" if self.avoid else "off (minimum norm)")
            else:
                self.message = "not redundant: no null space to use"
        elif key in VIEW_KEYS:
            self.camera.set_view(VIEW_KEYS[key])
            self.message = f"{self.camera.view} view"
        elif key == "v":
            self.message = f"{self.camera.next_view()} view"
        elif key == "r":
            self.reset()
            self.message = "reset"

    def pointer(self, drag, wheel) -> None:
        self.camera.orbit(*drag)
        self.camera.zoom_by(wheel)

    # --- postures -----------------------------------------------------------------------------
    def _next_posture(self) -> None:
        if self.solver is None:
            self.message = "no closed form for this arm: one posture (use the jog)"
            return
        if self._postures is not None and np.allclose(self.chain.fk(self.q), self._postures[0], rtol=0, atol=1e-9):
            pose, solutions = self._postures
        else:
            pose = self.frames[-1].copy()
            try:
                solutions = self.solver(pose)
            except ValueError as exc:  # a closed form that does not apply here after all
                self.message = f"no closed-form postures here: {exc}"
                return
        if len(solutions) == 0:
            self.message = "the closed form finds no posture within the limits here"
            return
        self._postures = (pose, solutions)
        current = solutions.nearest(self.q)
        k = 0 if current is None else (current + 1) % len(solutions)
        if len(solutions) == 1:
            self.message = f"one posture only: {solutions.postures[0]}"
        label = f"{k + 1} / {len(solutions)}: {solutions.postures[k]}"
        after = self.mode if self.mode in ("joint", "cartesian") else "joint"
        self._move_to(solutions.q[k], "posture", after, done=f"posture {label}")
        self.posture = label

    def _move_to(self, q, mode: str, after: str, done: str = "") -> None:
        """Moves to q along a joint-space quintic, one sample per step, then goes on in ``after``."""
        q = np.asarray(q, dtype=float)
        distance = float(np.max(np.abs(q - self.q))) if self.dof else 0.0
        steps = max(int(math.ceil(max(distance / MOVE_SPEED, MIN_MOVE) / DT)), 1)
        traj = rk.traj.quintic(self.q, q, np.arange(steps + 1) * DT)
        self._motion = deque(traj.q[1:])
        self.mode, self._after, self._done = mode, after, done
        self.message = done + " (moving)" if done else "approaching the start"

    # --- paths ----------------------------------------------------------------------------------
    def _plane(self):
        """Two unit vectors spanning the path's plane at the start pose."""
        p = self.chain.fk(self.q_start)[:3, 3]
        if self.planar:  # across the arm's reach (tangential), then outward
            out = np.array([p[0], p[1], 0.0])
            out = out / np.linalg.norm(out) if np.linalg.norm(out) > 1e-9 else np.array([1.0, 0.0, 0.0])
            return np.cross([0.0, 0.0, 1.0], out), out
        axes, lengths = self.chain.ellipsoid(self.q_start)
        if lengths[2] < 1e-9 * max(lengths[0], 1e-300):
            # The tool moves in a plane only (e.g. the PRR of the DH exercise): that plane.
            return axes[:, 0], axes[:, 1]
        out = np.array([p[0], p[1], 0.0])
        out = out / np.linalg.norm(out) if np.linalg.norm(out) > 1e-9 else np.array([1.0, 0.0, 0.0])
        side = np.cross([0.0, 0.0, 1.0], out)
        return side, np.array([0.0, 0.0, 1.0])

    def _path(self, name: str):
        """(points (K, 3), IK targets, joints (K, dof), missed (K,)) of path ``name``, solved once: the
        largest of PATH_SCALES whose every point is reached, else the smallest."""
        if name not in self._paths:
            for scale in PATH_SCALES:
                path = self._solved_path(name, scale * PATH_SIZE * self.size)
                if not path[3].any():  # every point reached
                    break
            self._paths[name] = path
        return self._paths[name]

    def _solved_path(self, name: str, r: float):
        """Path ``name`` of size r through the start's tool point, solved along (path=True)."""
        start = self.chain.fk(self.q_start)
        p0 = start[:3, 3]
        u, w = self._plane()
        if name == "circle":
            flat = rk.paths.circle(CIRCLE_POINTS, radius=r)  # starts at (r, 0)
            points = p0 + np.outer(flat[:, 0] - r, u) + np.outer(flat[:, 1], w)
        else:
            there = rk.paths.line(p0, p0 + 2 * r * u, LINE_STEP * self.size)
            points = np.concatenate([there, there[-2:0:-1]])  # there and back: a loop
        if self.task == "pose":
            targets = np.repeat(start[None], len(points), axis=0)
            targets[:, :3, 3] = points
        elif self.task == "position":
            targets = points
        elif self.task == "xy":
            targets = points[:, :2]
        else:
            phi = math.atan2(start[1, 0], start[0, 0])
            targets = np.column_stack([points[:, :2], np.full(len(points), phi)])
        res = rk.ik_batch(self.chain, targets, self.q_start, task=self.task, path=True)
        q = np.asarray(res.q, dtype=float).copy()
        missed = ~np.asarray(res.success, dtype=bool)
        for k in range(len(q)):  # an unreached point holds the joints of the point before
            if missed[k]:
                q[k] = q[k - 1] if k else self.q_start
        return points, targets, q, missed

    def _start_path(self, name: str) -> None:
        points, _, q, missed = self._path(name)
        self.trail.clear()
        self.path, self.missed, self._path_q = points, missed, q
        self._index = 0
        n_missed = int(np.count_nonzero(missed))
        self._path_message = (f"{name}: {len(points)} points, all reached" if not n_missed else
                              f"{name}: {n_missed} of {len(points)} points unreachable (red)")
        if np.max(np.abs(q[0] - self.q)) > 1e-12:
            self._move_to(q[0], "approach", name, done=self._path_message)
        else:
            self.mode, self._motion = name, None
            self.message = self._path_message

    # --- one step -------------------------------------------------------------------------------
    def advance(self, held: FrozenSet[str]) -> None:
        while self._motion is None and self._queue:  # the keys pressed during the last move
            self._apply(*self._queue.popleft())
        if self._motion is not None:
            self._set(self._motion.popleft())
            if self.mode == "approach":
                self.trail.append(self.position.copy())
            if not self._motion:
                self._motion = None
                self.mode = self._after
                self._command = self.frames[-1].copy()
                self._jog = None
                self.message = self._done
            return
        if self.mode in ("circle", "line"):
            self._index = (self._index + 1) % len(self._path_q)
            self._set(self._path_q[self._index])
            if self.missed[self._index]:
                self.sing = "unreachable"
            self.trail.append(self.position.copy())
            return
        if "plus" in held or "minus" in held:
            self._joint_step(("plus" in held) - ("minus" in held))
        elif any(k in held for k in AXIS_KEYS):
            self._cartesian_step(held)

    def _joint_step(self, sign: int) -> None:
        if sign == 0:
            return
        i = self.selected
        if self._jog is None or self._jog[0] != i:
            self._jog = (i, float(self.q[i]), 0)
        joint, anchor, count = self._jog
        step = JOINT_STEP[self.chain.joint_types[i]]
        value = anchor + (count + sign) * step
        q = self.q.copy()
        if value > self.upper[i] or value < self.lower[i]:
            limit = self.upper[i] if sign > 0 else self.lower[i]
            if q[i] == limit:
                self.message = f"joint {i + 1} is at its {'upper' if sign > 0 else 'lower'} limit"
                return
            q[i] = limit
            self._jog = None  # the next jog counts from the limit
        else:
            q[i] = value
            self._jog = (joint, anchor, count + sign)
        self.mode = "joint"
        self._set(q)
        self._command = self.frames[-1].copy()
        self.message = ""

    def _cartesian_step(self, held: FrozenSet[str]) -> None:
        twist = np.zeros(6)
        rotate = "shift" in held
        for key, (axis, sign) in AXIS_KEYS.items():
            if key in held:
                twist[axis + (3 if rotate else 0)] += sign
        if not np.any(twist):
            return
        allowed = TASK_DIRECTIONS[self.task]
        wanted = np.flatnonzero(twist)
        if any(k not in allowed for k in wanted):
            names = ("x", "y", "z", "about x", "about y", "about z")
            self.message = (f"this arm's tool cannot be commanded {', '.join(names[k] for k in wanted if k not in allowed)}"
                            f" (its {self.dof} joints control {self.task})")
            return
        command = self._command.copy()
        if rotate:
            angle_axis = twist[3:] * TURN_STEP
            command[:3, :3] = rk.pose.exp(np.r_[0.0, 0.0, 0.0, angle_axis])[:3, :3] @ command[:3, :3]
            delta = np.r_[0.0, 0.0, 0.0, angle_axis]
        else:
            command[:3, 3] += twist[:3] * MOVE_STEP
            delta = np.r_[twist[:3] * MOVE_STEP, 0.0, 0.0, 0.0]
        rows = list(TASK_DIRECTIONS[self.task])
        target = self._task_target(command)
        nullspace = "joint_limits" if (self.redundant and self.avoid) else None
        damping = self._damping()
        qd = rk.resolved_rate(self.chain, self.q, delta[rows] / DT, damping=damping, nullspace=nullspace,
                              task=self.task)
        guess = np.clip(self.q + DT * np.asarray(qd), self.lower, self.upper)
        res = reach_quietly(self.chain, target, guess, task=self.task, max_iter=REACH_ITER, tol=REACH_TOL, gain=1.0,
                            dt=DT)
        q = np.asarray(res.q, dtype=float)
        jump = float(np.max(np.abs(q - self.q))) if np.all(np.isfinite(q)) else math.inf
        self.mode = "cartesian"
        if res.converged and jump <= MAX_JOINT_STEP:
            self._set(q)
            self._command = command
            self._jog = None
            self.message = self._singularity_warning()
            return
        at_limit = [i + 1 for i in range(self.dof) if q[i] <= self.lower[i] + 1e-9 or q[i] >= self.upper[i] - 1e-9]
        if self.ratio < model.NEAR_RATIO or (res.converged and jump > MAX_JOINT_STEP):
            why = f"near a singularity (manipulability {self.w:.2g}, {100 * self.ratio:.1f} % of the best)"
            self.sing = "singular" if self.ratio < model.SINGULAR_RATIO else "near"
        elif at_limit:
            why = f"joint {', '.join(map(str, at_limit))} at its limit"
            self.sing = "limit"
        else:
            why = "out of reach"
        self.message = f"step refused: {why}"

    def _task_target(self, command: np.ndarray):
        if self.task == "pose":
            return command
        if self.task == "position":
            return command[:3, 3]
        if self.task == "xy":
            return command[:2, 3]
        return np.array([command[0, 3], command[1, 3], math.atan2(command[1, 0], command[0, 0])])

    def _singularity_warning(self) -> str:
        if self.sing in ("near", "singular"):
            return f"{self.sing} singularity: manipulability {self.w:.2g} ({100 * self.ratio:.1f} % of the best)"
        return ""

    # --- output ---------------------------------------------------------------------------------
    def row(self):
        return (self.steps, self.time, self.mode, *self.q.tolist(), *self.position.tolist(), *self.rpy.tolist(),
                self.w, self.sing)

    def state(self) -> SerialState:
        ellipsoid = self.chain.ellipsoid(self.q) if self.show_ellipsoid else None
        return SerialState(
            title=self.title, q=self.q, frames=self.frames, joint_types=self.chain.joint_types,
            axes=joint_axes(self.chain, self.q),
            lower=self.lower, upper=self.upper, selected=self.selected, position=self.position, rpy=self.rpy,
            manipulability=self.w, ratio=self.ratio, state=self.sing, mode=self.mode, posture=self.posture,
            ellipsoid=ellipsoid, path=self.path, missed=self.missed,
            trail=np.array(self.trail) if self.trail else np.zeros((0, 3)), camera=self.camera, size=self.size,
            floor=self.floor, planar=self.planar, task=self.task, avoid=self.avoid, redundant=self.redundant,
            message=self.message,
        )
