"""The 3-RRR planar parallel robot of the 3-RRR project: free, circle and clover modes (state and step logic).

* Free mode: the arrows move the effector 1 mm per step, ``k`` / ``l`` rotate it 0.01 rad; a step
  that would leave the workspace, stretch a leg (serial singularity) or land on a parallel
  singularity is refused and the effector stays.
  Free-mode poses are kept as whole numbers of steps from an anchor pose, so ``right*20`` from the
  origin ends at exactly ``x = 0.02``.
* Circle and clover: the seed program's curves, one point per step; the orientation comes from the
  core's avoidance planner (tilting before a parallel singularity, back after) or stays constant
  without avoidance. Switching to a path from elsewhere first moves the effector to the path's
  start in 1 mm / 0.01 rad steps (the "approach" rows of the log) along the core's
  ``RRR3.connect``: det A keeps its sign and stays clear of zero, so no approach crosses a
  parallel singularity.
* Which side: det A cannot change sign without a parallel singularity, so a path is traced on the
  robot's side. Its orientation is planned about the nominal orientation nearest to 0 (0, +-0.05,
  ... +-1.5 rad) at which the whole path is on the robot's side, clear of singularities (with
  avoidance; without, orientation 0 when the path's start is on the robot's side there). From
  home (det A < 0) the circle is traced about a tilted orientation for that reason: at
  orientation 0 it lies on the other side. When no orientation works, or no singularity-free
  approach exists, the switch is refused with a message and the robot stays.
* ``r`` goes back to where the run started (home, or the start of its path) along a
  singularity-free route; avoidance stays as the user set it. A robot driven across a parallel
  singularity in free mode has no such route: ``r`` then restarts at home (and says so).

Every kinematic quantity (inverse model, Jacobian determinants, singularity state, workspace, the
avoidance plan) comes from ``robokin.RRR3``.
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque
from typing import FrozenSet, Optional

import numpy as np
import robokin as rk

from . import rrr3_model as model
from .scene import Scene, arrows

#: Free-mode move per step (m) and rotation per step (rad), as in the seed program.
MOVE_STEP, TURN_STEP = 0.001, 0.01
#: Path points per turn: t advances 2 pi / 628 ~ 0.01 rad per step and the loop closes exactly.
PATH_POINTS = 628
#: The seed program's curves: circle radius, clover scale K.
CIRCLE_RADIUS, CLOVER_K = 0.1, 0.02
#: Working mode of the seed program (beta = +acos).
WORKING_MODE = (1, 1, 1)
#: Trail points kept (a little more than one turn of a path).
TRAIL = 700
HOME = (0.0, 0.0, 0.0)


@dataclasses.dataclass
class Rrr3State:
    """What the renderer needs."""

    pose: np.ndarray  # (x, y, phi)
    alpha: np.ndarray  # (3,)
    points: Optional[dict]  # "O", "A", "B": (3, 2) each
    det_a: float
    det_b: float
    det_a_norm: float  # det A / R_e
    det_b_norm: float  # det B / l1^3
    state: str  # none | near | parallel | serial
    mode: str  # free | approach | circle | clover
    working_mode: tuple
    avoid: bool
    path: Optional[np.ndarray]
    trail: np.ndarray
    distance: float  # to a parallel singularity, in [0, 1]
    workspace: Optional[model.Workspace]  # constant-orientation map at the current phi
    message: str


class Rrr3Scene(Scene):
    """The 3-RRR scene.

    Args:
        mode: ``"free"``, ``"circle"`` or ``"clover"``.
        avoid: Start with singularity avoidance on.
    """

    robot = "rrr3"
    columns = ("step", "time", "mode", "x", "y", "phi", "alpha_0", "alpha_1", "alpha_2", "det_a", "det_b",
               "det_a_norm", "det_b_norm", "distance", "avoid", "state")

    def __init__(self, mode: str = "free", avoid: bool = True) -> None:
        super().__init__()
        if mode not in ("free", "circle", "clover"):
            raise ValueError(f"mode: the 3-RRR scene has modes free, circle and clover, got {mode!r}")
        self.robot_model = rk.RRR3()
        self.working_mode = WORKING_MODE
        self.paths = {
            "circle": rk.paths.circle(PATH_POINTS, radius=CIRCLE_RADIUS),
            "clover": rk.paths.clover(PATH_POINTS, k=CLOVER_K),
        }
        self.start_mode = mode
        self.start_avoid = bool(avoid)
        self.trail: deque = deque(maxlen=TRAIL)
        self._workspace_cache: dict = {}
        self._plans: dict = {}
        self.reset()

    # --- the model, through the core ----------------------------------------------------------
    def _evaluate(self, pose):
        """The core's :class:`~robokin_sim.rrr3_model.Evaluation` at ``pose``, or None if a leg cannot reach it."""
        return model.evaluate(self.robot_model, pose, self.working_mode)

    def _set(self, pose, evaluated) -> None:
        alpha, det_a, det_b, distance, state, det_a_norm, det_b_norm = evaluated
        if self._last_det_a is not None and det_a * self._last_det_a < 0 and state in ("none", "near"):
            # det A changed sign between two samples: a parallel singularity was crossed between
            # them. Report it rather than hide it behind the sampling.
            state = "parallel"
        self.pose = np.asarray(pose, dtype=float)
        self.alpha, self.det_a, self.det_b, self.sing = alpha, det_a, det_b, state
        self.det_a_norm, self.det_b_norm = det_a_norm, det_b_norm
        self.distance = distance
        self._last_det_a = det_a if det_a != 0 else self._last_det_a
        self._points = None

    # --- keys ---------------------------------------------------------------------------------
    def reset(self) -> None:
        """Back to where the run started: home, then the start mode (see the module's notes)."""
        if not hasattr(self, "pose"):  # the first reset: the run starts at home
            self.avoid = self.start_avoid
            self._last_det_a = None
            self._set(HOME, self._evaluate(HOME))
            self._go_free()
            self.message = ""
            if self.start_mode != "free":
                self._start_path(self.start_mode)
            return
        self.trail.clear()
        if self.start_mode != "free":
            self._start_path(self.start_mode, reset=True)
            return
        try:
            poses = model.route(self.robot_model, self.pose, HOME, self.working_mode, MOVE_STEP, TURN_STEP)
        except rk.NoRouteError:
            self._restart()
            return
        self._go_free()
        self._path_name = None
        self._approach, self._after_approach = poses, "free"
        self.mode = "approach" if len(poses) else "free"
        self.message = "reset: back to home"
        if not len(poses):
            self._go_free()

    def _restart(self) -> None:
        """Home at once: the robot was driven across a parallel singularity, and every way back crosses one."""
        self._last_det_a = None
        self._set(HOME, self._evaluate(HOME))
        self._go_free()
        self.message = "reset: restarted at home (every way back crossed a parallel singularity)"
        if self.start_mode != "free":
            self._start_path(self.start_mode)
            self.message = "reset: restarted at home (every way back crossed a parallel singularity)"

    def _go_free(self) -> None:
        self.mode, self.path, self._plan, self._index = "free", None, None, 0
        self._approach, self._after_approach = None, None
        self._path_name = None
        self._anchor = self.pose.copy()
        self._counts = np.zeros(3, dtype=np.int64)

    def press(self, key: str, held: FrozenSet[str] = frozenset()) -> None:
        if key == "m":
            if self.mode == "free":
                self.message = "already in free mode: arrows move, k / l rotate"
            else:
                self.trail.clear()
                self._go_free()
                self.message = "free mode: arrows move, k / l rotate"
        elif key == "o":
            self._start_path("circle")
        elif key == "p":
            self._start_path("clover")
        elif key == "s":
            self.avoid = not self.avoid
            said = "singularity avoidance on" if self.avoid else "singularity avoidance off"
            self.message = said
            if self._path_name is not None:
                # Re-plan the orientations and move to the new plan's pose at the current point
                # (an approach, never a jump in phi).
                if self._start_path(self._path_name, index=self._index, keep_trail=True):
                    self.message = said + (": " + self.message if self.mode == "approach" else "")
                else:  # no way to the new plan: keep the old one
                    self.avoid = not self.avoid
                    self.message = f"avoidance stays {'on' if self.avoid else 'off'}: " + self.message
        elif key == "r":
            self.reset()

    def _orientation_plan(self, name: str, sign: int):
        """(orientations (K,), nominal phi) for path ``name`` on the side ``sign`` of det A, or None."""
        key = (name, self.avoid, sign)
        if key not in self._plans:  # planning takes ~0.1 s per nominal orientation: once per path and side
            self._plans[key] = model.path_orientations(self.robot_model, self.paths[name], self.working_mode,
                                                       sign, self.avoid)
        return self._plans[key]

    def _start_path(self, name: str, index: int = 0, keep_trail: bool = False, reset: bool = False) -> bool:
        """Approach path ``name`` at point ``index`` along a singularity-free route, or refuse (and
        stay); returns whether it goes."""
        sign = int(np.sign(self.det_a))
        planned = self._orientation_plan(name, sign) if sign != 0 else None
        why = "no orientation keeps it on the robot's side of the parallel singularities"
        poses = None
        if planned is not None:
            orientation, phi0 = planned
            path = self.paths[name]
            start = np.array([*path[index], orientation[index]])
            try:
                poses = model.route(self.robot_model, self.pose, start, self.working_mode, MOVE_STEP, TURN_STEP)
            except rk.NoRouteError as exc:
                why = "no singularity-free way there from here" if exc.reason == "regions" else str(exc)
        if poses is None:
            if reset:
                self._restart()
                return True
            self.message = f"{name} refused: {why}; move in free mode (m) and try again"
            return False
        if not keep_trail:
            self.trail.clear()
        self.path, self._path_name, self._plan, self._index = self.paths[name], name, orientation, index
        self._approach, self._after_approach = poses, name
        tilt = f" (about phi = {phi0:+.2f} rad)" if phi0 else ""
        prefix = "reset: " if reset else ""
        self.mode = "approach" if len(poses) else name
        self.message = f"{prefix}{name}{tilt}: approaching the start" if len(poses) else f"{prefix}{name}{tilt}"
        return True

    # --- one step -----------------------------------------------------------------------------
    def advance(self, held: FrozenSet[str]) -> None:
        if self.mode == "free":
            self._free_step(held)
        elif self.mode == "approach":
            target = self._approach[0]
            self._approach = self._approach[1:]
            evaluated = self._evaluate(target)
            if evaluated is not None:
                self._set(target, evaluated)
                self.trail.append(self.pose[:2].copy())
            if len(self._approach) == 0:
                after = self._after_approach
                if after == "free":
                    self._go_free()
                    self.message = "home"
                else:
                    self._approach, self._after_approach, self.mode = None, None, after
                    self.message = after
        else:
            self._path_step()

    def _path_step(self) -> None:
        self._index = (self._index + 1) % len(self.path)
        x, y = self.path[self._index]
        pose = np.array([x, y, self._plan[self._index]])
        evaluated = self._evaluate(pose)
        if evaluated is None:  # cannot happen with the default geometry; stay rather than jump
            self.message = "path point out of reach: holding"
            return
        self._set(pose, evaluated)
        self.trail.append(self.pose[:2].copy())

    def _free_step(self, held: FrozenSet[str]) -> None:
        dx, dy = arrows(held)
        dphi = ("l" in held) - ("k" in held)
        if not (dx or dy or dphi):
            return
        counts = self._counts + np.array([dx, dy, dphi], dtype=np.int64)
        pose = self._anchor + counts / np.array([1.0 / MOVE_STEP, 1.0 / MOVE_STEP, 1.0 / TURN_STEP])
        evaluated = self._evaluate(pose)
        reason = self._refusal(evaluated)
        if reason:
            self.message = f"step refused: {reason}"
            return
        self._counts = counts
        self._set(pose, evaluated)
        self.trail.append(self.pose[:2].copy())
        self.message = ""

    def _refusal(self, evaluated) -> str:
        """Why a free-mode step to a pose evaluated as ``evaluated`` must not be taken ('' if fine).

        As in the seed program, free mode is bounded by the workspace and its serial singularities
        (a stretched leg: the effector cannot go further that way). It may pass a parallel
        singularity, which the log and the panel then report, but never stops on one.
        """
        if evaluated is None:
            return "outside the workspace"
        if evaluated.state == "serial":
            return "a leg would be stretched or folded (serial singularity)"
        if evaluated.state == "parallel" and not evaluated.distance > self.distance:
            # Stepping away from a singularity the effector is already on is allowed.
            return "too close to a parallel singularity"
        return ""

    # --- output -------------------------------------------------------------------------------
    def row(self):
        x, y, phi = self.pose.tolist()
        return (self.steps, self.time, self.mode, x, y, phi, *self.alpha.tolist(), self.det_a, self.det_b,
                self.det_a_norm, self.det_b_norm, self.distance, int(self.avoid), self.sing)

    def workspace(self, phi: float) -> Optional[model.Workspace]:
        """The core's workspace map at orientation ``phi`` (cached on phi rounded to 0.01 rad)."""
        key = round(phi, 2)
        if key not in self._workspace_cache:
            if len(self._workspace_cache) > 64:
                self._workspace_cache.clear()
            self._workspace_cache[key] = model.workspace(self.robot_model, key, self.working_mode)
        return self._workspace_cache[key]

    def state(self) -> Rrr3State:
        if self._points is None:
            self._points = model.points(self.robot_model, self.pose, self.working_mode)
        return Rrr3State(
            pose=self.pose, alpha=self.alpha, points=self._points, det_a=self.det_a, det_b=self.det_b,
            det_a_norm=self.det_a_norm, det_b_norm=self.det_b_norm,
            distance=self.distance, state=self.sing, mode=self.mode, working_mode=self.working_mode, avoid=self.avoid, path=self.path,
            trail=np.array(self.trail), workspace=self.workspace(float(self.pose[2])), message=self.message,
        )
