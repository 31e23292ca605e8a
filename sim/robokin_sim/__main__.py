"""Entry point: ``robokin-sim`` and ``python -m robokin_sim``."""

from __future__ import annotations

import sys
from typing import Optional, Sequence


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Parses the command line, runs the simulator, names the files it wrote.

    Returns:
        The process exit status (0 on success).
    """
    from .config import has_display, parse_args
    from .loop import run

    argv = sys.argv[1:] if argv is None else list(argv)
    config = parse_args(argv)
    if "--demo" in argv and config.headless and not has_display():
        print("robokin-sim: no display found, running headless and recording instead of opening a window")
    try:
        result = run(config)
    except KeyboardInterrupt:
        return 130
    except OSError as exc:  # an output file that cannot be written
        print(f"robokin-sim: error: {exc}", file=sys.stderr)
        return 1
    except Exception as exc:
        import pygame

        if isinstance(exc, pygame.error) and not config.headless:
            print(f"robokin-sim: error: cannot open a window ({exc}); try --headless or --demo", file=sys.stderr)
            return 1
        raise
    rate = result.frames / result.seconds if result.seconds > 0 else float("inf")
    print(f"robokin-sim: {config.robot}, {result.frames} frames, {result.steps} steps in {result.seconds:.2f} s "
          f"({rate:.0f} frames/s)")
    if result.record:
        print(f"recording: {result.record}")
    if result.screenshot:
        print(f"screenshot: {result.screenshot}")
    if result.log:
        print(f"log: {result.log}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
