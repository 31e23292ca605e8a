"""Entry point: ``robokin-sim`` and ``python -m robokin_sim``."""

from __future__ import annotations

import sys
from typing import Optional, Sequence


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Parses the command line, runs the simulator, names the files it wrote.

    Returns:
        The process exit status: 0 on success, 1 when an output cannot be written (one line on
        stderr naming the file), 2 for a bad command line, 128 + N when signal N (SIGINT, SIGTERM,
        SIGHUP) stopped the run (its log, recording and screenshot are written whole and named on
        one line; see :mod:`robokin_sim.signals`).
    """
    from .config import has_display, parse_args
    from .signals import Stopped, requested, stop_on_signals

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
            stopped = requested()
    except (Stopped, KeyboardInterrupt) as exc:  # before the run had opened its outputs
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
    if stopped is not None:
        return _report_stop(Stopped(stopped), result)
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


def _written(result) -> str:
    """The files the run wrote, as ``log: PATH, recording: PATH, screenshot: PATH``."""
    named = (("log", result.log), ("recording", result.record), ("screenshot", result.screenshot))
    return ", ".join(f"{what}: {path}" for what, path in named if path)


def _report_stop(stop, result) -> int:
    """One line on stderr: the signal, the steps run, where the files are; the exit status. (The
    terminal may be gone after SIGHUP: a line that cannot be written is dropped.)"""
    files = _written(result)
    line = f"robokin-sim: {stop} after {result.steps} steps" + (f"; {files}" if files else "")
    try:
        print(line, file=sys.stderr, flush=True)
    except OSError:
        pass
    return stop.status


def _remove_own_temporaries(config) -> None:
    """Temporary files of this process's outputs that a stopped run had not yet removed."""
    from robokin.files import remove_own

    for path in (config.log, config.record, config.screenshot):
        if path:
            remove_own(path)


if __name__ == "__main__":
    sys.exit(main())
