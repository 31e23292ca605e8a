"""The documentation site's API reference (docs/_api_pages.py writes its pages when `make docs`
starts): a page for every public module and for every class of the package's namespace, and an
autodoc directive for every public name, so that no public callable is left out of the site; and
pybind11's signatures cleaned of their module paths. (`make docs` builds the site with warnings
as errors and checks the built pages' anchors: docs/check_reference.py.)"""

import dataclasses
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


def _modules():
    """The package's namespace and its public modules, by name."""
    yield "robokin", rk
    for m in _api_pages.public_modules():
        yield f"robokin.{m}", importlib.import_module(f"robokin.{m}")


def _public_callables():
    """Every public function and static method of the package's namespace and public modules."""
    for _, module in _modules():
        for name in module.__all__:
            obj = getattr(module, name)
            if inspect.isclass(obj):
                for attr, value in vars(obj).items():
                    if isinstance(value, staticmethod):
                        yield f"{obj.__name__}.{attr}", getattr(obj, attr)
            elif callable(obj):
                yield f"{module.__name__}.{name}", obj


def test_help_reads_as_for_python_functions():
    """pydoc heads a pybind11 built-in 'method of pybind11_detail_function_record... instance' and
    inspect.signature fails on it: every public function and static method is a plain function
    with its signature (robokin._signature)."""
    import pydoc

    checked = dict(_public_callables())
    assert {"Chain.from_dh", "Chain.from_urdf", "robokin.urdf_tree", "robokin.joint_limit_cost"} <= set(checked)
    for name, fn in checked.items():
        text = pydoc.render_doc(fn, renderer=pydoc.plaintext)
        assert "pybind11" not in text.splitlines()[2], (name, text.splitlines()[2])
        signature = inspect.signature(fn)
        assert "numpy" not in str(signature) or "ArrayLike" in str(signature), name
    assert str(inspect.signature(rk.Chain.from_dh)).startswith(
        "(rows: collections.abc.Sequence, modified: bool = False, tool: numpy.typing.ArrayLike | None = None,")
    assert rk.Chain.from_dh.__qualname__ == "Chain.from_dh" and rk.urdf_tree.__module__ == "robokin"


def _methods():
    """Every public method of the package's classes (dataclasses' generated __init__ aside: their
    fields are the class docstring's), as (name, function, its parameters, its text)."""
    from robokin._signature import _signature

    seen = set()
    for _, module in _modules():
        for name in module.__all__:
            cls = getattr(module, name)
            if not inspect.isclass(cls) or id(cls) in seen:
                continue
            seen.add(id(cls))
            for attr, value in vars(cls).items():
                if (attr.startswith("_") and attr != "__init__") or isinstance(value, (property, staticmethod)):
                    continue
                if attr == "__init__" and dataclasses.is_dataclass(cls) or not callable(value):
                    continue
                doc = value.__doc__ or ""
                try:
                    params = list(inspect.signature(value).parameters.values())
                except (TypeError, ValueError):  # a pybind11 method: its signature is its doc's first line
                    head, _, doc = doc.partition("\n")
                    params = list(_signature(head.split(") -> ")[0] + ")" if ") -> " in head else head).parameters.values())
                if attr == "__init__":
                    doc += cls.__doc__ or ""
                yield f"{cls.__name__}.{attr}", params, doc


def test_every_parameter_is_named_in_its_docstring():
    """A public function's or method's docstring says what each of its parameters is: its name
    appears in the text (the options of a **kwargs are listed from their class by with_options /
    kwargs_doc; a constructor's parameters may be in its class's docstring)."""
    calls = [(name, list(inspect.signature(fn).parameters.values()), fn.__doc__ or "")
             for name, fn in _public_callables()]
    missing = []
    for name, params, doc in calls + list(_methods()):
        for p in params:
            if p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL) and p.name != "self" and p.name not in doc:
                missing.append(f"{name}({p.name})")
    assert not missing
