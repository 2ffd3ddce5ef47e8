"""Buildings, dampers, fluids and records built in Python: read by the CLI's
file readers, so a dict that mirrors a file runs the file's run, and a bad
value is refused with the message `mrd sim` gives for the same file."""

import subprocess
import tomllib

import numpy as np
import pytest

import mrd

LEAD_RUBBER = "buildings/lead-rubber-7dof.toml"


def _lead_rubber_from_arrays():
    # buildings/lead-rubber-7dof.toml's values, typed in as arrays
    return mrd.Building.shear_chain(
        "lead-rubber-7dof",
        mass_kg=np.array([600.0e3, 500.0e3, 500.0e3, 500.0e3, 500.0e3, 500.0e3, 430.0e3]),
        stiffness_n_m=[0.0, 1.10e9, 1.05e9, 0.98e9, 0.90e9, 0.80e9, 0.68e9],
        damping_n_s_m=[0.32e6, 6.0e6, 5.7e6, 5.3e6, 4.9e6, 4.4e6, 3.7e6],
        isolators=[dict(kind="lead_rubber", count=24, characteristic_strength_n=72.0e3,
                        post_yield_stiffness_n_m=0.74e6, yield_displacement_m=0.011, exponent=2,
                        displacement_capacity_m=0.45)],
        dampers=[dict(element=0, count=1)],
    )


def test_building_from_arrays_runs_as_its_file(elcentro, source_dir):
    built = _lead_rubber_from_arrays()
    assert built.dofs == 7 and built.info["isolators"] == 1
    from_file = mrd.Building.from_file(source_dir / LEAD_RUBBER)
    a = mrd.sim(record=elcentro, duration_s=3.0, control="semi-active", building=built)
    b = mrd.sim(record=elcentro, duration_s=3.0, control="semi-active", building=from_file)
    assert a.peaks == b.peaks
    assert a.summary["building"] == "lead-rubber-7dof"
    m = mrd.load_motion(elcentro, duration_s=3.0)
    batch = mrd.batch([m], control="semi-active", building=built)
    assert batch.peaks["peak_base_displacement_m"][0] == a.peaks["peak_base_displacement_m"]


def test_damper_and_fluid_from_dicts_run_as_their_files(elcentro, source_dir):
    damper_file = source_dir / "dampers" / "thesis-200kn.toml"
    fluid_file = source_dir / "fluids" / "illustrative-20-year.toml"
    damper = mrd.Damper.from_dict(tomllib.loads(damper_file.read_text()))
    fluid = mrd.Fluid.from_dict(tomllib.loads(fluid_file.read_text()))
    assert damper.info["rated_force_n"] == 200e3
    # Table 3.1's coil, with the heating the thesis coil is assumed to have (2 K/W, 20 min).
    assert (damper.info["coil_resistance_ohm"], damper.info["coil_thermal_resistance_k_w"],
            damper.info["coil_thermal_time_constant_s"]) == (4.8, 2.0, 1200.0)
    assert (damper.info["coil_inductance_1a_h"], damper.info["coil_inductance_2a_h"]) == (5.0, 3.0)
    a = mrd.sim(record=elcentro, duration_s=3.0, idle_years=1.0, damper=damper, fluid=fluid)
    b = mrd.sim(record=elcentro, duration_s=3.0, idle_years=1.0, damper=str(damper_file), fluid=str(fluid_file))
    assert a.peaks == b.peaks


def test_record_from_an_array_runs_as_its_file(elcentro):
    r = mrd.Record.from_file(elcentro)
    assert r.dt_s == 0.02 and len(r) == 2689  # shared/ground_motions/README.md: El Centro NS, 2689 samples at 0.02 s
    copy = mrd.Record(np.array(r.accel_m_s2), r.dt_s, name="copy")
    a = mrd.sim(record=copy, duration_s=3.0, control="passive-on")
    b = mrd.sim(record=elcentro, duration_s=3.0, control="passive-on")
    assert a.peaks == b.peaks
    assert a.summary["record"] == "copy.csv"


def _cli_message(mrd_binary, args):
    p = subprocess.run([str(mrd_binary), "sim", "--duration-s", "1", *args], capture_output=True, text=True)
    assert p.returncode == 2, p.stderr
    return p.stderr[len("mrd: error: "):].rstrip("\n")


def test_bad_building_dict_has_the_file_readers_message(mrd_binary, tmp_path):
    document = {"building": {"name": "two", "mass_kg": [1e5, -1.0], "stiffness_n_m": [1e6, 1e7],
                             "damping_n_s_m": [1e3, 1e4]}}
    with pytest.raises(mrd.UsageError) as info:
        mrd.Building.from_dict(document, origin="b.toml")
    path = tmp_path / "b.toml"
    path.write_text(mrd._toml.dumps(document))
    assert str(info.value) == _cli_message(mrd_binary, ["--building", str(path)]).replace(str(path), "b.toml")
    assert "mass_kg[1]" in str(info.value)


def test_bad_damper_and_fluid_dicts(mrd_binary, source_dir, tmp_path):
    damper = tomllib.loads((source_dir / "dampers" / "thesis-200kn.toml").read_text())
    damper["rating"]["force_n"] = -5.0
    with pytest.raises(mrd.UsageError) as info:
        mrd.Damper.from_dict(damper, origin="d.toml")
    path = tmp_path / "d.toml"
    path.write_text(mrd._toml.dumps(damper))
    assert str(info.value) == _cli_message(mrd_binary, ["--damper", str(path)]).replace(str(path), "d.toml")
    fluid = tomllib.loads((source_dir / "fluids" / "thesis-model-fluid.toml").read_text())
    fluid["fluid"]["solid_fraction"] = 1.5
    with pytest.raises(mrd.UsageError, match=r"f.toml:\d+: fluid.solid_fraction"):
        mrd.Fluid.from_dict(fluid, origin="f.toml")


def test_bad_records():
    with pytest.raises(mrd.UsageError, match=r"r.csv:3: field 'accel_m_s2': expected a finite number"):
        mrd.Record([0.0, np.nan], 0.01, name="r")
    with pytest.raises(mrd.UsageError, match="expected a 1-D array"):
        mrd.Record(np.zeros((2, 2)), 0.01)
    with pytest.raises(mrd.UsageError, match="building: expected a file name or an mrd.Building, got an mrd.Record"):
        mrd.sim(building=mrd.Record([0.0, 1.0], 0.01), duration_s=1.0)


def test_load_motion_is_the_run_of_mrd_sim(elcentro):
    m = mrd.load_motion(elcentro, pga_g=0.1127, duration_s=2.0)
    assert len(m.accel_m_s2) == 2001 and not m.accel_m_s2.flags["OWNDATA"]
    assert abs(m.pga_m_s2 - 0.1127 * 9.80665) < 1e-12  # Table 6.3's PGA, standard gravity
    with pytest.raises(mrd.UsageError, match="^--pga-g"):
        mrd.load_motion(elcentro, pga_g=-1.0)
