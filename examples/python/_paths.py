"""Where the examples find the thesis records (the shared data folder beside the repository)."""

import os
import pathlib

REPO = pathlib.Path(__file__).resolve().parents[2]


def record(name: str = "elcentro_ns.csv") -> str:
    shared = pathlib.Path(os.environ.get("MRD_SHARED_DIR", REPO.parent / "shared"))
    return str(shared / "ground_motions" / name)
