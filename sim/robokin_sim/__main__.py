"""Entry point: ``robokin-sim`` and ``python -m robokin_sim``."""

from __future__ import annotations

import sys
from typing import Optional, Sequence


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Parses the command line, runs the simulator, names the files it wrote.

    Returns:
        The process exit status: 0 on success, 1 when an output cannot be written (one line on
        stderr naming the file), 2 for a bad command line, 128 + N when signal N (SIGINT, SIGTERM,
        SIGHUP) stopped the run (nothing is written then; see :mod:`robokin_sim.signals`).
    """
    from .config import has_display, parse_args
    from .signals import Stopped, stop_on_signals

    argv = sys.argv[1:] if argv is None else list(argv)
    config = parse_args(argv)
    if "--demo" in argv and config.headless and not has_display():
        print("robokin-sim: no display found, running headless and recording instead of opening a window")
    try:
        with stop_on_signals():
            try:
                from .loop import run

                result = run(config)
            except BaseException:
                _remove_own_temporaries(config)
                raise
    except (Stopped, KeyboardInterrupt) as exc:
        stop = exc if isinstance(exc, Stopped) else Stopped(2)
        kept = [p for p in (config.log, config.record, config.screenshot) if p]
        note = f"; {', '.join(kept)} not written" if kept else ""
        print(f"robokin-sim: {stop}{note}", file=sys.stderr)
        return stop.status
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


def _remove_own_temporaries(config) -> None:
    """Temporary files of this process's outputs that a stopped run had not yet removed."""
    from robokin._atomic import remove_own

    for path in (config.log, config.record, config.screenshot):
        if path:
            remove_own(path)


if __name__ == "__main__":
    sys.exit(main())
