"""Runs every benchmark module in this folder (bench_*.py, in name order) in one process, then
prints a summary of every goal.

A module's ``main()`` is called when it has one, otherwise the file runs as a script. A ``main()``
that returns a list of goals (dicts made by ``_timing.goal``: plain-words name, figure, unit, limit,
reference, met) has them listed at the end, each with its figure, its goal, what it is measured
against and "met" or "MISSED"; a module that reports no goals is named there as such. The exit
status is 1 when a module fails (an exception, e.g. a reference that disagrees with robokin); with
``--strict``, also when any goal is missed.
"""

from __future__ import annotations

import importlib.util
import math
import runpy
import sys
import time
import traceback
from pathlib import Path

HERE = Path(__file__).resolve().parent


def run_module(path: Path):
    """Runs one benchmark file: (its goals or None when it reports none, whether it failed)."""
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[path.stem] = module
    try:
        spec.loader.exec_module(module)
        if callable(getattr(module, "main", None)):
            result = module.main()
            return ([dict(g) for g in result if isinstance(g, dict)] if isinstance(result, list) else None), False
        runpy.run_path(str(path), run_name="__main__")
        return None, False
    except SystemExit as exc:  # a script's own exit status
        return None, exc.code not in (None, 0)
    except Exception:  # noqa: BLE001 - report and go on with the next module
        traceback.print_exc()
        return None, True


def _number(value: float, unit: str) -> str:
    if math.isnan(value):
        return "not measured"
    text = f"{value:.3f}" if unit == "x" else f"{value:.4g}"
    return text + (" x" if unit == "x" else f" {unit}")


def summary(results: dict, failed=()) -> str:
    """The summary table: results maps a module's file name to its goals (a list) or None (none
    reported); failed names the modules that stopped on an error."""
    goals = [dict(g, module=m) for m, gs in results.items() if gs for g in gs]
    missed = sum(not g["met"] for g in goals)
    lines = [f"=== goals: {len(goals) - missed} met, {missed} missed "
             "(ratios are robokin / reference, both timed in this run; lower is better) ==="]
    for g in goals:
        bound = (">= " if g.get("at_least") else "<= ") + _number(g["limit"], g["unit"])
        lines.append(f"  {'met   ' if g['met'] else 'MISSED'}  {g['name']}")
        lines.append(f"          {_number(g['figure'], g['unit'])} (goal {bound}); reference: {g['reference']}"
                     f"{'; ' + g['note'] if g.get('note') else ''}  [{g['module']}]")
    if failed:
        lines.append("  FAILED before reporting all their goals: " + ", ".join(failed))
    silent = [m for m, gs in results.items() if not gs and m not in failed]
    if silent:
        lines.append("  no goals reported to this summary by: " + ", ".join(silent) +
                     " (their own output above states what they measure)")
    return "\n".join(lines)


def exit_status(results: dict, failed: list, strict: bool) -> int:
    """1 when a module failed, or (strict) when any goal is missed; else 0."""
    missed = any(not g["met"] for gs in results.values() if gs for g in gs)
    return 1 if failed or (strict and missed) else 0


def main(strict: bool = False) -> int:
    sys.path.insert(0, str(HERE))
    results, failed = {}, []
    for path in sorted(HERE.glob("bench_*.py")):
        print(f"=== {path.name} ===", flush=True)
        start = time.perf_counter()
        results[path.name], bad = run_module(path)
        if bad:
            failed.append(path.name)
        print(f"({path.name}: {time.perf_counter() - start:.1f} s)\n", flush=True)
    print(summary(results, failed))
    return exit_status(results, failed, strict)


if __name__ == "__main__":
    sys.exit(main(strict="--strict" in sys.argv[1:]))
