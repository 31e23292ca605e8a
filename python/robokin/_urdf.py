"""URDF documents from a path or a string (robokin/__init__.py makes from_urdf Chain's and exports
urdf_tree): the document's text is read here, urdfdom parses it in the core, and what the core
accepted but changed is warned about at the caller's line."""

from __future__ import annotations

import os
import warnings

from . import _checks, _core
from ._core import Chain, UrdfTree
from ._signature import written
from .errors import URDFWarning


def _document(path_or_string: str | bytes | os.PathLike) -> bytes:
    """The XML document of path_or_string, as bytes: a str or bytes whose first non-blank character
    is '<' is the document itself (a str encoded as UTF-8, bytes handed to the parser as they are);
    any other str or bytes, and every os.PathLike, names a file (bytes decoded with os.fsdecode, as
    Python's own file functions do)."""
    if not isinstance(path_or_string, (str, bytes, os.PathLike)):
        raise TypeError("path_or_string: expected a URDF document or a path to one (str, bytes or os.PathLike), "
                        f"got {type(path_or_string).__name__}")
    if isinstance(path_or_string, (str, bytes)):
        text = path_or_string.lstrip(" \t\r\n" if isinstance(path_or_string, str) else b" \t\r\n")
        if text[:1] in ("<", b"<"):
            try:
                return path_or_string.encode() if isinstance(path_or_string, str) else path_or_string
            except UnicodeEncodeError:  # a lone surrogate
                raise ValueError("path_or_string: not a valid URDF document (text that is not Unicode)") from None
    path = os.fsdecode(path_or_string)
    if not path.strip(" \t\r\n"):
        raise ValueError("path_or_string: the URDF document is empty (an empty string)")
    if os.path.isdir(path):
        raise ValueError(f"path_or_string: '{path}' is a directory, not a URDF file")
    try:
        with open(path, "rb") as f:
            return f.read()
    except (OSError, ValueError):  # ValueError: a NUL in the path
        raise ValueError(f"path_or_string: no readable file '{path}' (and not a URDF string)") from None


def _link(name, argument: str) -> str | None:
    """A link's name, or None."""
    return _checks.instance(name, argument, str, "a link name (str)", optional=True)


def _warned(answer: tuple):
    """The core's (value, warnings): each warning a URDFWarning at the caller of the public call."""
    value, texts = answer
    for text in texts:
        warnings.warn(text, URDFWarning, stacklevel=3)
    return value


def from_urdf(path_or_string: str | bytes | os.PathLike, base: str | None = None, tip: str | None = None) -> Chain:
    """Builds the chain from link `base` to link `tip` of a URDF file or string, with the file's joint
    limits (continuous joints unlimited) and names (joint_names, link_names).

    path_or_string: a str or bytes whose first non-blank character is '<' is the document itself
      (bytes handed to the parser as they are); any other str or bytes, and any os.PathLike, is the
      path of a file (bytes decoded with os.fsdecode).
    base: the chain's first link; None: the root link (the one no joint has as its child).
    tip: the chain's last link; None: the end of the longest branch below base. Longest means the
      most movable (revolute, continuous, prismatic) joints. The links that many movable joints
      below base must all follow the same last movable joint, else ValueError naming the end of each
      branch (a two-armed robot: pass tip=). Among them the tip is the link with the most joints (the
      fixed flange or tool0 after the last movable joint), or, when several have that many, the
      deepest link they all hang from. Fixed leaves off other links (a 'base' frame) have fewer
      movable joints and never compete. robokin.urdf_tree shows the choice.

    Raises ValueError saying what is wrong with the file, the links or the chain between them;
    TypeError for an argument of the wrong kind. Emits robokin.URDFWarning for what was accepted but
    changed (a joint with lower == upper limit taken as unlimited, urdfdom's warnings).
    """
    document = _document(path_or_string)
    return _warned(_core.chain_from_urdf(document, _link(base, "base"), _link(tip, "tip")))


def urdf_tree(path_or_string: str | bytes | os.PathLike) -> UrdfTree:
    """The links and joints of a URDF file or string and the default base and tip of Chain.from_urdf.

    path_or_string: as Chain.from_urdf takes it. Returns a UrdfTree: links depth-first from the root,
    joints (name, type, parent, child) in the same order, root, base (the root), tip (None when the
    longest branches tie: tips lists their ends). Raises ValueError for a bad document, TypeError for
    an argument of the wrong kind; robokin.URDFWarning for what urdfdom accepted but warned about.
    """
    return _warned(_core.urdf_tree(_document(path_or_string)))


# Named and documented as the core's functions are (help(), the stubs and the reference read them).
written(from_urdf, "Chain.from_urdf", Chain.__module__)
written(urdf_tree, "urdf_tree", "robokin")
