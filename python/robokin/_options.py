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


def keywords(options) -> dict:
    """The fields of a bound options instance as keyword arguments."""
    return {name: getattr(options, name) for name in type(options).fields}


def _fields(options_class, exclude):
    return [(name, kind) for name, kind in zip(options_class.fields, options_class.kinds) if name not in exclude]


def options_section(options_class, indent: str = "    ", defaults=None, exclude=()) -> str:
    """The ``Options:`` section of a docstring, its heading at ``indent``: each field of
    ``options_class`` (but ``exclude``) with its kind, its default (``defaults``' value, else the
    struct's) and its doc (the header's)."""
    defaults = options_class() if defaults is None else defaults
    lines = [f"{indent}Options (keyword-only, the fields of :class:`{options_class.__name__}`):"]
    for name, kind in _fields(options_class, exclude):
        doc = " ".join((getattr(options_class, name).__doc__ or "").split())
        lines += textwrap.wrap(f"{name} ({kind}, default {getattr(defaults, name)!r}): {doc}", width=100,
                               initial_indent=indent + "    ", subsequent_indent=indent + "        ",
                               break_on_hyphens=False)
    return "\n".join(lines) + "\n"


def _with_options_section(doc: str, section) -> str:
    """doc with the options' section (``section(indent)``) inserted before its ``Returns:`` (else at
    its end)."""
    lines = doc.splitlines(keepends=True)
    for i, line in enumerate(lines):
        if line.strip() == "Returns:":
            return "".join(lines[:i]) + section(line[:len(line) - len(line.lstrip())]) + "\n" + "".join(lines[i:])
    return doc.rstrip() + "\n\n" + section("    ")


def with_options(options_class, *, defaults=None, exclude=()) -> Callable[[F], F]:
    """Decorator: replaces the ``**options`` of the wrapped function's signature by one keyword-only
    parameter per field of ``options_class`` (a bound core options struct) but ``exclude`` (fields
    the function takes as arguments of its own), default from ``defaults`` (an instance: for a call
    whose defaults differ from the struct's, which it must then apply itself) or
    ``options_class()``; adds the fields' docs to its docstring and records ``func.options_class``
    and the option names it takes, ``func.option_names``."""
    shown = options_class() if defaults is None else defaults

    def decorate(func: F) -> F:
        sig = inspect.signature(func)
        params = [p for p in sig.parameters.values() if p.kind is not inspect.Parameter.VAR_KEYWORD]
        clash = {p.name for p in params} & {name for name, _ in _fields(options_class, exclude)}
        if clash:
            raise TypeError(f"{func.__qualname__}: arguments {sorted(clash)} are {options_class.__name__} fields too")
        params += [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=getattr(shown, name),
                                     annotation=_annotation(kind))
                   for name, kind in _fields(options_class, exclude)]
        func.__signature__ = sig.replace(parameters=params)
        func.__doc__ = _with_options_section(
            func.__doc__ or "", lambda indent: options_section(options_class, indent, shown, exclude))
        func.options_class = options_class
        func.option_names = tuple(name for name, _ in _fields(options_class, exclude))
        return func

    return decorate
