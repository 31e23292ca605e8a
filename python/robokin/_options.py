"""Keyword-only options read from the core's options structs (defaults and docs written once, in C++).

A Python wrapper takes ``**options`` and forwards them to the core, which fills its options struct
from them (cpp/bindings/options.hpp) and validates it; :func:`with_options` gives the wrapper the
signature users see in ``help()`` and their editors (every option as a keyword-only parameter with
the struct's default) and an ``Options:`` section in its docstring from the struct's field docs.
"""

from __future__ import annotations

import inspect
import textwrap
from typing import Callable, TypeVar

F = TypeVar("F", bound=Callable)


def _annotation(kind: str) -> str:
    """The core's description of a field ('float', 'None or int') as a type annotation."""
    return f"Optional[{kind[len('None or '):]}]" if kind.startswith("None or ") else kind


def options_section(options_class, indent: str = "    ") -> str:
    """The ``Options:`` section of a docstring, its heading at ``indent``: each field of
    ``options_class`` with its kind, its default and its doc (the header's)."""
    defaults = options_class()
    lines = [f"{indent}Options (keyword-only, the fields of :class:`{options_class.__name__}`):"]
    for name, kind in zip(options_class.fields, options_class.kinds):
        doc = " ".join((getattr(options_class, name).__doc__ or "").split())
        lines += textwrap.wrap(f"{name} ({kind}, default {getattr(defaults, name)!r}): {doc}", width=100,
                               initial_indent=indent + "    ", subsequent_indent=indent + "        ",
                               break_on_hyphens=False)
    return "\n".join(lines) + "\n"


def _with_options_section(doc: str, options_class) -> str:
    """doc with the options' section inserted before its ``Returns:`` (else at its end)."""
    lines = doc.splitlines(keepends=True)
    for i, line in enumerate(lines):
        if line.strip() == "Returns:":
            section = options_section(options_class, line[:len(line) - len(line.lstrip())])
            return "".join(lines[:i]) + section + "\n" + "".join(lines[i:])
    return doc.rstrip() + "\n\n" + options_section(options_class)


def with_options(options_class) -> Callable[[F], F]:
    """Decorator: replaces the ``**options`` of the wrapped function's signature by one keyword-only
    parameter per field of ``options_class`` (a bound core options struct), default from
    ``options_class()``, adds the fields' docs to its docstring and records the class as
    ``func.options_class``."""
    defaults = options_class()

    def decorate(func: F) -> F:
        sig = inspect.signature(func)
        params = [p for p in sig.parameters.values() if p.kind is not inspect.Parameter.VAR_KEYWORD]
        params += [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=getattr(defaults, name),
                                     annotation=_annotation(kind))
                   for name, kind in zip(options_class.fields, options_class.kinds)]
        func.__signature__ = sig.replace(parameters=params)
        func.__doc__ = _with_options_section(func.__doc__ or "", options_class)
        func.options_class = options_class
        return func

    return decorate
