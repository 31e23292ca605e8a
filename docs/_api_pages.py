"""The API reference's pages, written when the site build starts: one page for the package's own
names (``robokin.__all__``), one per class among them, one per public module.

Each object is described once (Sphinx would otherwise warn of a duplicate, and -W fail): a module's
names that the package re-exports are described on the package's pages, and the module's page links
to them. The public modules are those tests/test_public_modules.py checks: every module of the
package whose name has no leading underscore, less the demos (programs, not APIs).
"""

import importlib
import inspect
import pathlib
import pkgutil
import re

import docutils.nodes

PROGRAMS = ("demo", "demo_postures")

# pybind11 spells types by their module paths; the reference reads as the stubs and the docstrings do.
_SPELLING = [
    (r"robokin\._core\.", ""),
    (r"numpy\.typing\.NDArray\[numpy\.float64\]", "ndarray"),
    (r"numpy\.typing\.NDArray\[numpy\.(\w+)\]", r"ndarray[\1]"),
    (r"numpy\.typing\.ArrayLike", "array_like"),
    (r"numpy\.ndarray", "ndarray"),
    (r"typing\.SupportsInt \| typing\.SupportsIndex", "int"),
    (r"typing\.SupportsFloat \| typing\.SupportsIndex", "float"),
    (r"collections\.abc\.", ""),
    (r"typing\.", ""),
    (r"os\.PathLike", "PathLike"),
    (r"TypeAliasForwardRef\('([^']*)'\)", r"\1"),  # an alias of conf.autodoc_type_aliases, in a union
]


def public_modules():
    import robokin

    return sorted(m.name for m in pkgutil.iter_modules(robokin.__path__)
                  if not m.name.startswith("_") and m.name not in PROGRAMS)


def clean(text):
    for pattern, repl in _SPELLING:
        text = re.sub(pattern, repl, text)
    return text


def clean_signature(app, what, name, obj, options, signature, return_annotation):
    if signature is None:
        return None
    signature = clean(signature)
    # A bound method's first parameter (self: Chain) is said by its place in the class.
    signature = re.sub(r"^\(self(: [\w.]+)?(, )?", "(", signature)
    return signature, clean(return_annotation) if return_annotation else return_annotation


# Sphinx's own roles and directives, unknown to plain docutils: not a fault of the docstring.
_SPHINX_ONLY = ("Unknown interpreted text role", "Unknown directive type", "No role entry", "No directive entry")


def _rest_problems(text):
    """docutils' warnings and errors for ``text`` parsed as reStructuredText, Sphinx's roles aside."""
    import docutils.core
    import docutils.utils

    # Sphinx's roles and directives need its build environment: checked as plain ones.
    text = re.sub(r":[\w:.+-]+:`", "`", text)
    text = re.sub(r"^(\s*)\.\. [\w:-]+::", r"\1.. note::", text, flags=re.M)
    doctree = docutils.core.publish_doctree(text, settings_overrides={"report_level": 5, "halt_level": 5,
                                                                        "warning_stream": False})
    return [m for m in doctree.findall(docutils.nodes.system_message)
            if m["level"] >= 2 and not any(s in m.astext() for s in _SPHINX_ONLY)]


def clean_docstring(app, what, name, obj, options, lines):
    """Module paths out of the text; a docstring written as plain text (most of the core's, and the
    Python ones whose lists docutils would misread) is shown as written, in a literal block, rather
    than as broken markup."""
    type_doc = (inspect.getdoc(type(obj)) or "").strip().splitlines()
    if what in ("data", "attribute") and not inspect.isroutine(obj) and type_doc and type_doc[0] in lines:
        lines[:] = []  # a constant without a doc comment: not its type's (numpy.ndarray's, dict's) docstring
        return
    lines[:] = [clean(line) for line in lines]
    # |det A| is an absolute value, not a substitution.
    escaped = [re.sub(r"(?<![\\`])\|([^|`\n]+)\|", r"\\|\1\\|", line) for line in lines]
    if lines and _rest_problems("\n".join(escaped)):
        lines[:] = [".. code-block:: text", ""] + ["   " + line for line in lines] + [""]
    else:
        lines[:] = escaped


def shadowed(rk, name):
    """A module whose name the package gives to something else (robokin.ik is the function): its
    page is not the index target of that name."""
    return hasattr(rk, name) and not inspect.ismodule(getattr(rk, name))


def _title(text, mark="="):
    return f"{text}\n{mark * len(text)}\n"


def _package_page(rk, classes):
    funcs = [n for n in rk.__all__ if callable(getattr(rk, n)) and not inspect.isclass(getattr(rk, n))
             and not inspect.ismodule(getattr(rk, n))]
    data = [n for n in rk.__all__ if not callable(getattr(rk, n)) and not inspect.ismodule(getattr(rk, n))]
    out = [_title("robokin"), ".. module:: robokin\n", "The names ``import robokin as rk`` gives.\n",
           _title("Classes", "-"), ".. toctree::\n   :maxdepth: 1\n"]
    out += [f"   robokin.{n}" for n in classes]
    out += ["", _title("Functions", "-")]
    out += [f".. autofunction:: robokin.{n}\n" for n in funcs]
    out += [_title("Constants", "-")]
    out += [f".. autodata:: robokin.{n}\n   :no-value:\n" for n in data]
    return "\n".join(out)


def _class_page(name):
    return "\n".join([_title(f"robokin.{name}"), f".. autoclass:: robokin.{name}", "   :members:",
                      "   :undoc-members:", ""])


def _module_page(rk, name):
    module = importlib.import_module(f"robokin.{name}")
    exported = {id(getattr(rk, n)): n for n in rk.__all__}
    out = [_title(f"robokin.{name}"), f".. automodule:: robokin.{name}", "   :no-members:"]
    out += ["   :no-index:", ""] if shadowed(rk, name) else [""]
    elsewhere = [n for n in module.__all__ if id(getattr(module, n)) in exported]
    own = [n for n in module.__all__ if n not in elsewhere]
    if elsewhere:
        out.append("Also in the package namespace, described there: "
                   + ", ".join(f":py:obj:`robokin.{exported[id(getattr(module, n))]}`" for n in elsewhere) + ".\n")
    for n in own:
        obj = getattr(module, n)
        if inspect.isclass(obj):
            out += [f".. autoclass:: robokin.{name}.{n}", "   :members:", "   :undoc-members:", ""]
        elif callable(obj):
            out.append(f".. autofunction:: robokin.{name}.{n}\n")
        else:
            out.append(f".. autodata:: robokin.{name}.{n}\n   :no-value:\n")
    return "\n".join(out)


def write(folder):
    """Writes the reference's pages into ``folder`` (rewritten only when changed: Sphinx rereads what is newer)."""
    import robokin as rk

    folder = pathlib.Path(folder)
    folder.mkdir(exist_ok=True)
    classes = [n for n in rk.__all__ if inspect.isclass(getattr(rk, n))]
    modules = public_modules()
    pages = {"robokin": _package_page(rk, classes)}
    pages.update({f"robokin.{n}": _class_page(n) for n in classes})
    pages.update({f"robokin.{n}": _module_page(rk, n) for n in modules})
    index = [_title("API reference"), "Generated from the docstrings (``help()`` shows the same text).\n",
             ".. toctree::\n   :maxdepth: 1\n", "   robokin"] + [f"   robokin.{n}" for n in modules]
    pages["index"] = "\n".join(index) + "\n"
    for stale in folder.glob("*.rst"):
        if stale.stem not in pages:
            stale.unlink()
    for stem, text in pages.items():
        path = folder / f"{stem}.rst"
        if not path.exists() or path.read_text() != text:
            path.write_text(text)
