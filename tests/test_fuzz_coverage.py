"""Every public callable of robokin is driven by a property test: the COVERS sets of the
test_fuzz_*.py files together name every public function of the package and its modules, and
every public method, property and constructor of its model classes (the objects users build and
call: Chain, RRR3, IKSolver, IKSolutions). A new public call without a property test fails here."""

import importlib
import inspect
import pathlib

import robokin as rk
from robokin import _core, demo, plots, plots_rrr3, rrr3_design

MODULES = {"closed": rk.closed, "paths": rk.paths, "robots": rk.robots, "rrr3_design": rrr3_design,
           "plots": plots, "plots_rrr3": plots_rrr3, "demo": demo}
MODEL_CLASSES = [rk.Chain, rk.RRR3, rk.IKSolver, _core.IKSolutions]


def _public(name):
    return not name.startswith("_")


def public_api():
    names = set()
    for name in rk.__all__:
        obj = getattr(rk, name)
        if callable(obj) and not inspect.isclass(obj):
            names.add(name)
    for prefix, module in MODULES.items():
        for name, obj in vars(module).items():
            if _public(name) and inspect.isfunction(obj) and obj.__module__ == module.__name__:
                names.add(f"{prefix}.{name}")
    for cls in MODEL_CLASSES:
        names.add(f"{cls.__name__}.__init__")
        for name, obj in vars(cls).items():
            if _public(name) and (callable(obj) or isinstance(obj, (property, staticmethod, classmethod))
                                  or type(obj).__name__ == "property"):
                names.add(f"{cls.__name__}.{name}")
    return names


def covered():
    names = set()
    for path in sorted(pathlib.Path(__file__).parent.glob("test_fuzz_*.py")):
        if path.stem == "test_fuzz_coverage":
            continue
        names |= set(getattr(importlib.import_module(path.stem), "COVERS", ()))
    return names


def test_every_public_call_has_a_property_test():
    missing = sorted(public_api() - covered())
    assert not missing, f"public calls no test_fuzz_*.py covers: {missing}"


def test_covers_names_only_what_exists():
    # A misspelt or stale COVERS entry would hide a gap.
    api = public_api()
    unknown = sorted(n for n in covered() if not n.startswith("sim.") and n not in api
                     and n.split(".")[0] not in {"RRR3Fk", "RRR3Newton", "RRR3Plan", "RRR3Workspace", "RRR3Singularity",
                                                 "ReachResult", "TrackResult", "IKResult", "IKBatchResult", "IKSolutions",
                                                 "AreaCurve", "BestL2"})
    assert not unknown, f"COVERS names that are not public calls: {unknown}"
