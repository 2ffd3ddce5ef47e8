"""The scripts of examples/python run and write their figures."""

import os
import subprocess
import sys

import pytest

pytest.importorskip("matplotlib")


@pytest.mark.parametrize("script, figure", [
    ("chapter6_comparison.py", "chapter6_comparison.png"),
    ("clipped_optimal.py", "clipped_optimal.png"),
])
def test_example_writes_its_figure(script, figure, source_dir, elcentro, tmp_path):
    env = dict(os.environ, MPLCONFIGDIR=str(tmp_path / "mpl"))
    p = subprocess.run([sys.executable, str(source_dir / "examples" / "python" / script), "--record", elcentro,
                        "--out", str(tmp_path)], capture_output=True, text=True, env=env)
    assert p.returncode == 0, p.stderr
    png = tmp_path / figure
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"wrote {png}" in p.stdout
