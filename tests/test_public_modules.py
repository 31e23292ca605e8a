"""Every public module of robokin says what it exports: ``__all__`` names exactly the functions,
classes and constants it defines for users (no leaked imports such as ``np`` or helpers from
another module), and every name in it exists."""

import importlib
import inspect
import pkgutil

import pytest

import robokin

PUBLIC = sorted(m.name for m in pkgutil.iter_modules(robokin.__path__) if not m.name.startswith("_")
                and m.name not in ("demo", "demo_postures"))  # the demos are programs (python -m), not APIs


def defined_here(module):
    names = set()
    for name, obj in vars(module).items():
        if name.startswith("_") or inspect.ismodule(obj):
            continue
        if (inspect.isfunction(obj) or inspect.isclass(obj)) and getattr(obj, "__module__", "") == module.__name__:
            names.add(name)
        elif name.isupper():  # a constant of the module's own
            names.add(name)
    return names


@pytest.mark.parametrize("name", PUBLIC)
def test_all_names_what_the_module_defines(name):
    module = importlib.import_module(f"robokin.{name}")
    assert hasattr(module, "__all__"), f"robokin.{name} has no __all__"
    missing = [n for n in module.__all__ if not hasattr(module, n)]
    assert not missing, f"robokin.{name}.__all__ names what does not exist: {missing}"
    assert len(set(module.__all__)) == len(module.__all__)
    assert not {"np", "math", "Optional", "annotations"} & set(module.__all__)
    # Re-exports (ik's result classes from the core, closed's Chain) may be listed; own definitions must be.
    assert defined_here(module) <= set(module.__all__), sorted(defined_here(module) - set(module.__all__))


def test_the_package_exports_resolve():
    assert all(hasattr(robokin, n) for n in robokin.__all__)
    star = {}
    exec("from robokin import *", star)
    assert "np" not in star and set(robokin.__all__) <= set(star)


def test_the_core_module_ships_no_test_hooks():
    """Test hooks and benchmark references live in robokin._testing, not in the public core module."""
    from robokin import _core, _testing

    hooks = ("throw", "parallel_for_throwing", "KdlIk", "hessian_times", "vmath_sincos", "vmath_atan2")
    for name in ("_" + h for h in hooks):
        assert not hasattr(_core, name), name
    for name in hooks:
        assert hasattr(_testing, name), name
    chain = robokin.robots.ur5()
    assert _testing.hessian_times(chain, [0.1] * 6, [0.0] * 6).shape == (6, 6)
