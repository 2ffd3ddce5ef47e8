"""Bad input raises mrd.UsageError with the message `mrd sim` prints after 'mrd: error: '."""

import subprocess

import pytest

import mrd


def _cli_error(mrd_binary, args):
    p = subprocess.run([str(mrd_binary), "sim", *args], capture_output=True, text=True)
    assert p.returncode == 2
    prefix = "mrd: error: "
    assert p.stderr.startswith(prefix), p.stderr
    return p.stderr[len(prefix):].rstrip("\n")


def _python_error(**kw):
    with pytest.raises(mrd.UsageError) as info:
        mrd.sim(**kw)
    assert isinstance(info.value, ValueError)
    return str(info.value)


def test_missing_record(mrd_binary, tmp_path):
    path = str(tmp_path / "no-such-record.csv")
    message = _cli_error(mrd_binary, ["--record", path])
    assert path in message
    assert _python_error(record=path) == message


@pytest.mark.parametrize(
    "option, value, keyword",
    [
        ("--pga-g", "-1", dict(pga_g=-1.0)),
        ("--control", "active", dict(control="active")),
        ("--plant", "bench", dict(plant="bench")),
        ("--step-s", "0.5", dict(step_s=0.5)),
    ],
)
def test_bad_option_value(option, value, keyword, mrd_binary):
    message = _cli_error(mrd_binary, [option, value, "--duration-s", "1"])
    assert message.startswith(option)
    assert _python_error(duration_s=1.0, **keyword) == message


def test_bad_building_file(mrd_binary, tmp_path):
    path = tmp_path / "building.toml"
    path.write_text("[building]\nname = 3\n")
    message = _cli_error(mrd_binary, ["--building", str(path), "--duration-s", "1"])
    assert _python_error(building=str(path), duration_s=1.0) == message
