"""Fixtures of the module's tests: the banks the CTest fixtures build (tests/CMakeLists.txt,
`python_module`), named by environment variables; a missing one fails the test, never skips it."""
import os

import pytest


def _env(name):
    value = os.environ.get(name)
    if not value:
        pytest.fail(f"{name} is not set: run these tests through ctest (python_module), which names the banks")
    return value


@pytest.fixture(scope="session")
def banks():
    """Paths: the sphere and (0.35, 0.2) PAN bank (fields 1-3), the sphere's modal bank (glass,
    with transfer), the tiny ground bank (steel, soil), the pebble's own PAN and its mesh, the
    glass bar's object bank and its mesh (object_checks'; 0.20 x 0.02 x 0.01 m from the origin)."""
    return {key: _env(f"CLATTER_TEST_{key.upper()}")
            for key in ("pan", "modal", "ground", "pebble_pan", "pebble_obj", "object", "object_obj")}


@pytest.fixture(scope="session")
def synth_program():
    return _env("CLATTER_SYNTH")


@pytest.fixture(scope="session")
def source_dir():
    return _env("CLATTER_SOURCE_DIR")
