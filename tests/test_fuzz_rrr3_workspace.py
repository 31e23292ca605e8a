"""Property tests of RRR3WorkspaceOptions: the options of RRR3.workspace as a core struct (any
keywords hold what was given or name the keyword; validate() and RRR3.workspace accept and refuse
the same options, with the same message)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import robokin as rk

from fuzz import check_call, wild_floats

COVERS = {"RRR3WorkspaceOptions"}

values = {
    "phi": st.one_of(wild_floats, st.floats(-4.0, 4.0), st.sampled_from(["abc", None])),
    "mode": st.one_of(st.tuples(*[st.sampled_from([1, -1])] * 3), st.sampled_from([(1, 2, 1), (1, 1), "abc", None])),
    "n": st.one_of(st.integers(-3, 12), st.sampled_from([5001, 2**63, 1.5, "5", None, True])),
    "tol": st.one_of(wild_floats, st.floats(1e-9, 1.0), st.sampled_from(["abc", None])),
    "bogus": st.just(1.0),
}


@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_workspace_options_from_any_keywords(data):
    names = st.sampled_from(sorted(values))
    keys = data.draw(st.lists(names, unique=True, max_size=4))
    given_kw = {k: data.draw(values[k]) for k in keys}
    o = check_call(lambda: rk.RRR3WorkspaceOptions(**given_kw), *given_kw)
    if o is None:
        return
    for name, value in given_kw.items():
        got = getattr(o, name)
        if name == "mode":
            assert got == tuple(int(v) for v in value)
        else:
            assert got == value or (got != got and value != value)
    try:
        o.validate()
        valid = None
    except ValueError as e:
        valid = str(e)
        assert valid.split(":")[0] in o.fields
    # The map takes the same arguments and refuses them with the same message (a tiny grid: fast).
    robot = rk.RRR3()
    small = dict(phi=o.phi, mode=o.mode, n=min(o.n, 12) if o.n >= 2 else o.n, tol=o.tol)
    if valid is None:
        m = robot.workspace(**small)
        assert m.cells.shape == (small["n"], small["n"])
    else:
        with pytest.raises(ValueError) as err:
            robot.workspace(**{**small, "n": o.n})
        assert str(err.value) == valid


def test_workspace_options_defaults_are_the_calls():
    o = rk.RRR3WorkspaceOptions()
    assert (o.phi, o.mode, o.n, o.tol) == (0.0, (1, 1, 1), 200, rk.RRR3_DEFAULTS["singular_tol"])
    robot = rk.RRR3()
    a, b = robot.workspace(n=40), robot.workspace(phi=o.phi, mode=o.mode, n=40, tol=o.tol)
    np.testing.assert_array_equal(a.cells, b.cells)
