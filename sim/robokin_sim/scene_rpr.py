"""The RPR arm of the redundancy study tracking a straight line with the Reach loop (state and step logic).

The line runs from point 1, on the workspace boundary (``t1 = pi/2``, the joint's upper limit),
to point 2 and back, one path point per step, each reached by ``rk.reach`` from the joints the
previous step left. ``s`` switches between the minimum-norm solution and the null-space term that
keeps the joints away from their limits. Free mode moves the tip 1 cm per step with the arrows.
"""

from __future__ import annotations

import dataclasses
from collections import deque
from typing import FrozenSet, Optional, Tuple

import numpy as np
import robokin as rk

from .scene import Scene, arrows, reach_quietly

#: Seed 000's Figure 2 line: joints at point 1 (t1 at its upper limit, the workspace boundary), point 2.
Q1, P2 = rk.robots.RPR_LINE_Q1, rk.robots.RPR_LINE_P2
#: Spacing of the line's points: the seed cuts the segment into "very close" points.
LINE_STEP = 0.01
#: Tip move per step in free mode and during approaches (metres).
FREE_STEP = 0.01
#: Trail points kept.
TRAIL = 4000


@dataclasses.dataclass
class RprState:
    """What the renderer needs."""

    q: np.ndarray
    frames: np.ndarray  # (4, 4, 4) base, after each joint
    target: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    line: np.ndarray  # (K, 2)
    trail: np.ndarray  # (T, 2)
    mode: str
    avoid: bool
    error: float
    converged: bool
    message: str


class RprScene(Scene):
    """The RPR line / free scene.

    Args:
        mode: ``"line"`` or ``"free"``.
        avoid: Start with null-space joint-limit avoidance (else minimum-norm).
    """

    robot = "rpr"
    columns = ("step", "time", "mode", "x", "y", "q_0", "q_1", "q_2", "error")

    def __init__(self, mode: str = "line", avoid: bool = True) -> None:
        super().__init__()
        if mode not in ("line", "free"):
            raise ValueError(f"mode: the RPR scene has modes line and free, got {mode!r}")
        self.chain = rk.robots.rpr()
        self.lower, self.upper = (np.asarray(v, dtype=float) for v in self.chain.limits)
        self.p1 = self.chain.fk(Q1)[:2, 3].copy()
        self.line = rk.paths.line(self.p1, P2, LINE_STEP)
        self.start_mode = mode
        self.start_avoid = bool(avoid)
        self.trail: deque = deque(maxlen=TRAIL)
        self.reset()

    # --- keys ---------------------------------------------------------------------------------
    def reset(self) -> None:
        self.q = Q1.copy()
        self.tip = self.p1.copy()
        self.target = self.p1.copy()
        self.avoid = self.start_avoid
        self.error = 0.0
        self.converged = True
        self.trail.clear()
        self.trail.append(self.tip.copy())
        self._approach: Optional[np.ndarray] = None
        self._index, self._direction = 0, 1
        self.mode = "free"
        self.message = ""
        if self.start_mode == "line":
            self._start_line()

    def press(self, key: str, held: FrozenSet[str] = frozenset()) -> None:
        if key == "m":
            self.mode, self._approach = "free", None
            self.target = self.tip.copy()
            self.message = "free mode: arrows move the tip"
        elif key in ("o", "p"):
            self._start_line()
        elif key == "s":
            self.avoid = not self.avoid
            self.message = "null-space joint-limit avoidance" if self.avoid else "minimum-norm solution"
        elif key == "r":
            self.reset()

    def _start_line(self) -> None:
        """Goes to the nearer end of the line (a logged approach if the tip is elsewhere), then traces it."""
        ends = (self.line[0], self.line[-1])
        near = int(np.linalg.norm(self.tip - ends[1]) < np.linalg.norm(self.tip - ends[0]))
        self._index = len(self.line) - 1 if near else 0
        self._direction = -1 if near else 1
        self.trail.clear()
        if np.linalg.norm(self.tip - ends[near]) > 1e-9:
            self._approach = rk.paths.line(self.tip, ends[near], FREE_STEP)[1:]
            self.mode = "approach"
        else:
            self._approach = None
            self.mode = "line"
        self.message = "tracing the line from point 1 to point 2"

    # --- one step -----------------------------------------------------------------------------
    def _reach(self, target) -> Tuple[np.ndarray, float, bool]:
        # "Precision not reached" is reported on the panel and in the log's error column.
        res = reach_quietly(self.chain, target, self.q, nullspace="joint_limits" if self.avoid else None)
        return np.asarray(res.q), float(res.error), bool(res.converged)

    def _move(self, target, reached=None) -> bool:
        q, error, converged = reached or self._reach(target)
        if not np.all(np.isfinite(q)):
            return False
        self.q, self.error, self.converged = q, error, converged
        self.target = np.asarray(target, dtype=float)
        self.tip = self.chain.fk(q)[:2, 3].copy()
        self.trail.append(self.tip.copy())
        return True

    def advance(self, held: FrozenSet[str]) -> None:
        if self.mode == "free":
            dx, dy = arrows(held)
            if dx or dy:
                target = self.target + FREE_STEP * np.array([dx, dy], dtype=float)
                reached = self._reach(target)
                if reached[2] and self._move(target, reached):
                    self.message = ""
                else:
                    # The arm cannot follow (workspace boundary or a joint limit): stay put.
                    self.message = "move refused: out of reach within the joint limits"
            return
        if self.mode == "approach":
            self._move(self._approach[0])
            self._approach = self._approach[1:]
            if len(self._approach) == 0:
                self._approach, self.mode = None, "line"
            return
        # Line: ping-pong between the ends, one point per step.
        nxt = self._index + self._direction
        if not 0 <= nxt < len(self.line):
            self._direction = -self._direction
            nxt = self._index + self._direction
        self._index = nxt
        self._move(self.line[nxt])

    # --- output -------------------------------------------------------------------------------
    def row(self):
        return (self.steps, self.time, self.mode, self.tip[0], self.tip[1], *self.q.tolist(), self.error)

    def state(self) -> RprState:
        return RprState(
            q=self.q, frames=self.chain.frames(self.q), target=self.target, lower=self.lower,
            upper=self.upper, line=self.line, trail=np.array(self.trail), mode=self.mode,
            avoid=self.avoid, error=self.error, converged=self.converged, message=self.message,
        )
