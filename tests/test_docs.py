"""The documentation site's API reference (docs/_api_pages.py writes its pages when `make docs`
starts): a page for every public module and for every class of the package's namespace, and an
autodoc directive for every public name, so that no public callable is left out of the site; and
pybind11's signatures cleaned of their module paths. (`make docs` builds the site with warnings
as errors and checks the built pages' anchors: docs/check_reference.py.)"""

import importlib
import inspect
import pathlib
import re
import sys

import robokin as rk

DOCS = pathlib.Path(__file__).resolve().parents[1] / "docs"
sys.path.insert(0, str(DOCS))

import _api_pages  # noqa: E402
import check_reference  # noqa: E402


def _directives(folder):
    text = "\n".join(p.read_text() for p in folder.glob("*.rst"))
    return set(re.findall(r"^\.\. auto(?:function|class|data|module):: (\S+)", text, flags=re.M))


def test_every_public_name_has_its_directive(tmp_path):
    _api_pages.write(tmp_path)
    documented = _directives(tmp_path)
    for name in rk.__all__:
        obj = getattr(rk, name)
        if not inspect.ismodule(obj):
            assert f"robokin.{name}" in documented, name
    exported = {id(getattr(rk, n)) for n in rk.__all__}
    modules = _api_pages.public_modules()
    assert "symbolic" in modules and "demo" not in modules
    for m in modules:
        module = importlib.import_module(f"robokin.{m}")
        assert f"robokin.{m}" in documented and (tmp_path / f"robokin.{m}.rst").exists(), m
        for name in module.__all__:
            if id(getattr(module, name)) not in exported:
                assert f"robokin.{m}.{name}" in documented, f"robokin.{m}.{name}"
    classes = [n for n in rk.__all__ if inspect.isclass(getattr(rk, n))]
    assert all((tmp_path / f"robokin.{c}.rst").exists() for c in classes)


def test_pages_are_rewritten_only_when_changed_and_stale_ones_removed(tmp_path):
    _api_pages.write(tmp_path)
    (tmp_path / "robokin.gone.rst").write_text("stale")
    page = tmp_path / "robokin.Chain.rst"
    before = page.stat().st_mtime_ns
    _api_pages.write(tmp_path)
    assert not (tmp_path / "robokin.gone.rst").exists()
    assert page.stat().st_mtime_ns == before


def test_pybind11_signatures_read_as_the_stubs():
    line = rk.Chain.fk.__doc__.splitlines()[0]
    assert "numpy.typing" in line or "robokin._core" in line  # what is cleaned is there to clean
    signature = line[line.index("("):line.rindex(")") + 1]
    sig, _ = _api_pages.clean_signature(None, "method", "robokin.Chain.fk", rk.Chain.fk, {}, signature, None)
    assert sig.startswith("(q: array_like") and "numpy." not in sig and "robokin._core" not in sig
    assert _api_pages.clean("x: typing.SupportsInt | typing.SupportsIndex") == "x: int"


def test_the_built_site_checker_finds_a_missing_name(tmp_path):
    (tmp_path / "api").mkdir()
    (tmp_path / "api" / "robokin.html").write_text('<dt id="robokin.ik">')
    assert check_reference.main(["check_reference.py", str(tmp_path)]) == 1
    expected = check_reference.expected_anchors()
    assert {"robokin.ik", "robokin.Chain.fk", "robokin.symbolic.fk", "module-robokin.symbolic"} <= expected
