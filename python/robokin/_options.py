"""Keyword-only options read from the core's options structs (defaults written once, in C++).

A Python wrapper takes ``**options`` and forwards them to the core, which fills its options struct
from them (cpp/bindings/options.hpp) and validates it; :func:`with_options` gives the wrapper the
signature users see in ``help()`` and their editors: every option as a keyword-only parameter with
the struct's default.
"""

from __future__ import annotations

import inspect
from typing import Callable, TypeVar

F = TypeVar("F", bound=Callable)


def _annotation(kind: str) -> str:
    """The core's description of a field ('float', 'None or int') as a type annotation."""
    return f"Optional[{kind[len('None or '):]}]" if kind.startswith("None or ") else kind


def with_options(options_class) -> Callable[[F], F]:
    """Decorator: replaces the ``**options`` of the wrapped function's signature by one keyword-only
    parameter per field of ``options_class`` (a bound core options struct), default from ``options_class()``."""
    defaults = options_class()

    def decorate(func: F) -> F:
        sig = inspect.signature(func)
        params = [p for p in sig.parameters.values() if p.kind is not inspect.Parameter.VAR_KEYWORD]
        params += [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=getattr(defaults, name),
                                     annotation=_annotation(kind))
                   for name, kind in zip(options_class.fields, options_class.kinds)]
        func.__signature__ = sig.replace(parameters=params)
        return func

    return decorate
