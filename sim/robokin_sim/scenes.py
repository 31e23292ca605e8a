"""The table of scenes: one entry per ``--robot`` name, from which the command line (its choices,
its help text), the key help and the factories of scenes and renderers are derived.

Adding a robot to the simulator is one entry here. The serial arms are every arm of
:mod:`robokin.robots` (``rk.robots.names()``) but the RPR study's arm, which keeps its own scene (the
straight line of the RPR study's Figure 2); ``--urdf FILE`` makes a serial scene of the chain it loads.
"""

from __future__ import annotations

import dataclasses
from typing import Callable, Dict, Tuple

import robokin as rk

#: Modes of every serial arm; the first is the default.
SERIAL_MODES = ("free", "circle", "line")


@dataclasses.dataclass(frozen=True)
class SceneEntry:
    """One robot of the simulator.

    Attributes:
        name: The ``--robot`` name.
        title: What the window title and the panel call it.
        modes: The modes it offers, the default first.
        demo_mode: The mode ``--demo`` runs headless.
        scene: ``scene(config)`` builds the scene (a :class:`robokin_sim.scene.Scene`).
        renderer: ``renderer(size)`` builds the renderer drawing its states.
        help: The key list of its help overlay: ``(keys, what they do)``.
    """

    name: str
    title: str
    modes: Tuple[str, ...]
    demo_mode: str
    scene: Callable
    renderer: Callable
    help: Tuple[Tuple[str, str], ...]

    @property
    def default_mode(self) -> str:
        return self.modes[0]


def _rrr3_scene(config):
    from .scene_rrr3 import Rrr3Scene

    return Rrr3Scene(mode=config.mode, avoid=config.avoid)


def _rrr3_renderer(size):
    from .render_rrr3 import Rrr3Renderer

    return Rrr3Renderer(size)


def _rpr_scene(config):
    from .scene_rpr import RprScene

    return RprScene(mode=config.mode, avoid=config.avoid)


def _rpr_renderer(size):
    from .render_rpr import RprRenderer

    return RprRenderer(size)


def _serial_scene(config):
    from .scene_serial import SerialScene

    if config.urdf:
        from .urdf import load

        chain, title = load(config.urdf, config.base, config.tip)
        return SerialScene(chain, name="urdf", title=title, mode=config.mode, avoid=config.avoid)
    return SerialScene(rk.robots.get(config.robot), name=config.robot, mode=config.mode, avoid=config.avoid)


def _serial_renderer(size):
    from .render_serial import SerialRenderer

    return SerialRenderer(size)


_COMMON_KEYS = (("space", "pause"), ("r", "reset"), ("h", "this help"), ("esc", "quit"))

RRR3_HELP = (
    ("m", "free mode: arrows move 1 mm, k / l rotate 0.01 rad"),
    ("o", "trace the circle (r = 0.1 m)"),
    ("p", "trace the four-leaf clover"),
    ("s", "singularity avoidance on / off"),
) + _COMMON_KEYS

RPR_HELP = (
    ("o / p", "trace the line from point 1 to point 2"),
    ("m", "free mode: arrows move the tip 1 cm"),
    ("s", "null-space joint-limit avoidance / minimum norm"),
) + _COMMON_KEYS

SERIAL_HELP = (
    ("1 - 9 / tab", "select a joint (tab: the next one)"),
    ("+ / -", "jog the selected joint (0.01 rad or 2 mm per step)"),
    ("arrows", "move the tool in base x / y (2 mm per step)"),
    ("pageup / pagedown", "move the tool in base z"),
    ("shift", "with arrows, pageup, pagedown: turn about x, y, z (0.01 rad)"),
    ("n", "next closed-form posture of this tool pose"),
    ("e", "velocity ellipsoid (translation) on / off"),
    ("f1 - f4 / v", "view front, side, top, iso (v: the next one)"),
    ("mouse", "drag to orbit, wheel to zoom"),
    ("m / o / p", "free mode / trace the circle / the line"),
    ("s", "null-space joint-limit avoidance (redundant arms)"),
) + _COMMON_KEYS


def _table() -> Dict[str, SceneEntry]:
    table = {
        "rrr3": SceneEntry("rrr3", "3-RRR parallel robot", ("free", "circle", "clover"), "clover", _rrr3_scene,
                           _rrr3_renderer, RRR3_HELP),
        "rpr": SceneEntry("rpr", "RPR (redundancy study)", ("line", "free"), "line", _rpr_scene, _rpr_renderer, RPR_HELP),
    }
    for name in rk.robots.names():
        if name not in table:
            table[name] = SceneEntry(name, name, SERIAL_MODES, "circle", _serial_scene, _serial_renderer, SERIAL_HELP)
    table["urdf"] = SceneEntry("urdf", "URDF", SERIAL_MODES, "circle", _serial_scene, _serial_renderer, SERIAL_HELP)
    return table


#: ``--robot`` name -> SceneEntry (``urdf`` is what ``--urdf FILE`` selects).
SCENES: Dict[str, SceneEntry] = _table()

#: The names ``--robot`` accepts (every entry but ``urdf``, which ``--urdf`` selects).
ROBOTS = tuple(sorted(n for n in SCENES if n != "urdf"))


def entry(robot: str) -> SceneEntry:
    """The table's entry of ``robot`` (ValueError naming it when there is none)."""
    try:
        return SCENES[robot]
    except KeyError:
        raise ValueError(f"robot: no scene named {robot!r}; choose from {', '.join(ROBOTS)}") from None


def canonical(name: str) -> str:
    """The table's name for ``name`` written with or without ``_`` / ``-`` and in any case
    (``planar3r`` and ``Planar-3R`` are ``planar_3r``); ``name`` itself when none matches."""
    key = name.strip().lower().replace("-", "").replace("_", "")
    for robot in SCENES:
        if robot.replace("_", "") == key:
            return robot
    return name
