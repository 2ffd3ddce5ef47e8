"""mrd.batch's speed against the C++ batch path's on the same runs.

The runs are those of bench/closed_loop_bench.cpp's BM_Batch<Mode>/<runs>: a
synthetic 40 s motion (seed 1, 0.1127 g, 1 ms step), run i scaled by
0.5 + 0.05 (i mod 31) after 0.25 (i mod 11) years idle. Three speeds, in
simulated seconds per wall second (x real time, all runs on one core):

  python     the whole mrd.batch call, as a Python user times it
  in-call    the C++ batch::run_closed_loop_batch call inside it (no Python)
  benchmark  mrd_bench_closed_loop's BM_Batch<Mode>/<runs> (its own process),
             when --cpp-bench names it

Speeds are per CPU second of the thread that runs the batch (as Google
Benchmark's rate counters are), so that other work on the machine does not
count; the wall-clock speeds are printed too. Each is the best of --repeat.
Exit status 1 when the Python call is more than 10 % slower than the
in-call C++ time (or than the benchmark's).

    PYTHONPATH=build/host-release/python python3 python/bench/batch_bench.py \\
        --cpp-bench build/host-release/bench/mrd_bench_closed_loop
"""

import argparse
import json
import subprocess
import sys

import numpy as np

import mrd

BENCH_NAMES = {"passive-off": "BM_BatchPassiveOff", "passive-on": "BM_BatchPassiveOn",
               "semi-active": "BM_BatchSemiActive"}


def cpp_benchmark_x_real_time(binary: str, mode: str, runs: int, repeat: int) -> float:
    name = f"{BENCH_NAMES[mode]}/{runs}"
    p = subprocess.run([binary, f"--benchmark_filter=^{name}$", "--benchmark_format=json",
                        f"--benchmark_repetitions={repeat}", "--benchmark_report_aggregates_only=false"],
                       capture_output=True, text=True, check=True)
    rows = [b for b in json.loads(p.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
    if not rows:
        raise SystemExit(f"{binary}: no {name} (its sizes are 8, 64 and 250 runs; semi-active 8 and 64)")
    return max(b["x_real_time"] for b in rows)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--runs", type=int, default=64, help="runs in the batch (default 64)")
    p.add_argument("--duration-s", type=float, default=40.0, help="length of the motion, s (default 40)")
    p.add_argument("--control", default="passive-on", choices=sorted(BENCH_NAMES))
    p.add_argument("--repeat", type=int, default=5, help="repetitions, best kept (default 5)")
    p.add_argument("--cpp-bench", help="mrd_bench_closed_loop, to run its BM_Batch<Mode>/<runs> too")
    a = p.parse_args()

    motion = mrd.load_motion(None, pga_g=0.1127, step_s=1e-3, duration_s=a.duration_s, seed=1)
    i = np.arange(a.runs)
    scale = 0.5 + 0.05 * (i % 31)
    idle_years = 0.25 * (i % 11)
    records = [motion.accel_m_s2] * a.runs

    best = dict(python_cpu=float("inf"), cpp_cpu=float("inf"), python_wall=float("inf"), cpp_wall=float("inf"))
    for _ in range(a.repeat):
        r = mrd.batch(records, scale=scale, idle_years=idle_years, control=a.control)
        for key, value in (("python_cpu", r.cpu_seconds), ("cpp_cpu", r.cpp_cpu_seconds),
                           ("python_wall", r.seconds), ("cpp_wall", r.cpp_seconds)):
            best[key] = min(best[key], value)
    simulated_s = r.simulated_s
    python_x = simulated_s / best["python_cpu"]
    cpp_x = simulated_s / best["cpp_cpu"]
    print(f"{a.runs} runs x {a.duration_s:g} s, {a.control}, lanes {r.lane_isa}, best of {a.repeat}, "
          "x real time per CPU second (per wall second):")
    print(f"  python     mrd.batch            {python_x:8.0f} ({simulated_s / best['python_wall']:.0f})")
    print(f"  in-call    C++ batch path       {cpp_x:8.0f} ({simulated_s / best['cpp_wall']:.0f})")
    ratio = best["python_cpu"] / best["cpp_cpu"]
    print(f"  python / in-call time: {ratio:.4f}")
    ok = ratio <= 1.10
    if a.cpp_bench:
        bench_x = cpp_benchmark_x_real_time(a.cpp_bench, a.control, a.runs, a.repeat)
        print(f"  benchmark  {BENCH_NAMES[a.control]}/{a.runs} {bench_x:8.0f} x real time")
        print(f"  benchmark / python speed: {bench_x / python_x:.4f}")
        ok = ok and bench_x / python_x <= 1.10
    print("within 10 %" if ok else "NOT within 10 %")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
