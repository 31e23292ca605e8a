"""Private names stay private: a module of robokin imports no private name (``_x``) of another public
module (what modules share lives in a private module, ``robokin._name``), and the simulator uses
robokin's public API only (no ``robokin._name`` module, no ``_x`` name from robokin)."""

import ast
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "python" / "robokin"
SIM = ROOT / "sim" / "robokin_sim"


def _module_of(path: pathlib.Path, root: pathlib.Path, package: str, node: ast.ImportFrom) -> str:
    """The absolute dotted name of what ``node`` imports from (``path`` lies in ``root``, the
    folder of ``package``)."""
    if not node.level:
        return node.module or ""
    parts = [package, *path.parent.relative_to(root).parts]
    base = parts[: len(parts) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _private(dotted: str) -> bool:
    return any(p.startswith("_") for p in dotted.split(".")[1:])


def violations(source: str, path: pathlib.Path, root: pathlib.Path, package: str) -> list:
    """The offending imports of one file of ``package`` (robokin, or the simulator, which may use
    robokin's public API only)."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found += [f"{path.name}:{node.lineno}: imports the private module {a.name}" for a in node.names
                      if a.name.split(".")[0] == "robokin" and _private(a.name)]
        if not isinstance(node, ast.ImportFrom) or node.module == "__future__":
            continue
        module = _module_of(path, root, package, node)
        if module.split(".")[0] == "robokin" and package != "robokin" and _private(module):
            found.append(f"{path.name}:{node.lineno}: imports the private module {module}")
        elif not _private(module):  # a private name out of a public module (robokin's own or not)
            found += [f"{path.name}:{node.lineno}: imports the private name {module}.{a.name}" for a in node.names
                      if a.name.startswith("_") and module != package]
    return found


def test_robokin_modules_import_no_private_name_of_another_module():
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        found += violations(path.read_text(), path, PACKAGE, "robokin")
    assert not found, "\n".join(found)


def test_the_simulator_uses_the_public_api_only():
    found = []
    for path in sorted(SIM.rglob("*.py")):
        found += violations(path.read_text(), path, SIM, "robokin_sim")
    assert not found, "\n".join(found)


def test_the_checker_finds_what_it_forbids():
    def bad(source, package="robokin"):
        root = PACKAGE if package == "robokin" else SIM
        return violations(source, root / "x.py", root, package)

    assert bad("from .reachability import _plan\n")
    assert bad("from .plots import plot_chain as _p, _new_figure\n")
    assert bad("from robokin.plots import _new_figure\n")
    assert not bad("from ._checks import real_array\nfrom . import robots as _robots\nfrom . import _core\n")
    assert bad("from robokin._atomic import AtomicPath\n", "robokin_sim")
    assert bad("import robokin._core\n", "robokin_sim")
    assert bad("from robokin import _core\n", "robokin_sim")
    assert bad("from robokin.plots import _new_figure\n", "robokin_sim")
    assert not bad("from robokin.files import AtomicPath\nfrom .loop import run as _run\nfrom . import _x\n",
                   "robokin_sim")
