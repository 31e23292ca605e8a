"""Key names, the input of one frame, and scripted key presses (``--keys right*20,down*10``).

The simulator works with key *names*, not pygame codes, so scenes and scripted runs do not depend
on pygame. A key is *pressed* on the frame it goes down and *held* on every frame it stays down:
mode switches and toggles act on presses, moves and rotations on held keys (one step per frame).
A script item may hold keys together, joined by ``+`` (``shift+up*10``: Shift and the up arrow for
10 frames).
"""

from __future__ import annotations

import dataclasses
from typing import FrozenSet, Iterator, Tuple

#: Every key the simulator understands (DESIGN.md, "Simulator"); the second line is the serial
#: arms' (joint selection and jog, Cartesian z, postures, the ellipsoid, the camera's views).
KEYS = ("m", "o", "p", "left", "right", "up", "down", "k", "l", "s", "space", "r", "h", "esc",
        "1", "2", "3", "4", "5", "6", "7", "8", "9", "tab", "plus", "minus", "pageup", "pagedown", "shift",
        "n", "e", "f1", "f2", "f3", "f4", "v")

#: Other spellings accepted in scripts.
ALIASES = {"escape": "esc", " ": "space", "pause": "space", "=": "plus", "-": "minus", "pgup": "pageup",
           "pgdn": "pagedown", "page_up": "pageup", "page_down": "pagedown"}

#: Keys acting every frame while held; the others act once when pressed.
HELD_KEYS = frozenset({"left", "right", "up", "down", "k", "l", "plus", "minus", "pageup", "pagedown", "shift"})

#: Longest hold a script may ask for (keeps a typo like right*1e9 from running for ever).
MAX_HOLD = 1_000_000


@dataclasses.dataclass(frozen=True)
class Input:
    """The keys of one frame: those that went down this frame, and all those down; and the mouse:
    pixels dragged with a button down (dx, dy) and wheel clicks (up positive)."""

    pressed: FrozenSet[str] = frozenset()
    held: FrozenSet[str] = frozenset()
    drag: Tuple[int, int] = (0, 0)
    wheel: int = 0


NO_INPUT = Input()


@dataclasses.dataclass(frozen=True)
class KeyScript:
    """A parsed ``--keys`` script: ``(key, frames)`` items played one after the other."""

    items: Tuple[Tuple[str, int], ...]  # (key or "key+key", frames)

    def __bool__(self) -> bool:
        return bool(self.items)

    @property
    def frames(self) -> int:
        """Frames the script lasts."""
        return sum(n for _, n in self.items)

    def inputs(self) -> Iterator[Input]:
        """One :class:`Input` per frame: each item presses its key on its first frame and holds it
        for its N frames, then releases it (so ``l*10,l*10`` is two presses)."""
        for key, count in self.items:
            held = frozenset(key.split("+"))
            yield Input(pressed=held, held=held)
            for _ in range(count - 1):
                yield Input(held=held)


def parse_script(text: str) -> KeyScript:
    """Parses ``KEY*N`` items separated by commas (``*N`` may be left out for N = 1).

    Raises:
        ValueError: Naming the bad item and the keys allowed.
    """
    items = []
    for raw in text.split(","):
        item = raw.strip().lower()
        if not item:
            continue
        name, star, count_text = item.partition("*")
        name = _key_name(name.strip())
        if name is None:
            raise ValueError(f"--keys: unknown key {raw.strip()!r} (keys: {', '.join(KEYS)}; "
                             "hold several with +, e.g. shift+up)")
        count_text = count_text.strip()
        if star and not count_text.isdigit():
            raise ValueError(f"--keys: bad count in {raw.strip()!r}, expected KEY*N with N a whole number")
        if len(count_text) > 7:
            raise ValueError(f"--keys: count in {raw.strip()!r} must be between 1 and {MAX_HOLD}")
        try:
            count = int(count_text) if star else 1
        except ValueError:
            raise ValueError(f"--keys: bad count in {raw.strip()!r}, expected KEY*N with N a whole number") from None
        if not 1 <= count <= MAX_HOLD:
            raise ValueError(f"--keys: count in {raw.strip()!r} must be between 1 and {MAX_HOLD}")
        items.append((name, count))
    return KeyScript(tuple(items))


def _key_name(text: str):
    """A key or keys held together (``shift+up``) under their names in :data:`KEYS`; None when
    one is unknown. ``+`` alone is the plus key."""
    if text == "+":
        return "plus"
    parts = [ALIASES.get(p.strip(), p.strip()) for p in text.split("+")] if "+" in text else [ALIASES.get(text, text)]
    if not parts or any(p not in KEYS for p in parts):
        return None
    return "+".join(dict.fromkeys(parts))
