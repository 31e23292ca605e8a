"""A matplotlib Figure for robokin's plotting modules, made without pyplot."""

from __future__ import annotations


def new_figure(**kwargs):
    """A Figure outside pyplot's global state (no display needed; save it with fig.savefig)."""
    try:
        from matplotlib.figure import Figure
        from mpl_toolkits import mplot3d  # type: ignore[import-untyped]  # noqa: F401  (registers 3-D)
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("robokin.plots needs matplotlib: pip install 'robokin[plot]'") from exc
    return Figure(**kwargs)
