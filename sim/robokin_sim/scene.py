"""What every scene offers the game loop: keys in, one step at a time, a log row out.

A scene owns the model state of one robot and its step logic; it never draws (the renderers do)
and never prints. The kinematics it needs are calls into robokin's core.
"""

from __future__ import annotations

import math
import threading
import warnings
from typing import FrozenSet, Sequence, Tuple

import robokin as rk

#: Seconds of simulated time per step: the seed program ran at 60 frames per second, one step each.
DT = 1.0 / 60.0


class Scene:
    """Base class: step counting and the interface the loop relies on.

    Subclasses set ``robot``, ``columns`` and implement :meth:`press`, :meth:`advance`,
    :meth:`reset` and :meth:`row`.
    """

    robot: str = ""
    columns: Tuple[str, ...] = ()

    def __init__(self) -> None:
        self.steps = 0
        #: One line telling what the last step did (shown on the panel), e.g. why a move was refused.
        self.message = ""

    @property
    def time(self) -> float:
        """Simulated time of the current state, seconds (``steps * DT``)."""
        return self.steps * DT

    def press(self, key: str, held: FrozenSet[str] = frozenset()) -> None:
        """A key went down (mode switches, toggles, reset), with the keys ``held`` at the time
        (Shift). Unknown keys are ignored."""

    def pointer(self, drag: Tuple[int, int], wheel: int) -> None:
        """The mouse dragged ``drag`` pixels with a button down, the wheel turned ``wheel`` clicks.
        Ignored unless the scene has a camera."""

    def step(self, held: FrozenSet[str]) -> None:
        """Advances the model by one step with the keys held during it."""
        self.advance(held)
        self.steps += 1

    def advance(self, held: FrozenSet[str]) -> None:
        raise NotImplementedError

    def reset(self) -> None:
        raise NotImplementedError

    def row(self) -> Sequence:
        """The log row of the current state, matching ``columns``."""
        raise NotImplementedError


def finite(*values: float) -> bool:
    """True when every value is a finite number."""
    return all(math.isfinite(v) for v in values)


def arrows(held: FrozenSet[str]) -> Tuple[int, int]:
    """The direction (dx, dy) in whole steps the arrow keys ask for (opposite keys cancel)."""
    return (("right" in held) - ("left" in held), ("up" in held) - ("down" in held))


# Warning filters are process-wide and catch_warnings saves them on entry and puts them back whole
# on exit: two threads' blocks interleaving would put back each other's filters (leaving "ignore"
# behind for the whole process). The scenes' blocks take this lock, so that they nest.
_QUIET = threading.Lock()


def reach_quietly(*args, **kwargs):
    """``rk.reach`` without its PrecisionWarning: the scenes report a missed tolerance themselves
    (on the panel and in the log)."""
    with _QUIET, warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        return rk.reach(*args, **kwargs)
