"""Python values as TOML text for mrd's file readers: a dict of tables (a
dict) and arrays of tables (a list of dicts), each table's keys numbers,
strings, booleans or lists of them. Floats are written in their shortest
form that reads back exactly (repr), so the reader sees the very values."""

from __future__ import annotations

import json
import math
from typing import Any, Dict, List, Mapping

import numpy as np


def _value(key: str, v: Any) -> str:
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        f = float(v)
        if math.isnan(f):
            return "nan"
        if math.isinf(f):
            return "inf" if f > 0 else "-inf"
        return repr(f)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, np.ndarray):
        v = v.tolist()
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(key, x) for x in v) + "]"
    raise TypeError(f"{key}: a TOML value is a number, a string, a boolean or a list of them, got {type(v).__name__}")


def _is_table(v: Any) -> bool:
    return isinstance(v, Mapping)


def _is_table_array(v: Any) -> bool:
    return isinstance(v, (list, tuple)) and len(v) > 0 and all(isinstance(x, Mapping) for x in v)


def _table(lines: List[str], header: str, table: Mapping[str, Any], array: bool) -> None:
    lines.append(f"[[{header}]]" if array else f"[{header}]")
    nested = []
    for key, v in table.items():
        if _is_table(v) or _is_table_array(v):
            nested.append((key, v))
        else:
            lines.append(f"{key} = {_value(key, v)}")
    for key, v in nested:
        if _is_table(v):
            _table(lines, f"{header}.{key}", v, False)
        else:
            for t in v:
                _table(lines, f"{header}.{key}", t, True)


def dumps(document: Mapping[str, Any]) -> str:
    """The TOML text of `document`: top-level keys are tables or arrays of tables."""
    if not isinstance(document, Mapping):
        raise TypeError(f"expected a dict of tables, got {type(document).__name__}")
    lines: List[str] = []
    for key, v in document.items():  # top-level keys first: a key after a table header belongs to it
        if not (_is_table(v) or _is_table_array(v)):
            lines.append(f"{key} = {_value(key, v)}")
    for key, v in document.items():
        if _is_table(v):
            _table(lines, key, v, False)
        elif _is_table_array(v):
            for t in v:
                _table(lines, key, t, True)
    return "\n".join(lines) + "\n"


def plain(document: Mapping[str, Any]) -> Dict[str, Any]:
    """A copy with NumPy arrays as lists (for repr and comparisons)."""
    def conv(v: Any) -> Any:
        if isinstance(v, Mapping):
            return {k: conv(x) for k, x in v.items()}
        if isinstance(v, (list, tuple)):
            return [conv(x) for x in v]
        if isinstance(v, np.ndarray):
            return v.tolist()
        return v
    return conv(document)
