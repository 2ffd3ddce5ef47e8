"""Paths the tests need: from the environment ctest sets (tests/python/CMakeLists.txt),
else the repository's layout (build/host-release, ../shared)."""

import os
import pathlib

import pytest

_REPO = pathlib.Path(__file__).resolve().parents[2]


def _path(name: str, default: pathlib.Path) -> pathlib.Path:
    return pathlib.Path(os.environ.get(name) or default)


@pytest.fixture(scope="session")
def source_dir() -> pathlib.Path:
    return _path("MRD_SOURCE_DIR", _REPO)


@pytest.fixture(scope="session")
def shared_dir(source_dir: pathlib.Path) -> pathlib.Path:
    return _path("MRD_SHARED_DIR", source_dir.parent / "shared")


@pytest.fixture(scope="session")
def mrd_binary(source_dir: pathlib.Path) -> pathlib.Path:
    path = _path("MRD_BINARY", source_dir / "build" / "host-release" / "host_sim" / "mrd")
    if not path.is_file():
        pytest.skip(f"{path} is missing (build mrd, or set MRD_BINARY)")
    return path


@pytest.fixture(scope="session")
def elcentro(shared_dir: pathlib.Path) -> str:
    path = shared_dir / "ground_motions" / "elcentro_ns.csv"
    if not path.is_file():
        pytest.skip(f"{path} is missing (the shared thesis data)")
    return str(path)
