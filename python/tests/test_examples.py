"""The scripts of examples/python run and write their figures."""

import os
import subprocess
import sys

import pytest

pytest.importorskip("matplotlib")


@pytest.mark.parametrize("script, figure, options", [
    ("chapter6_comparison.py", "chapter6_comparison.png", ["--record", "{record}"]),
    ("clipped_optimal.py", "clipped_optimal.png", ["--record", "{record}"]),
    ("damper_size_sweep.py", "damper_size_sweep.png",
     ["--records", "{record}", "--duration-s", "10", "--factors", "0.5,1,2"]),
    ("odbdco_v_on_sweep.py", "odbdco_v_on_sweep.png",
     ["--records", "{record}", "--duration-s", "10", "--v-on-mm-s", "2,6,20"]),
])
def test_example_writes_its_figure(script, figure, options, source_dir, elcentro, tmp_path):
    env = dict(os.environ, MPLCONFIGDIR=str(tmp_path / "mpl"))
    args = [o.format(record=elcentro) for o in options]
    p = subprocess.run([sys.executable, str(source_dir / "examples" / "python" / script), *args,
                        "--out", str(tmp_path)], capture_output=True, text=True, env=env)
    assert p.returncode == 0, p.stderr
    png = tmp_path / figure
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"wrote {png}" in p.stdout
