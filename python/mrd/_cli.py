"""fragility, risk, schedule, calibrate and discrepancy: the ``mrd``
program's commands called from Python. Each keyword is the command's option
(``pga_g=[0.1, 0.2]`` is ``--pga-g 0.1 --pga-g 0.2``, ``no_plots=True`` is
``--no-plots``); the command runs as it does from a shell, with the same
checks and the same numbers, into a folder whose summary.json and CSV tables
come back as a dict and NumPy arrays. Bad input raises
:class:`mrd.UsageError` with the message the command prints after
``mrd: error:``."""

from __future__ import annotations

import csv
import json
import os
import pathlib
import shutil
import subprocess
import tempfile
from typing import Any, Dict, List, Mapping, Optional, Union

import numpy as np

from ._mrd import UsageError
from ._objects import Building, Damper, Fluid, Record, _labels, _scratch, as_file, relabel

_ERROR = "mrd: error: "


def binary() -> str:
    """The ``mrd`` program the commands run: $MRD_BINARY, else the one built
    beside this package, else ``mrd`` on PATH."""
    env = os.environ.get("MRD_BINARY")
    if env:
        return env
    try:
        from ._config import MRD_BINARY  # written by the build
    except ImportError:  # pragma: no cover - a package copied without its build
        MRD_BINARY = ""
    if MRD_BINARY and os.path.isfile(MRD_BINARY):
        return MRD_BINARY
    found = shutil.which("mrd")
    if not found:
        raise FileNotFoundError("the mrd program was not found: build it, or set MRD_BINARY")
    return found


class CommandResult:
    """What a command wrote.

    Attributes:
        summary: summary.json as a dict.
        tables: each CSV the command wrote, by file stem, as a dict of
            columns (float64 arrays; a column that is not numbers: a list of str).
        folder: the output folder (a temporary one, removed at exit, unless ``out=``).
        stdout: what the command printed.
        warnings: the command's warnings ("mrd <command>: warning: ..." lines, without the prefix).
    """

    __slots__ = ("summary", "tables", "folder", "stdout", "warnings")

    def __repr__(self) -> str:
        return f"CommandResult(folder={str(self.folder)!r}, tables={sorted(self.tables)})"


def _measured_csv(columns: Mapping[str, Any], name: str) -> str:
    """A record of named columns (time_s, displacement_m, current_cmd_A,
    force_N, ...) written as the CSV the commands read."""
    arrays = {k: np.asarray(v, dtype=np.float64) for k, v in columns.items()}
    lengths = {len(a) for a in arrays.values()}
    if len(lengths) != 1:
        raise UsageError(f"{name}: expected columns of one length, got lengths {sorted(lengths)}")
    folder = _scratch() / f"measured-{id(columns):x}-{len(os.listdir(_scratch()))}"
    folder.mkdir()
    path = folder / f"{name}.csv"
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(list(arrays))
        for row in zip(*(a.tolist() for a in arrays.values())):
            w.writerow([repr(v) for v in row])
    _labels[str(path)] = f"{name}.csv"
    return str(path)


def _value(key: str, v: Any) -> str:
    if isinstance(v, Building):
        return as_file(v, "building")
    if isinstance(v, Damper):
        return as_file(v, "damper")
    if isinstance(v, Fluid):
        return as_file(v, "fluid")
    if isinstance(v, Record):
        return as_file(v, "record")
    if isinstance(v, CommandResult):
        return str(v.folder)
    if isinstance(v, Mapping):
        return _measured_csv(v, key)
    if isinstance(v, (os.PathLike, str)):
        return os.fspath(v)
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    return str(v)


def _arguments(options: Mapping[str, Any]) -> List[str]:
    args: List[str] = []
    for key, v in options.items():
        if v is None or v is False:
            continue
        flag = "--" + key.replace("_", "-")
        if v is True:
            args.append(flag)
        elif isinstance(v, (list, tuple, np.ndarray)):
            for x in (v.tolist() if isinstance(v, np.ndarray) else v):
                args += [flag, _value(key, x)]
        else:
            args += [flag, _value(key, v)]
    return args


def _read_table(path: pathlib.Path) -> Dict[str, Any]:
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    if not rows:
        return {}
    header, body = rows[0], rows[1:]
    table: Dict[str, Any] = {}
    for c, name in enumerate(header):
        column = [r[c] if c < len(r) else "" for r in body]
        try:
            table[name] = np.array([float(x) if x != "" else np.nan for x in column], dtype=np.float64)
        except ValueError:
            table[name] = column
    return table


def run_command(command: str, out: Union[None, str, "os.PathLike[str]"] = None, **options: Any) -> CommandResult:
    """Runs ``mrd <command>`` with ``options`` (see the module's docstring)
    into ``out`` (None: a temporary folder) and reads what it wrote."""
    if out is None:
        folder = pathlib.Path(tempfile.mkdtemp(prefix=f"{command}-", dir=_scratch())) / "out"
    else:
        folder = pathlib.Path(os.fspath(out))
    args = [binary(), command, *_arguments(options), "--out", str(folder)]
    p = subprocess.run(args, capture_output=True, text=True)
    lines = p.stderr.splitlines()
    if p.returncode != 0:
        errors = [line[len(_ERROR):] for line in lines if line.startswith(_ERROR)]
        message = relabel(errors[-1] if errors else p.stderr.strip())
        if p.returncode == 2:
            raise UsageError(message)
        raise RuntimeError(f"mrd {command} failed (exit {p.returncode}): {message}")
    prefix = f"mrd {command}: warning: "
    r = CommandResult()
    r.folder = folder
    r.stdout = p.stdout
    r.warnings = [relabel(line[len(prefix):]) for line in lines if line.startswith(prefix)]
    summary = folder / "summary.json"
    r.summary = json.loads(summary.read_text()) if summary.is_file() else {}
    r.tables = {t.stem: _read_table(t) for t in sorted(folder.glob("*.csv"))}
    return r


def fragility(out: Optional[str] = None, **options: Any) -> CommandResult:
    """``mrd fragility``: fragility curves over records x PGA x idle time x
    control mode (``mrd fragility --help`` lists the options and fields).

    Example: ``mrd.fragility(record=[path], pga_g=[0.1, 0.3], idle_years=[0, 1],
    control=["passive-on"], bootstrap=0)``; ``result.tables["fragility"]``
    holds fragility.csv's columns. ``building``/``damper``/``fluid`` take
    files or mrd objects, ``record`` files or mrd.Record objects.
    """
    return run_command("fragility", out, **options)


def risk(out: Optional[str] = None, **options: Any) -> CommandResult:
    """``mrd risk``: lifetime risk per mixing policy from a fragility study
    (``fragility=`` its CommandResult, folder or fragility.csv; ``mrd risk
    --help`` lists the rest)."""
    return run_command("risk", out, **options)


def schedule(out: Optional[str] = None, **options: Any) -> CommandResult:
    """``mrd schedule``: capacity over years of service under the mixing
    policies (``mrd schedule --help``); ``tables["capacity"]`` is capacity.csv."""
    return run_command("schedule", out, **options)


def calibrate(out: Optional[str] = None, **options: Any) -> CommandResult:
    """``mrd calibrate``: fits a baseline damper model to characterization
    records (``mrd calibrate --help``). ``measured`` (and ``check``,
    ``test``) take files, or dicts of NumPy columns named as the CSV's
    (time_s, displacement_m, current_cmd_A, force_N, ...). The fitted
    damper: ``mrd.Damper.from_file(result.folder / "damper.toml")``."""
    return run_command("calibrate", out, **options)


def discrepancy(out: Optional[str] = None, **options: Any) -> CommandResult:
    """``mrd discrepancy``: names the physical effect behind a
    model-measurement gap (``mrd discrepancy --help``). ``measured`` takes a
    file or a dict of NumPy columns; ``baseline`` a damper.toml or an mrd.Damper."""
    return run_command("discrepancy", out, **options)
