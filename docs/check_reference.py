"""Checks that the built API reference describes every public name: each name of
``robokin.__all__`` and of each public module's ``__all__``, and each public method and property of
the classes among them, has its anchor in the site (`make docs` runs this after the build).

    .venv/bin/python docs/check_reference.py build/docs/html
"""

import importlib
import inspect
import pathlib
import re
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

import _api_pages  # noqa: E402


def _members(cls, prefix):
    for name, obj in vars(cls).items():
        if name.startswith("_"):
            continue
        if callable(obj) or isinstance(obj, (property, staticmethod, classmethod)) or type(obj).__name__ == "property":
            yield f"{prefix}.{name}"


def expected_anchors():
    """The anchors (Sphinx's ids: the object's dotted name) the reference must hold."""
    import robokin as rk

    exported = {id(getattr(rk, n)): n for n in rk.__all__}
    names = set()
    for n in rk.__all__:
        obj = getattr(rk, n)
        if inspect.ismodule(obj):
            continue
        names.add(f"robokin.{n}")
        if inspect.isclass(obj):
            names.update(_members(obj, f"robokin.{n}"))
    for m in _api_pages.public_modules():
        module = importlib.import_module(f"robokin.{m}")
        if not _api_pages.shadowed(rk, m):
            names.add(f"module-robokin.{m}")
        for n in module.__all__:
            obj = getattr(module, n)
            if id(obj) in exported:
                continue
            names.add(f"robokin.{m}.{n}")
            if inspect.isclass(obj):
                names.update(_members(obj, f"robokin.{m}.{n}"))
    return names


def anchors(html_dir):
    found = set()
    for page in pathlib.Path(html_dir).rglob("*.html"):
        found.update(re.findall(r'id="([^"]+)"', page.read_text(encoding="utf-8")))
    return found


def main(argv):
    html_dir = pathlib.Path(argv[1] if len(argv) > 1 else "build/docs/html")
    missing = sorted(expected_anchors() - anchors(html_dir / "api"))
    if missing:
        print(f"{len(missing)} public name(s) missing from the API reference in {html_dir}:", *missing, sep="\n  ")
        return 1
    print(f"API reference: every public name described ({len(expected_anchors())} anchors)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
