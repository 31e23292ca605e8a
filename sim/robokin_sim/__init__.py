"""robokin-sim: the pygame simulator of robokin (the 3-RRR parallel robot, the RPR arm and any serial
arm: the catalogue's, or a URDF file's; one table of scenes, robokin_sim.scenes).

``robokin-sim --help`` (or ``python -m robokin_sim --help``) lists the options; ``h`` in the window
lists the keys. :func:`robokin_sim.loop.run` runs it from Python.
"""

__all__ = ["main", "run"]


def main(argv=None) -> int:
    from .__main__ import main as _main

    return _main(argv)


def run(config, render: bool = True):
    from .loop import run as _run

    return _run(config, render=render)
