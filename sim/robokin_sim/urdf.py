"""``--urdf FILE [--base LINK --tip LINK]``: the chain of a URDF file for the serial scene.

The core builds the chain (:meth:`robokin.Chain.from_urdf`, urdfdom's parser), and chooses the
links left out: the base is the root link, the tip the end of the longest branch below it (its
docstring gives the rule; a tie between branches asks for ``--tip``).
"""

from __future__ import annotations

import os
from typing import Optional, Tuple

import robokin as rk


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def load(path: str, base: Optional[str] = None, tip: Optional[str] = None) -> Tuple[rk.Chain, str]:
    """The chain from ``base`` to ``tip`` of the URDF file ``path`` (None: the core's default links)
    and a title for it naming the links it runs between.

    Raises:
        ValueError: One line saying why the file gives no chain (unreadable, not URDF, no such
            link, no movable joint between the links, several longest branches, ...).
    """
    if not os.path.isfile(path):
        raise ValueError(f"no such file: {path}")
    try:
        chain = rk.Chain.from_urdf(path, base, tip)
    except (ValueError, TypeError) as exc:
        raise ValueError(_one_line(exc).replace("pass tip=...", "pass --tip LINK")) from None
    links = chain.link_names
    return chain, f"{os.path.basename(path)} ({links[0]} -> {links[-1]})"
