"""Every public callable of robokin is driven by a property test: the COVERS sets of the
test_fuzz_*.py files together name every public function of the package and its modules, every
public method, property and constructor of its model classes (the objects users build and call:
Chain, RRR3, IKSolver, IKSolutions, ClosedSolver), and the simulator's entry points (command line, key scripts,
scenes). A new public call without a property test fails here."""

import importlib
import inspect
import pathlib

import robokin as rk
import robokin_sim.config
import robokin_sim.keys
import robokin_sim.scene
import robokin_sim.scene_rpr
import robokin_sim.scene_rrr3
import robokin_sim.scene_serial
from robokin import _core, demo, plots, plots_arm, plots_rrr3, rrr3_design

MODULES = {"closed": rk.closed, "paths": rk.paths, "robots": rk.robots, "rrr3_design": rrr3_design,
           "plots": plots, "plots_arm": plots_arm, "plots_rrr3": plots_rrr3, "demo": demo}
MODULES.update({"traj": rk.traj, "pose": rk.pose})
import robokin.dask  # noqa: E402  (rk.reachability is the function, the module is in sys.modules)
import robokin.plots_reachability  # noqa: E402
import sys  # noqa: E402
MODULES.update({"reachability": sys.modules["robokin.reachability"], "plots_reachability": robokin.plots_reachability,
                "dask": robokin.dask})
import robokin.symbolic  # noqa: E402  (sympy: imported on first use, not by import robokin)
MODULES["symbolic"] = robokin.symbolic
MODEL_CLASSES = [rk.Chain, rk.RRR3, rk.IKSolver, _core.IKSolutions, rk.closed.ClosedSolver]
# What the simulator takes from its user: the command line, key scripts, and scenes stepped by keys.
SIM = {"sim.parse_args", "sim.parse_script", "sim.Rrr3Scene", "sim.RprScene", "sim.Scene.step", "sim.SerialScene",
       "sim.Scene.pointer"}
SIM_MODULES = [robokin_sim.config, robokin_sim.keys, robokin_sim.scene, robokin_sim.scene_rpr, robokin_sim.scene_rrr3,
               robokin_sim.scene_serial]


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
        for name, obj in vars(cls).items():
            # A constructor users call (pybind11 documents its signature); Chain and IKSolutions
            # come from factories, their __init__ only says so.
            if name == "__init__" and (obj.__doc__ or "").startswith("__init__("):
                names.add(f"{cls.__name__}.__init__")
            if _public(name) and (callable(obj) or isinstance(obj, (property, staticmethod, classmethod))
                                  or type(obj).__name__ == "property"):
                names.add(f"{cls.__name__}.{name}")
    return names | SIM


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


def resolve(name):
    """The object a COVERS name stands for (AttributeError when there is none)."""
    first, *rest = name.split(".")
    if first == "sim":
        first, *rest = rest
        homes = SIM_MODULES
    else:
        homes = [rk, _core, *MODULES.values()]
    obj = MODULES.get(first) or next(getattr(h, first) for h in homes if hasattr(h, first))
    for part in rest:
        obj = getattr(obj, part)
    return obj


def test_covers_names_only_what_exists():
    # A misspelt or stale COVERS entry would hide a gap.
    unknown = []
    for name in sorted(covered()):
        try:
            resolve(name)
        except (AttributeError, StopIteration):
            unknown.append(name)
    assert not unknown, f"COVERS names that name nothing: {unknown}"
