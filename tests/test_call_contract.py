"""Every public call has one shape: data arguments (positional or keyword), a few named call
arguments, and the fields of one bound options class as keyword-only options, whose defaults are
written once, in C++. The test walks the public API (every module's ``__all__``, every public
method of every class in it, Python wrappers and core calls alike) and fails when a keyword is
neither a data argument, a call argument below nor a field of the call's options class; when a
``**kwargs`` is not an options class's; when Python re-states an option's default; or when a data
argument has a default (other than None) that the table of data defaults below does not explain,
so that no option hides among the positional arguments."""

import importlib
import inspect
import pkgutil
import re


import robokin
from robokin import _core
from robokin._options import with_options

# Keyword-only arguments that are not options, and why each is a call's own.
CALL_ARGUMENTS = {
    "seed": "the generator's seed: which restarts run, not how a solve runs",
    "path": "ik_batch: the targets form a path (how the data is laid out)",
    "nullspace": "resolved against the chain (its joint limits) before it is an option",
    "chunks": "robokin.dask: how the data is cut, not what is computed",
    "areas": "the design study: the function computing the areas (robokin.dask passes its own)",
    "ax": "a figure's axes",
    "frames": "plots.arm: what the drawing shows (a figure's content; no computation reads it)",
    "axes": "plots.arm: what the drawing shows (a figure's content; no computation reads it)",
    "ellipsoid": "plots.arm: what the drawing shows (a figure's content; no computation reads it)",
    "out": "numpy's idiom: the caller's array the result is written into",
}

# Parameters named like an option of some class whose default is a data default of their own.
DATA_DEFAULTS = {
    ("robokin.traj", "dt"): "a trajectory's sampling period, not the Reach loop's time step",
}

# Data arguments with a default (other than None), and why each is data, not an option: what is
# computed, or about what, not how the computation runs.
POSITIONAL_DEFAULTS = {
    **dict.fromkeys(("a1", "a2", "a3", "d1", "d6", "stroke", "base_radius", "platform_radius", "l1", "l2"),
                    "an arm's dimensions: the robot computed for (the textbook's by default)"),
    **dict.fromkeys(("part", "task", "measure", "in_frame", "mode"),
                    "which quantity is computed (the frame or its point, the task's rows, the measure, the "
                    "frame a point is expressed in, the 3-RRR's working mode)"),
    "limits": "the joint limits solutions are marked against ('default': the chain's)",
    "modified": "the DH table's convention: how the data reads",
    "qdot_max": "the robot's joint speed limits: what counts as a reconfiguration",
    "method": "which closed form or IK gives the solutions (track_postures, closed.planar_3r): both give the "
              "same answers by their definitions",
    "starts": "track_postures' numerical sets: how many IK starts sample each waypoint's postures",
    "tol": "RRR3.singularity: the normalised determinant below which a pose is called singular (the answer's "
           "definition; RRR3_DEFAULTS['singular_tol'] by default)",
    **dict.fromkeys(("num", "dt", "radius", "center", "k", "law"),
                    "the path or trajectory sampled: its sizes, its sampling, its time law"),
    "lengths": "robokin.symbolic: the lengths as symbols or as the chain's values (what the formula shows)",
    "simplify": "robokin.symbolic: whether the formula is simplified (what it shows)",
    **dict.fromkeys(("color", "alpha", "lw", "axis", "fps", "size", "surface_samples", "snapshots"),
                    "a figure's or an animation's content and look"),
}

# Core calls that take **kwargs: the options classes that they fill (and their docstrings list).
CORE_KWARGS = {
    "RRR3.workspace": ["RRR3WorkspaceOptions"],
    "RRR3.plan": ["RRR3PlanOptions"],
    "RRR3.connect": ["RRR3ConnectOptions"],
    "RRR3.plan_loop": ["RRR3LoopOptions"],  # and the plan's but phi and closed, as its doc says
    "IKSolver.__init__": ["IKOptions"],
    "RRR3.ik_newton": ["RRR3NewtonOptions"],
    "RRR3.fk": ["RRR3NewtonOptions"],
    "ClosedSolver.__init__": ["ClosedFamilyOptions"],
}

PUBLIC_MODULES = ["robokin"] + sorted(
    f"robokin.{m.name}" for m in pkgutil.iter_modules(robokin.__path__)
    if not m.name.startswith("_") and m.name not in ("demo", "demo_postures"))

OPTIONS_CLASSES = {name: cls for name, cls in vars(_core).items()
                   if inspect.isclass(cls) and hasattr(cls, "fields") and hasattr(cls, "kinds")}


def field_defaults():
    """Each option name -> the set of reprs of its defaults across the options classes."""
    out = {}
    for cls in OPTIONS_CLASSES.values():
        for name in cls.fields:
            out.setdefault(name, set()).add(repr(getattr(cls(), name)))
    return out


def public_calls():
    """(module, qualified name, callable) of every public call, each once."""
    seen, calls = set(), []
    for module_name in PUBLIC_MODULES:
        module = importlib.import_module(module_name)
        for name in module.__all__:
            obj = getattr(module, name)
            if inspect.isclass(obj):
                if name in OPTIONS_CLASSES:
                    continue  # an options class's constructor takes its own fields
                members = [(f"{name}.{a}", getattr(obj, a)) for a, v in vars(obj).items()
                           if (not a.startswith("_") or a == "__init__") and callable(getattr(obj, a))]
            elif callable(obj) and not inspect.ismodule(obj):
                members = [(name, obj)]
            else:
                continue
            for qualname, f in members:
                if id(f) not in seen:
                    seen.add(id(f))
                    calls.append((module_name, qualname, f))
    return calls


def split_top(text):
    """text split at the commas outside brackets and quotes."""
    parts, depth, quote, current = [], 0, None, ""
    for ch in text:
        if quote:
            quote = None if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(current.strip())
            current = ""
            continue
        current += ch
    if current.strip():
        parts.append(current.strip())
    return parts


def core_parameters(f):
    """(name, kind) of a core call's parameters from pybind11's signature line: kind 'positional',
    'keyword' (after a bare *) or 'kwargs'."""
    line = (f.__doc__ or "").splitlines()[0]
    m = re.match(r"\w+\((.*)\)( -> .*)?$", line)
    assert m, f"no signature line in {line!r}"
    out, keyword_only = [], False
    for part in split_top(m.group(1)):
        if part == "*":
            keyword_only = True
        elif part.startswith("**"):
            out.append((part[2:], "kwargs"))
        elif not part.startswith("self"):
            out.append((part.split(":")[0].split("=")[0].strip(), "keyword" if keyword_only else "positional"))
    return out


def core_defaults(f):
    """{name: default text} of a core call's positional parameters with a default."""
    line = (f.__doc__ or "").splitlines()[0]
    m = re.match(r"\w+\((.*)\)( -> .*)?$", line)
    out = {}
    for part in split_top(m.group(1)):
        if part == "*" or part.startswith("**"):
            break
        if "=" in part and not part.startswith("self"):
            out[part.split(":")[0].split("=")[0].strip()] = part.split("=", 1)[1].strip()
    return out


def loose_default(qualname, name, default):
    """The problem of a data argument's default that no table explains, or None."""
    if default == "None" or name in POSITIONAL_DEFAULTS or name in CALL_ARGUMENTS:
        return None
    return (f"{qualname}: {name}={default} is a data argument's default no table explains (an option? a "
            "field of the call's options class; data? POSITIONAL_DEFAULTS, with the reason)")


def problems_of(module_name, qualname, f, defaults):
    """What breaks the call contract in one call's signature."""
    try:
        sig = inspect.signature(f)
    except (TypeError, ValueError):
        sig = None
    if sig is None or "self" in sig.parameters and list(sig.parameters)[1:] == ["args", "kwargs"]:
        if not (getattr(f, "__doc__", None) or "").startswith(f.__name__ + "("):
            return []  # pybind11's placeholder of a class without a constructor
        problems = []
        for name, kind in core_parameters(f):
            if kind == "kwargs":
                classes = CORE_KWARGS.get(qualname)
                if classes is None:
                    problems.append(f"{qualname}: **{name} is no options class's (add it to CORE_KWARGS)")
                    continue
                for field in OPTIONS_CLASSES[classes[0]].fields:
                    if f"{field}=" not in f.__doc__:
                        problems.append(f"{qualname}: its docstring does not list the option {field}")
            elif kind == "keyword" and name not in CALL_ARGUMENTS:
                problems.append(f"{qualname}: keyword {name!r} is neither an option nor a call argument")
        problems += [p for name, d in core_defaults(f).items() if (p := loose_default(qualname, name, d))]
        return problems
    fields = set(getattr(f, "option_names", ()))
    problems = []
    for p in sig.parameters.values():
        if p.kind is p.VAR_KEYWORD:
            problems.append(f"{qualname}: **{p.name} takes keywords no options class checks (use with_options)")
        elif p.kind is p.KEYWORD_ONLY and p.name not in fields and p.name not in CALL_ARGUMENTS:
            problems.append(f"{qualname}: keyword {p.name!r} is neither an option nor a call argument")
        elif (p.name not in fields and p.default not in (p.empty, None) and repr(p.default) in defaults.get(p.name, ())
              and (module_name, p.name) not in DATA_DEFAULTS):
            problems.append(f"{qualname}: {p.name}={p.default!r} re-states the option {p.name} (defaults live in C++)")
        elif p.kind is p.POSITIONAL_OR_KEYWORD and p.default is not p.empty:
            if problem := loose_default(qualname, p.name, repr(p.default)):
                problems.append(problem)
    return problems


def test_every_public_call_keeps_the_contract():
    defaults = field_defaults()
    calls = public_calls()
    assert len(calls) > 100  # the walk reaches the API, not a handful of names
    problems = [msg for module_name, qualname, f in calls for msg in problems_of(module_name, qualname, f, defaults)]
    assert not problems, "\n".join(problems)


def test_the_options_of_python_wrappers_are_their_class_fields_with_the_core_defaults():
    for module_name, qualname, f in public_calls():
        options_class = getattr(f, "options_class", None)
        if options_class is None or not inspect.isfunction(f):
            continue
        params = inspect.signature(f).parameters
        shown = f.option_names
        assert shown and set(shown) <= set(options_class.fields), qualname
        for name in shown:
            assert params[name].kind is inspect.Parameter.KEYWORD_ONLY, (qualname, name)
            assert f"{name} (" in f.__doc__, f"{qualname}: its docstring does not document the option {name}"


def test_every_options_class_is_some_calls():
    used = {getattr(f, "options_class", None) for _, _, f in public_calls()}
    used |= {OPTIONS_CLASSES[c] for classes in CORE_KWARGS.values() for c in classes}
    assert set(OPTIONS_CLASSES.values()) <= used, set(OPTIONS_CLASSES) - {c.__name__ for c in used if c}


# --- the checker itself: it finds what it is for -----------------------------------------------------

def test_the_checker_finds_a_stray_keyword_a_loose_kwargs_and_a_restated_default():
    defaults = field_defaults()

    def stray(chain, *, colour="red"):
        """stray(chain)"""

    def loose(chain, **kwargs):
        """loose(chain)"""

    def restated(robot, n=200):
        """restated(robot)"""

    def hidden(chain, q, iterations=50):
        """hidden(chain, q)"""

    @with_options(_core.RRR3WorkspaceOptions)
    def fine(robot, *, ax=None, **options):
        """fine(robot)"""

    assert problems_of("m", "stray", stray, defaults) == ["stray: keyword 'colour' is neither an option nor a call argument"]
    assert problems_of("m", "loose", loose, defaults) == [
        "loose: **kwargs takes keywords no options class checks (use with_options)"]
    assert problems_of("m", "restated", restated, defaults) == [
        "restated: n=200 re-states the option n (defaults live in C++)"]
    assert problems_of("m", "fine", fine, defaults) == []
    assert problems_of("m", "hidden", hidden, defaults) == [
        "hidden: iterations=50 is a data argument's default no table explains (an option? a field of the call's "
        "options class; data? POSITIONAL_DEFAULTS, with the reason)"]


def test_the_checker_reads_core_signatures():
    assert core_parameters(_core.RRR3.workspace) == [("kwargs", "kwargs")]
    assert core_parameters(_core.ik) == [("chain", "positional"), ("target", "positional"), ("q0", "positional"),
                                         ("seed", "positional"), ("kwargs", "kwargs")]
    assert problems_of("robokin", "RRR3.workspace", _core.RRR3.workspace, field_defaults()) == []
    assert problems_of("robokin", "RRR3.nothing", _core.RRR3.workspace, field_defaults()) == [
        "RRR3.nothing: **kwargs is no options class's (add it to CORE_KWARGS)"]
    assert split_top("a: tuple[int, int] = (1, 2), b: str = 'x,y'") == ["a: tuple[int, int] = (1, 2)", "b: str = 'x,y'"]
    assert core_defaults(_core.RRR3.singularity) == {"mode": "(1, 1, 1)", "tol": "0.001"}
