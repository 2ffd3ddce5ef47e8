#!/usr/bin/env bash
# The spread of the closed-loop peaks over sensor noise on the hardware plant:
# the four records of Table 6.2 at 0.1127 g, fully mixed and 2.5 years idle,
# passive-off, passive-on and semi-active, each with sensor-noise seeds 1..N.
# Prints one line per record, control and idle time: mean [min–max] of the
# peak base displacement, damper force and floor acceleration, and the largest
# coil current, time above the 2.5 A rating and command changes a second.
# Usage: scripts/hardware-noise-spread.sh [--seeds N] [--mrd PATH] [--shared DIR]
#        (defaults: 20, build/host-release/host_sim/mrd, ../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=20 mrd=build/host-release/host_sim/mrd shared=../shared
while (($#)); do
  case $1 in
    --seeds) seeds=$2; shift 2 ;;
    --mrd) mrd=$2; shift 2 ;;
    --shared) shared=$2; shift 2 ;;
    *) echo "hardware-noise-spread: unknown option '$1' (expected --seeds, --mrd, --shared)" >&2; exit 2 ;;
  esac
done
[[ $seeds =~ ^[1-9][0-9]*$ ]] || { echo "hardware-noise-spread: --seeds: expected a whole number >= 1, got '$seeds'" >&2; exit 2; }
[[ -x $mrd ]] || { echo "hardware-noise-spread: $mrd: not found (build with cmake --preset host-release first)" >&2; exit 2; }
for r in hachinohe_ns northridge_sylmar_ns kobe_jma_ns elcentro_ns; do
  [[ -f $shared/ground_motions/$r.csv ]] || { echo "hardware-noise-spread: $shared/ground_motions/$r.csv: not found" >&2; exit 2; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for r in hachinohe_ns northridge_sylmar_ns kobe_jma_ns elcentro_ns; do
  for y in 0 2.5; do
    for m in passive-off passive-on semi-active; do
      for s in $(seq 1 "$seeds"); do
        "$mrd" sim --plant hardware --record "$shared/ground_motions/$r.csv" --pga-g 0.1127 --control "$m" \
          --idle-years "$y" --sensor-seed "$s" --out "$work/$r~$m~$y~$s" >/dev/null
      done
    done
  done
done
python3 - "$work" <<'PY'
import collections, glob, json, statistics, sys
runs = collections.defaultdict(list)
for f in glob.glob(sys.argv[1] + "/*/summary.json"):
    rec, mode, years, _ = f.split("/")[-2].split("~")
    runs[(rec, mode, years)].append(json.load(open(f)))
def spread(v, k, scale=1.0, digits=2):
    x = [r[k] * scale for r in v]
    return f"{statistics.mean(x):.{digits}f} [{min(x):.{digits}f}-{max(x):.{digits}f}]"
print("record control idle_years seeds | peak base disp [mm] | peak damper force [kN] | peak floor accel [m/s2]"
      " | max peak coil current [A] | max time above rated [s] | command changes [1/s]")
for (rec, mode, years), v in sorted(runs.items()):
    print(f"{rec} {mode} {years} {len(v)} | {spread(v, 'peak_base_displacement_m', 1e3)} | "
          f"{spread(v, 'peak_damper_force_kn')} | {spread(v, 'peak_superstructure_accel_m_s2', digits=3)} | "
          f"{max(r['peak_coil_current_a'] for r in v):.3f} | {max(r['time_above_rated_s'] for r in v):.3f} | "
          f"{spread(v, 'command_changes_per_s')}")
PY
