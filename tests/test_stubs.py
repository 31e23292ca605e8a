"""The type stubs of the C++ modules are generated from the bindings (scripts/make_stubs.py,
pybind11-stubgen): the committed ones must be exactly what the installed modules generate, so a
binding changed without `make stubs` fails here."""

import importlib.util
import pathlib

import robokin
import robokin._core as core

ROOT = pathlib.Path(__file__).resolve().parent.parent
spec = importlib.util.spec_from_file_location("make_stubs", ROOT / "scripts" / "make_stubs.py")
make_stubs = importlib.util.module_from_spec(spec)
spec.loader.exec_module(make_stubs)


def test_committed_stubs_are_generated_from_the_bindings():
    generated = make_stubs.generate()
    assert set(generated) == {"_core.pyi", "_testing.pyi"}
    for name, text in generated.items():
        committed = (ROOT / "python" / "robokin" / name).read_text()
        assert committed == text, f"python/robokin/{name} differs from what the bindings generate: run `make stubs`"


def test_the_stub_declares_every_public_name_of_the_core_and_ships_with_the_package():
    stub = (ROOT / "python" / "robokin" / "_core.pyi").read_text()
    public = [n for n in dir(core) if not n.startswith("_")]
    missing = [n for n in public if f"class {n}" not in stub and f"def {n}(" not in stub and f"{n}:" not in stub]
    assert not missing
    installed = pathlib.Path(robokin.__file__).parent / "_core.pyi"
    assert installed.read_text() == stub  # the installed package carries the stub users' editors read


def test_options_signatures_in_the_stub_come_from_the_core_structs():
    # The options structs' fields and docs (their headers' `fields` lists) reach the stub.
    stub = (ROOT / "python" / "robokin" / "_core.pyi").read_text()
    block = stub[stub.index("class IKOptions"):stub.index("class IKResult")]
    for name in core.IKOptions.fields:
        assert f"def {name}(self)" in block
