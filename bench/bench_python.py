"""sympl from Python against the same runs in C++, side by side in one process.

    PYTHONPATH=build/python python3 bench/bench_python.py [--quick]

1. Henon-Heiles, blanes_moan_s6, 10^6 steps: the wall time of
   System.run(observe=False) seen from Python, against the program's own
   timing of the same unobserved run in C++ (run(timing=True)['seconds'],
   the median of its repeats: what `sympl run` and the report time).
2. 10^4 Henon-Heiles starts, leapfrog_kdk, 2 threads: the wall time of
   System.ensemble seen from Python (numpy rows in, arrays out), against
   the ensemble runner's own time inside C++ (['seconds']).
3. A Python force callable (System.from_force), Henon-Heiles, leapfrog_kdk:
   the cost per step against the built-in system's.

Rounds interleaved; medians printed with the ratios (docs/python.md).
"""
import statistics
import sys
import time

import numpy as np

import sympl

quick = "--quick" in sys.argv
rounds = 3 if quick else 9
hh = sympl.System("henon_heiles")
dt = 0.01
t_end = 1e4  # 10^6 steps of dt = 0.01


def median(values):
    return statistics.median(values)


print(f"1. Henon-Heiles, blanes_moan_s6, {t_end / dt:.0f} steps")
python_s, cpp_s, ratios = [], [], []
for _ in range(rounds):
    start = time.perf_counter()
    r = hh.run("blanes_moan_s6", t_end=t_end, dt=dt, observe=False)
    wall = time.perf_counter() - start
    timed = hh.run("blanes_moan_s6", t_end=t_end, dt=dt, energy=False, timing=True)["seconds"]
    assert r["stable"] and r["steps"] == round(t_end / dt)
    python_s.append(wall)
    cpp_s.append(timed)
    ratios.append(wall / timed)
print(f"   python run(observe=False) {median(python_s) * 1e3:8.2f} ms   C++ timed run {median(cpp_s) * 1e3:8.2f} ms"
      f"   ratio {median(ratios):.3f}")

count = 10_000
rng = np.random.default_rng(7)
starts = np.zeros((count, 4))
starts[:, 1] = rng.uniform(-0.1, 0.1, count)  # y
starts[:, 3] = rng.uniform(-0.1, 0.1, count)  # py
# px from the energy 1/12 (a bounded, mostly regular shell)
potential = starts[:, 1] ** 2 / 2 - starts[:, 1] ** 3 / 3
starts[:, 2] = np.sqrt(2 * (1 / 12 - potential) - starts[:, 3] ** 2)
ens_t_end = 20.0 if quick else 100.0
print(f"2. Henon-Heiles ensemble, {count} starts, leapfrog_kdk, dt = 0.05, {ens_t_end / 0.05:.0f} steps, 2 threads")
python_s, cpp_s, ratios = [], [], []
for _ in range(rounds):
    start = time.perf_counter()
    e = hh.ensemble(starts, "leapfrog_kdk", t_end=ens_t_end, dt=0.05, threads=2)
    wall = time.perf_counter() - start
    assert e["stable"].all()
    python_s.append(wall)
    cpp_s.append(e["seconds"])
    ratios.append(wall / e["seconds"])
print(f"   python ensemble {median(python_s) * 1e3:8.2f} ms   C++ ensemble runner {median(cpp_s) * 1e3:8.2f} ms"
      f"   ratio {median(ratios):.3f}")


def force(q):
    x, y = q[..., 0], q[..., 1]
    return np.stack([-x - 2 * x * y, -y - x * x + y * y], axis=-1)


def potential(q):
    x, y = q[..., 0], q[..., 1]
    return (x * x + y * y) / 2 + x * x * y - y**3 / 3


mine = sympl.System.from_force(force, q0=hh.x0[:2], p0=hh.x0[2:], potential=potential)
steps = 10_000
print(f"3. A Python force callable, Henon-Heiles, leapfrog_kdk, {steps} steps (one force call a step)")
python_s, cpp_s, ratios = [], [], []
for _ in range(rounds):
    start = time.perf_counter()
    mine.run("leapfrog_kdk", t_end=steps * 0.05, dt=0.05, observe=False)
    wall = time.perf_counter() - start
    timed = hh.run("leapfrog_kdk", t_end=steps * 0.05, dt=0.05, energy=False, timing=True)["seconds"]
    python_s.append(wall / steps)
    cpp_s.append(timed / steps)
    ratios.append(wall / timed)
print(f"   python force {median(python_s) * 1e9:10.0f} ns a step   built-in {median(cpp_s) * 1e9:6.1f} ns a step"
      f"   ratio {median(ratios):.0f}")
rows = 1000
print(f"   the same in an ensemble of {rows} rows in lockstep (one call a kick for all rows), 200 steps:")
python_s, cpp_s, ratios = [], [], []
for _ in range(rounds):
    e = mine.ensemble(starts[:rows], "leapfrog_kdk", t_end=10.0, dt=0.05, sample_every=200)
    f = hh.ensemble(starts[:rows], "leapfrog_kdk", t_end=10.0, dt=0.05, sample_every=200, threads=1)
    python_s.append(e["seconds"] / (rows * 200))
    cpp_s.append(f["seconds"] / (rows * 200))
    ratios.append(e["seconds"] / f["seconds"])
print(f"   python force {median(python_s) * 1e9:10.1f} ns a row-step   C++ ensemble (1 thread) "
      f"{median(cpp_s) * 1e9:6.1f} ns a row-step   ratio {median(ratios):.1f}")
