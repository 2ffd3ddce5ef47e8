"""Paths the tests need, from the environment ctest sets (python/CMakeLists.txt)."""

import os
import pathlib

import pytest


def _path(name: str) -> pathlib.Path:
    value = os.environ.get(name)
    if not value:
        pytest.skip(f"{name} is not set (run the tests through ctest -L python)")
    return pathlib.Path(value)


@pytest.fixture(scope="session")
def mrd_binary() -> pathlib.Path:
    return _path("MRD_BINARY")


@pytest.fixture(scope="session")
def shared_dir() -> pathlib.Path:
    return _path("MRD_SHARED_DIR")


@pytest.fixture(scope="session")
def source_dir() -> pathlib.Path:
    return _path("MRD_SOURCE_DIR")


@pytest.fixture(scope="session")
def elcentro(shared_dir: pathlib.Path) -> str:
    path = shared_dir / "ground_motions" / "elcentro_ns.csv"
    if not path.is_file():
        pytest.skip(f"{path} is missing (the shared thesis data)")
    return str(path)
