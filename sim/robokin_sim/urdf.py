"""``--urdf FILE [--base LINK --tip LINK]``: the chain of a URDF file for the serial scene.

The core builds the chain (:meth:`robokin.Chain.from_urdf`, urdfdom's parser). When ``--base`` or
``--tip`` is left out, it is read off the file's link tree here: the base is the root link (the one
no joint has as its child), the tip the end of the longest branch from the base (most movable
joints, then most joints; the first in the file on a tie).
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from typing import Optional, Tuple

import robokin as rk

MOVABLE = ("revolute", "continuous", "prismatic")


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def default_links(path: str) -> Tuple[str, str]:
    """(base, tip) of the URDF at ``path``: its root link and the end of its longest branch.

    Raises:
        ValueError: The file cannot be read as XML or has no single root link.
    """
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise ValueError(_one_line(exc)) from None
    links = [link.get("name") for link in root.iter("link") if link.get("name")]
    children: dict = {}
    parents = set()
    for joint in root.iter("joint"):
        parent, child = joint.find("parent"), joint.find("child")
        if parent is None or child is None:
            continue
        movable = joint.get("type") in MOVABLE
        children.setdefault(parent.get("link"), []).append((child.get("link"), movable))
        parents.add(child.get("link"))
    roots = [name for name in links if name not in parents]
    if len(roots) != 1:
        raise ValueError(f"expected one root link, found {len(roots)}" + (f" ({', '.join(roots[:5])})" if roots else ""))
    best = (-1, -1, roots[0])
    stack = [(roots[0], 0, 0, {roots[0]})]
    while stack:
        link, moving, joints, seen = stack.pop()
        if (moving, joints) > best[:2]:
            best = (moving, joints, link)
        for child, movable in reversed(children.get(link, [])):
            if child not in seen:  # a cycle is the core's to report
                stack.append((child, moving + movable, joints + 1, seen | {child}))
    return roots[0], best[2]


def load(path: str, base: Optional[str] = None, tip: Optional[str] = None) -> Tuple[rk.Chain, str]:
    """The chain from ``base`` to ``tip`` of the URDF file ``path`` and a title for it.

    Raises:
        ValueError: One line saying why the file gives no chain (unreadable, not URDF, no such
            link, no movable joint between the links, ...).
    """
    if not os.path.isfile(path):
        raise ValueError(f"no such file: {path}")
    if base is None or tip is None:
        auto_base, auto_tip = default_links(path)
        base, tip = base or auto_base, tip or auto_tip
    try:
        chain = rk.Chain.from_urdf(path, base, tip)
    except (ValueError, TypeError) as exc:
        raise ValueError(_one_line(exc)) from None
    if chain.dof == 0:
        raise ValueError(f"no movable joint between {base} and {tip}")
    return chain, f"{os.path.basename(path)} ({base} -> {tip})"
