"""help() for the core's free functions as for Python's own, and Python's own written as the core's.

pybind11 makes each a built-in function whose ``__self__`` is its function record, so pydoc heads
its help ``joint_limit_cost(...) method of pybind11_detail_function_record_... instance`` and
``inspect.signature`` fails on it. :func:`plain` gives a function that forwards to it, with the
signature of pybind11's first docstring line as ``__signature__`` and the rest of the docstring as
its own: help(), ``inspect.signature``, the stubs and the documentation read it as written.
:func:`written` presents a Python function the same way (its postponed annotations unquoted).
"""

from __future__ import annotations

import ast
import inspect
import re
from typing import Callable, List

_HEAD = re.compile(r"^(\w+)\((.*)\)(?: -> (.+))?$")


class _Text(str):
    """An annotation (or a default that is not a literal) as pybind11 wrote it, shown without quotes."""

    def __repr__(self) -> str:
        return str(self)


def _default(text: str):
    """A default's value when it is a literal (None, False, 0.5, 'frame'), else its text."""
    try:
        return ast.literal_eval(text)
    except (ValueError, SyntaxError):
        return _Text(text)


def _split(params: str) -> List[str]:
    """The parameters of a signature's text, split at the commas outside brackets."""
    parts, depth, start = [], 0, 0
    for i, ch in enumerate(params):
        if ch in "[(":
            depth += 1
        elif ch in "])":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(params[start:i].strip())
            start = i + 1
    last = params[start:].strip()
    return parts + [last] if last else parts


def _signature(head: str) -> inspect.Signature:
    """The inspect.Signature of pybind11's ``name(a: T, b: U = d, *, c: V = e) -> R``."""
    _, params, returns = _HEAD.match(head).groups()
    kind, out = inspect.Parameter.POSITIONAL_OR_KEYWORD, []
    for text in _split(params):
        if text == "*":
            kind = inspect.Parameter.KEYWORD_ONLY
            continue
        if text.startswith("**"):
            out.append(inspect.Parameter(text[2:].split(":")[0], inspect.Parameter.VAR_KEYWORD))
            continue
        name, _, rest = text.partition(": ")
        annotation, _, default = rest.partition(" = ")
        out.append(inspect.Parameter(name, kind, annotation=_Text(annotation) if annotation else inspect.Parameter.empty,
                                     default=_default(default) if default else inspect.Parameter.empty))
    return inspect.Signature(out, return_annotation=_Text(returns) if returns else inspect.Signature.empty)


def plain(core: Callable, qualname: str, module: str) -> Callable:
    """A function forwarding to the core's built-in ``core`` (one overload), documented as it is,
    named ``module.qualname`` (``Chain.from_dh`` for a static method)."""
    head, _, doc = core.__doc__.partition("\n")

    def call(*args, **kwargs):
        return core(*args, **kwargs)

    call.__name__, call.__qualname__, call.__module__ = core.__name__, qualname, module
    call.__signature__ = _signature(head.strip())
    call.__doc__ = inspect.cleandoc(doc)
    return call


def written(func: Callable, qualname: str, module: str) -> Callable:
    """A Python function presented as the core's are: named ``module.qualname``, its docstring
    cleaned, its postponed annotations (text, PEP 563) shown as written, unquoted."""
    def unquoted(annotation):
        return _Text(annotation) if isinstance(annotation, str) else annotation

    sig = inspect.signature(func)
    func.__signature__ = sig.replace(parameters=[p.replace(annotation=unquoted(p.annotation))
                                                 for p in sig.parameters.values()],
                                     return_annotation=unquoted(sig.return_annotation))
    func.__qualname__, func.__module__ = qualname, module
    func.__doc__ = inspect.cleandoc(func.__doc__)
    return func
