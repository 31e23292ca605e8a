"""Runs every benchmark module in this folder (bench_*.py, in name order) in one process.

A module's ``main()`` is called when it has one, otherwise the file runs as a script. When a
``main()`` returns a list of goals ({"name", "ratio", "goal", "met"}), they are summed up at the end.
The exit status is non-zero when a module fails (an exception, e.g. a reference that disagrees with
robokin); with ``--strict``, also when a goal is not met.
"""

from __future__ import annotations

import importlib.util
import runpy
import sys
import time
import traceback
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main(strict: bool = False) -> int:
    sys.path.insert(0, str(HERE))
    failed, goals = [], []
    for path in sorted(HERE.glob("bench_*.py")):
        print(f"=== {path.name} ===", flush=True)
        start = time.perf_counter()
        try:
            spec = importlib.util.spec_from_file_location(path.stem, path)
            module = importlib.util.module_from_spec(spec)
            sys.modules[path.stem] = module
            spec.loader.exec_module(module)
            if callable(getattr(module, "main", None)):
                result = module.main()
                if isinstance(result, list):
                    goals += [dict(g, module=path.name) for g in result if isinstance(g, dict)]
            else:
                runpy.run_path(str(path), run_name="__main__")
        except SystemExit as exc:  # a script's own exit status
            if exc.code not in (None, 0):
                failed.append(path.name)
        except Exception:  # noqa: BLE001 - report and go on with the next module
            traceback.print_exc()
            failed.append(path.name)
        print(f"({path.name}: {time.perf_counter() - start:.1f} s)\n", flush=True)
    if goals:
        print("=== goals ===")
        for g in goals:
            print(f"  {'MET    ' if g['met'] else 'NOT MET'} {g['name']:<40} {g['ratio']:7.3f}x  (goal <= {g['goal']})"
                  f"  [{g['module']}]")
    if failed:
        print("failed: " + ", ".join(failed))
    return 1 if failed or (strict and not all(g["met"] for g in goals)) else 0


if __name__ == "__main__":
    sys.exit(main(strict="--strict" in sys.argv[1:]))
