"""The Python module `sympl` (src/python/: sympl_module.cpp, system.cpp, ...): the program's systems,
methods and report from Python, each result against what theory or the C++ side gives."""
import math

import numpy as np
import pytest

import sympl

HH_P1 = 0.5692099788303082  # Henon-Heiles at E = 1/6 from q = (0, 0.1), p2 = 0


def test_lists_name_the_built_in_systems_and_methods():
    names = [s["name"] for s in sympl.systems()]
    assert "henon_heiles" in names and "kepler" in names
    kepler = next(s for s in sympl.systems() if s["name"] == "kepler")
    assert kepler["parameters"]["eccentricity"] == 0.5
    assert "blanes_moan_s6" in sympl.tables()
    assert "dprkn8" in sympl.methods()


def test_a_run_returns_numpy_arrays_and_keeps_the_energy_to_the_method_order():
    hh = sympl.System("henon_heiles")
    assert hh.degrees_of_freedom == 2
    assert isinstance(hh.x0, np.ndarray) and hh.x0.shape == (4,)
    # A fourth-order table: halving dt divides the energy error by about 2^4.
    errors = [hh.run("forest_ruth_4", t_end=200.0, dt=dt)["max_energy_error"] for dt in (0.1, 0.05)]
    assert abs(math.log2(errors[0] / errors[1]) - 4) < 0.5
    r = hh.run("leapfrog_kdk", t_end=10.0, dt=0.1, energy_every=10, trajectory_every=5)
    assert r["steps"] == 100 and r["stable"]
    assert r["final_state"].shape == (4,)
    assert r["trajectory"].shape == (21, 5)  # t, q1, q2, p1, p2 every 5 steps from t = 0
    assert r["trajectory"][-1, 0] == pytest.approx(10.0)
    np.testing.assert_array_equal(r["trajectory"][-1, 1:], r["final_state"])
    # The rows are the run's own numbers, handed over, not copied: the array
    # views memory its base owns (a copy into a new array owns its own).
    assert r["trajectory"].base is not None and not r["trajectory"].flags.owndata
    # ... and the same bits as the program writes (17 digits read back).
    again = hh.run("leapfrog_kdk", t_end=10.0, dt=0.1, times=r["trajectory"][:-1, 0])["trajectory"]
    np.testing.assert_array_equal(again[:, 1:], r["trajectory"][:-1, 1:])
    assert r["energy_series"].shape[1] == 2
    assert r["energy_series"][:, 1].max() <= r["max_energy_error"]


def test_a_formula_system_runs_as_the_built_in_one():
    mine = sympl.System.from_formulas(T="(px^2 + py^2) / 2", V="(x^2 + y^2) / 2 + x^2*y - y^3/3",
                                      coordinates=["x", "y"], q0=[0, 0.1], p0=[HH_P1, 0],
                                      name="python_henon_heiles")
    builtin = sympl.System("henon_heiles")
    for method in ("blanes_moan_s6", "dprkn8"):
        a = mine.run(method, t_end=50.0, dt=0.05)
        b = builtin.run(method, t_end=50.0, dt=0.05)
        assert a["generic_path"] and not b["generic_path"]
        assert a["steps"] == b["steps"]
        # The same steps on forces equal to rounding.
        assert np.max(np.abs(a["final_state"] - b["final_state"])) < 1e-11
    assert mine.energy(mine.x0) == pytest.approx(1 / 6, rel=1e-15)


def test_errors_are_value_errors_with_the_programs_messages():
    with pytest.raises(ValueError, match="unknown system 'henon_heils'; did you mean 'henon_heiles'"):
        sympl.System("henon_heils")
    with pytest.raises(ValueError, match="unknown method 'blanes_moan_s7'"):
        sympl.System("pendulum").run("blanes_moan_s7", t_end=1.0, dt=0.1)
    with pytest.raises(ValueError, match="dt = 0; expected a finite step > 0 for leapfrog_kdk"):
        sympl.System("pendulum").run("leapfrog_kdk", t_end=1.0)
    with pytest.raises(ValueError, match="a run of 1e.15 steps; expected at most 1e.09"):
        sympl.System("pendulum").run("leapfrog_kdk", t_end=1e12, dt=1e-3)
    # What a run would hold is refused before anything is allocated, with the figures.
    with pytest.raises(ValueError, match=r"a run that would hold 17.9 GiB \(an energy series of 4e\+08 rows \(energy_every = 1\)\)"):
        sympl.System("pendulum").run("leapfrog_kdk", t_end=4e6, dt=0.01, energy_every=1)
    with pytest.raises(ValueError, match=r"would hold 36.9 GiB \(a trajectory of 4e\+08 rows\)"):
        sympl.System("pendulum").run("leapfrog_kdk", t_end=4e6, dt=0.01, trajectory_every=1)
    with pytest.raises(ValueError, match=r"would hold 119 GiB \(Gauss-Legendre's Jacobian and Newton matrix"):
        sympl.System("fpu_beta", {"n": 20000}).run("gauss_6", t_end=1.0, dt=0.1)
    with pytest.raises(ValueError, match="V, column 6: unknown name 'z'"):
        sympl.System.from_formulas(T="p[0]^2/2", V="q[0]*z", q0=[1.0], p0=[0.0], name="bad_formula")
    with pytest.raises(ValueError, match="needs a separable Hamiltonian"):
        sympl.System("double_pendulum").run("leapfrog_kdk", t_end=1.0, dt=0.1)
    with pytest.raises(ValueError, match="expected a one-dimensional sequence"):
        sympl.System("pendulum").energy([[1.0, 2.0]])
    with pytest.raises(TypeError):
        sympl.System(3)


def test_the_report_returns_its_work_precision_columns(tmp_path):
    scene = tmp_path / "pendulum.toml"
    scene.write_text('system = "pendulum"\nmethods = ["leapfrog_kdk", "forest_ruth_4"]\n'
                     'dt = [0.2, 0.1]\nt_end = 20\n')
    result = sympl.report([str(scene)], out=str(tmp_path / "report"), quick=True)
    wp = result["work_precision"]
    assert (tmp_path / "report" / "work_precision.csv").exists()
    assert set(wp["method"]) == {"leapfrog_kdk", "forest_ruth_4"}
    assert isinstance(wp["dt"], np.ndarray) and len(wp["dt"]) == 4


def test_the_report_figures_draw_each_methods_runs_in_sweep_order(tmp_path):
    pytest.importorskip("matplotlib")
    scene = tmp_path / "pendulum.toml"
    scene.write_text('system = "pendulum"\nmethods = ["leapfrog_kdk", "forest_ruth_4", "odeint_rk4"]\n'
                     'dt = [0.2, 0.1, 0.05]\nt_end = 20\n')
    result = sympl.report([str(scene)], out=str(tmp_path / "report"), quick=True, plots=True)
    assert set(result["figures"]) == {"final_error", "max_energy_error"}
    for measure, figure in result["figures"].items():
        png = tmp_path / "report" / f"work_precision_{measure}.matplotlib.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        (panel,) = [ax for ax in figure.axes if ax.get_visible()]
        assert panel.get_xscale() == "log" and panel.get_yscale() == "log"
        wp = result["work_precision"]
        for line in panel.get_lines():
            rows = [k for k, m in enumerate(wp["method"]) if m == line.get_label() and wp["status"][k] == "stable"
                    and wp["seconds"][k] > 0 and wp[measure][k] > 0]
            # Each curve is its method's runs, in the rows' (sweep) order, at their seconds and errors.
            assert list(line.get_xdata()) == [wp["seconds"][k] for k in rows]
            assert list(line.get_ydata()) == [wp[measure][k] for k in rows]
            assert line.get_linestyle() == ("--" if wp["kind"][rows[0]] == "odeint" else "-")
        assert sorted(line.get_label() for line in panel.get_lines()) == sorted(set(wp["method"]))
    with pytest.raises(ValueError, match="measure = 'seconds'; expected 'final_error' or 'max_energy_error'"):
        sympl.plot_report(result, "seconds")


def test_the_report_draws_with_the_module_as_loaded_under_another_name(tmp_path):
    # The module inside a package of the user's, loaded as elsewhere.sympl:
    # report(plots=True) must find plot_report in itself, not in a `sympl`.
    import importlib.util
    import os
    import pathlib
    import shutil
    import subprocess
    import sys
    package = tmp_path / "elsewhere"
    package.mkdir()
    (package / "__init__.py").write_text("")
    shutil.copy(sympl.__file__, package / pathlib.Path(sympl.__file__).name)
    scene = tmp_path / "pendulum.toml"
    scene.write_text('system = "pendulum"\nmethods = ["leapfrog_kdk"]\ndt = [0.2, 0.1]\nt_end = 10\n')
    script = ("import importlib, sys\n"
              "s = importlib.import_module('elsewhere.sympl')\n"
              f"r = s.report([{str(scene)!r}], out={str(tmp_path / 'report')!r}, plots=True)\n"
              "assert 'sympl' not in sys.modules, 'a top-level sympl was imported'\n"
              "print(sorted(r['figures']))\n")
    # Prepended, the parent's path kept (matplotlib may come from it): a
    # top-level `sympl` may then be found, and must not be imported.
    path = os.pathsep.join(p for p in (str(tmp_path), os.environ.get("PYTHONPATH", "")) if p)
    done = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env={**os.environ, "PYTHONPATH": path},
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    drawn = "['final_error', 'max_energy_error']" if importlib.util.find_spec("matplotlib") else "[]"
    assert done.stdout.strip() == drawn


def test_the_walk_through_of_docs_python_md_runs_as_written(tmp_path, monkeypatch):
    import pathlib
    import re
    page = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"
    blocks = re.findall(r"```python\n(.*?)```", page.read_text(), re.S)
    assert blocks
    monkeypatch.chdir(tmp_path)
    walk = {}  # one namespace, as a notebook runs its cells in turn
    import importlib.util
    for block in blocks:
        if "plot_report" in block and importlib.util.find_spec("matplotlib") is None:
            continue  # matplotlib is optional (README); the figures' own test skips without it too
        exec(compile(block, str(page), "exec"), walk)


def test_a_table_of_ones_own_runs_by_name_and_composes_to_its_order():
    leapfrog = sympl.Table("my_leapfrog", kick=[0.5, 0.5], drift=[1.0, 0.0], order=2)
    fourth = leapfrog.triple_jump()
    assert fourth.name != leapfrog.name and len(fourth.kick) == 4
    pendulum = sympl.System("pendulum")

    def slope(name):
        e = [pendulum.run(name, t_end=100.0, dt=dt)["max_energy_error"] for dt in (0.1, 0.05)]
        return math.log2(e[0] / e[1])

    assert abs(slope("my_leapfrog") - 2) < 0.15
    assert abs(slope(fourth.name) - 4) < 0.3
    with pytest.raises(ValueError, match="is already a method"):
        sympl.Table("leapfrog_kdk", kick=[0.5, 0.5], drift=[1.0, 0.0])
    with pytest.raises(ValueError, match="convention 'sideways'"):
        sympl.Table("odd", kick=[1.0], drift=[1.0], convention="sideways")
    verdict = sympl.check_table(kick=[0.5, 0.5], drift=[1.0, 0.0])
    assert verdict["verdict_order"] == 2
    # Symplectic Euler (order 1) then its adjoint, each for half the step, is
    # symmetric: order 2; Suzuki's five-stage fractal of a symmetric order-2
    # table is order 4.
    euler = sympl.Table("my_euler", kick=[1.0], drift=[1.0], order=1)
    assert abs(slope("my_euler") - 1) < 0.15
    assert abs(slope(euler.then(euler.adjoint()).name) - 2) < 0.15
    assert abs(slope(leapfrog.suzuki().name) - 4) < 0.3


def test_an_ensemble_runs_every_start_as_a_single_run_does():
    hh = sympl.System("henon_heiles")
    starts = np.array([[0.0, q2, math.sqrt(2 / 12 - q2 ** 2 + 2 * q2 ** 3 / 3), 0.0] for q2 in np.linspace(-0.2, 0.3, 16)])
    out = sympl.System("henon_heiles").ensemble(starts, "blanes_moan_s6", t_end=20.0, dt=0.05, threads=2)
    assert out["stable"].all() and out["final_states"].shape == (16, 4)
    single = hh.run("blanes_moan_s6", t_end=20.0, dt=0.05, x0=starts[3])
    assert np.max(np.abs(out["final_states"][3] - single["final_state"])) < 1e-12
    assert out["max_energy_error"].max() < 1e-6
    with pytest.raises(ValueError, match="expected rows of 4 numbers"):
        hh.ensemble(starts[:, :3], "blanes_moan_s6", t_end=1.0, dt=0.1)
    with pytest.raises(ValueError, match="expected a plain splitting table"):
        hh.ensemble(starts, "rk4", t_end=1.0, dt=0.1)


def test_states_at_given_times_come_from_the_interpolant_to_its_order():
    # A circular orbit, run by a tenth-order table: the Hermite interpolant's
    # error dominates, h^4/384 |x| (cubic) and h^6/46080 |x''| (quintic),
    # with |x^(k)| = 1 on the unit circle.
    kepler = sympl.System("kepler", parameters={"eccentricity": 0.0})
    times = np.linspace(0.0, 2 * math.pi, 37)
    exact = np.stack([np.cos(times), np.sin(times)], axis=1)

    def error(dt, order):
        rows = kepler.run("sofroniou_spaletta_10", t_end=2 * math.pi, dt=dt, times=times, order=order)["trajectory"]
        assert rows.shape == (37, 5)
        np.testing.assert_array_equal(rows[:, 0], times)
        return np.max(np.abs(rows[:, 1:3] - exact))

    for order, denominator in ((3, 384), (5, 46080)):
        coarse, fine = error(0.1, order), error(0.05, order)
        assert abs(math.log2(coarse / fine) - (order + 1)) < 0.15
        assert fine <= 1.1 * 0.05 ** (order + 1) / denominator
    with pytest.raises(ValueError, match="expected increasing times"):
        kepler.run("leapfrog_kdk", t_end=1.0, dt=0.1, times=[0.5, 0.2])
    with pytest.raises(ValueError, match="order = 4; expected 3 or 5"):
        kepler.run("leapfrog_kdk", t_end=1.0, dt=0.1, times=[0.5], order=4)


def test_an_ensemble_lets_other_python_threads_run():
    # The GIL is released over the C++ run: a Python thread keeps running
    # while ensembles run in another, for half a second or more in all
    # (however fast the build: they repeat until then).
    import threading
    import time
    hh = sympl.System("henon_heiles")
    starts = np.tile(hh.x0, (4000, 1))
    span = {}

    def work():
        span["from"] = time.perf_counter()
        while time.perf_counter() - span["from"] < 0.5:
            hh.ensemble(starts, "blanes_moan_s6", t_end=200.0, dt=0.05, threads=1)
        span["to"] = time.perf_counter()

    worker = threading.Thread(target=work)
    stamps = []
    worker.start()
    while worker.is_alive():
        stamps.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    assert span["to"] - span["from"] >= 0.5
    inside = [t for t in stamps if span["from"] + 0.1 < t < span["to"] - 0.1]
    # Released: a stamp about every millisecond (about 300 here). Held over
    # each call (16e6 trajectory-steps, 0.06 s or more), the GIL would let
    # the stamps through only between calls: a few per call, ten calls at most.
    assert len(inside) > 50


def test_the_charged_pushers_run_by_name_to_their_order():
    # Boris in uniform fields, and its relativistic form, are second order:
    # the final state against a run at dt/16 halves its error four-fold.
    for parameters, method in (({}, "boris"), ({"speed_of_light": 3.0}, "boris(relativistic = true)")):
        particle = sympl.System("charged_uniform", parameters=parameters)
        fine = particle.run(method, t_end=10.0, dt=0.1 / 16)["final_state"]
        errors = [np.max(np.abs(particle.run(method, t_end=10.0, dt=dt)["final_state"] - fine)) for dt in (0.1, 0.05)]
        assert abs(math.log2(errors[0] / errors[1]) - 2) < 0.15, method


def test_an_unobserved_run_keeps_the_final_state_of_the_observed_one():
    hh = sympl.System("henon_heiles")
    for method in ["blanes_moan_s6", "dprkn8", "rk4"]:
        watched = hh.run(method, t_end=100.0, dt=0.05)
        alone = hh.run(method, t_end=100.0, dt=0.05, observe=False)
        assert alone["steps"] == watched["steps"] == 2000
        assert alone["force_evaluations"] == watched["force_evaluations"]
        # The same steps; a splitting table's kicks that meet at step ends are
        # joined into one where no observer sits between them: a rounding per
        # step apart, 8e-14 after these 2000 steps.
        assert np.abs(alone["final_state"] - watched["final_state"]).max() <= 1e-12
        # The energy error at the end is at most the largest one along the way.
        assert 0 <= alone["final_energy_error"] <= watched["max_energy_error"]
        assert alone["seconds"] > 0
    with pytest.raises(ValueError, match="observe=False runs with nothing watched"):
        hh.run("rk4", t_end=1.0, dt=0.1, observe=False, trajectory_every=1)


def henon_heiles_force(q):
    x, y = q[..., 0], q[..., 1]
    return np.stack([-x - 2 * x * y, -y - x * x + y * y], axis=-1)


def henon_heiles_potential(q):
    x, y = q[..., 0], q[..., 1]
    return (x * x + y * y) / 2 + x * x * y - y**3 / 3


def test_a_python_force_runs_as_the_built_in_system_to_the_bit():
    hh = sympl.System("henon_heiles")
    mine = sympl.System.from_force(henon_heiles_force, q0=hh.x0[:2], p0=hh.x0[2:], potential=henon_heiles_potential)
    for method in ["leapfrog_kdk", "blanes_moan_s6", "dprkn8", "rk4"]:
        a = mine.run(method, t_end=20.0, dt=0.05)
        b = hh.run(method, t_end=20.0, dt=0.05)
        assert a["generic_path"]
        # The same operations on the same forces: the same numbers.
        assert np.array_equal(a["final_state"], b["final_state"])
        assert a["max_energy_error"] == b["max_energy_error"]
    # An ensemble moves all rows in lockstep, one call per kick for all of them.
    calls = []

    def counted(q):
        calls.append(q.shape)
        return henon_heiles_force(q)

    lockstep = sympl.System.from_force(counted, q0=hh.x0[:2], p0=hh.x0[2:], potential=henon_heiles_potential)
    starts = np.tile(hh.x0, (50, 1))
    starts[:, 1] += np.linspace(-0.05, 0.05, 50)
    e = lockstep.ensemble(starts, "leapfrog_kdk", t_end=10.0, dt=0.05, sample_every=20)
    f = hh.ensemble(starts, "leapfrog_kdk", t_end=10.0, dt=0.05, sample_every=20)
    assert all(shape == (50, 2) for shape in calls[1:])
    assert np.abs(e["final_states"] - f["final_states"]).max() <= 1e-12
    assert np.allclose(e["max_energy_error"], f["max_energy_error"], rtol=1e-6, atol=1e-15)
    assert e["stable"].all()


def test_a_python_force_is_checked_and_its_errors_reach_python():
    with pytest.raises(TypeError, match="force: expected a callable"):
        sympl.System.from_force(3, q0=[0.1], p0=[0.0])
    with pytest.raises(ValueError, match=r"force\(q\) returned shape \(1,\) for q of shape \(2,\)"):
        sympl.System.from_force(lambda q: q[:1], q0=[0.1, 0.2], p0=[0.0, 0.0])
    with pytest.raises(ValueError, match=r"force\(q\) is not finite at the initial state"):
        sympl.System.from_force(lambda q: np.full_like(q, np.inf), q0=[0.0, 0.2], p0=[0.0, 0.0])
    with pytest.raises(ValueError, match=r"masses\[1\] = -1; expected finite masses > 0"):
        sympl.System.from_force(henon_heiles_force, q0=[0.1, 0.2], p0=[0.0, 0.0], masses=[1.0, -1.0])
    with pytest.raises(ValueError, match=r"potential\(q\) returned shape"):
        sympl.System.from_force(henon_heiles_force, q0=[0.1, 0.2], p0=[0.0, 0.0], potential=lambda q: q)

    def fails_later(q):
        if q[0] > 0.15:
            raise ZeroDivisionError("the user's own error")
        return -q

    moving = sympl.System.from_force(fails_later, q0=[0.1, 0.0], p0=[1.0, 0.0])
    with pytest.raises(ZeroDivisionError, match="the user's own error"):
        moving.run("leapfrog_kdk", t_end=1.0, dt=0.01)
    with pytest.raises(ValueError, match="megno=True needs the force's derivative"):
        moving.ensemble(np.zeros((2, 2)), "leapfrog_kdk", t_end=1.0, dt=0.1, megno=True)
    # Tao's binding is chosen from H's second derivatives, on dual numbers: refused in a Python force's terms.
    spring = sympl.System.from_force(lambda q: -q, q0=[1.0], p0=[0.0], potential=lambda q: 0.5 * float(q @ q))
    for method in ("tao(leapfrog_kdk)", "tao(leapfrog_kdk, omega = 10)"):
        with pytest.raises(ValueError, match=r"a Python force gives F\(q\) in double only, not the second derivatives"):
            spring.run(method, t_end=1.0, dt=0.1)


def test_a_formula_system_may_carry_its_exact_solution():
    osc = sympl.System.from_formulas(T="p[0]^2 / 2", V="w^2 * q[0]^2 / 2", q0=[1.0], p0=[0.0],
                                     parameters={"w": 2.0}, exact_q=["cos(w*t)"], exact_p=["-w*sin(w*t)"],
                                     name="oscillator_exact")
    r = osc.run("leapfrog_kdk", t_end=10.0, dt=0.001)
    assert abs(r["final_state"][0] - math.cos(20.0)) < 1e-4
    with pytest.raises(ValueError, match=r"exact_q\[0\] = 0 at t = 0 where the initial q\[0\] is 1"):
        sympl.System.from_formulas(T="p[0]^2 / 2", V="q[0]^2 / 2", q0=[1.0], p0=[0.0], exact_q=["sin(t)"],
                                   exact_p=["cos(t)"], name="oscillator_wrong")


def test_a_poincare_section_lies_on_the_plane_and_keeps_the_energy():
    hh = sympl.System("henon_heiles")
    cut = hh.section("blanes_moan_s6", dt=0.05, steps=100_000)
    assert cut.shape[1] == 4 and cut.shape[0] > 100
    assert np.all(np.abs(cut[:, 0]) < 1e-12)   # x = 0
    assert np.all(cut[:, 2] > 0)               # crossing upwards: dx/dt = px > 0
    e0 = hh.energy(hh.x0)
    # Each crossing is read off the step's cubic Hermite interpolant, within
    # dt^4/384 max|x''''| of the orbit per component (poincare_section.hpp):
    # with |x''''| and |grad H| at most 2 on this orbit, its energy within
    # 4 * 2 * 2 dt^4/384 of the start (the sixth-order steps add 1e-9).
    dt = 0.05
    assert max(abs(hh.energy(row) - e0) for row in cut) <= 16 * dt**4 / 384
    with pytest.raises(ValueError, match="section method 'rk4'; expected a plain splitting table"):
        hh.section("rk4", dt=0.05, steps=10)


def test_a_scene_may_be_a_dict_and_its_mistakes_are_named():
    scene = {"name": "osc_dict", "system": "harmonic_oscillator", "methods": ["leapfrog_kdk", "dprkn8"],
             "t_end": 20.0, "dt": [0.1, 0.05]}
    with pytest.raises(TypeError, match=r"scenes\[0\]\['dt'\]\[1\]: a value of type set"):
        sympl.report([dict(scene, dt=[0.1, {0.05}])], out="unused")
    with pytest.raises(ValueError, match=r"scenes\[0\]:.*unknown key 'tend'"):
        sympl.report([dict(scene, tend=1.0)], out="unused")


def test_a_run_resumes_from_its_checkpoint_bit_for_bit(tmp_path):
    hh = sympl.System("henon_heiles")
    file = str(tmp_path / "hh.checkpoint")
    # 1000 steps, a checkpoint every 300: the file holds step 900 at the end.
    whole = hh.run("blanes_moan_s6", t_end=50.0, dt=0.05, checkpoint=file, checkpoint_every=300)
    again = hh.run("blanes_moan_s6", t_end=50.0, dt=0.05, checkpoint=file, checkpoint_every=300, resume=True)
    assert whole["steps"] == again["steps"] == 1000
    assert np.array_equal(whole["final_state"], again["final_state"])
    assert again["max_energy_error"] == whole["max_energy_error"]
    # A run that is not this one is refused, with what differs.
    with pytest.raises(ValueError, match="not resumed from"):
        hh.run("blanes_moan_s6", t_end=50.0, dt=0.025, checkpoint=file, checkpoint_every=300, resume=True)
    with pytest.raises(ValueError, match="not resumed from"):
        hh.run("blanes_moan_s6", t_end=60.0, dt=0.05, checkpoint=file, checkpoint_every=300, resume=True)
    with pytest.raises(ValueError, match="expected a file name and a number of steps > 0"):
        hh.run("blanes_moan_s6", t_end=50.0, dt=0.05, checkpoint=file)
    with pytest.raises(ValueError, match="observe=False with checkpoints"):
        hh.run("blanes_moan_s6", t_end=50.0, dt=0.05, checkpoint=file, checkpoint_every=10, observe=False)
    with pytest.raises(ValueError, match="checkpoints with trajectory_every, times or energy_every"):
        hh.run("blanes_moan_s6", t_end=50.0, dt=0.05, checkpoint=file, checkpoint_every=10, trajectory_every=5)
    # A formula system defined otherwise under the same name (in another
    # process: one process refuses two definitions of a name) is another
    # system: its checkpoint's identity holds the formulas, not the name alone.
    import subprocess
    import sys
    file = str(tmp_path / "formula.checkpoint")
    script = ("import sympl, sys\n"
              "s = sympl.System.from_formulas(T='p[0]^2 / 2', V=sys.argv[1], q0=[1.0], p0=[0.0], name='same_name')\n"
              f"s.run('leapfrog_kdk', t_end=50.0, dt=0.05, checkpoint={file!r}, checkpoint_every=300, resume=True)\n")
    first = sympl.System.from_formulas(T="p[0]^2 / 2", V="q[0]^2 / 2", q0=[1.0], p0=[0.0], name="same_name")
    first.run("leapfrog_kdk", t_end=50.0, dt=0.05, checkpoint=file, checkpoint_every=300)
    same = subprocess.run([sys.executable, "-c", script, "q[0]^2 / 2"], capture_output=True, text=True, timeout=60)
    assert same.returncode == 0, same.stderr
    other = subprocess.run([sys.executable, "-c", script, "q[0]^4 / 4"], capture_output=True, text=True, timeout=60)
    assert other.returncode != 0 and "not resumed from" in other.stderr


def test_events_are_located_as_scipy_takes_them_and_stop_a_run():
    # The oscillator q = cos t, p = -sin t: q = 0 at pi/2 + k pi, falling at
    # pi/2 + 2 k pi. Each crossing is read off the step's cubic Hermite
    # interpolant, within dt^4/384 max|q''''| = dt^4/384 in q, so in time
    # (|dq/dt| = 1 there), plus the sixth-order table's phase error (1e-10).
    osc = sympl.System("harmonic_oscillator")
    dt = 0.05

    def q_zero(t, q, p):
        return q[0]

    out = osc.events("blanes_moan_s6", t_end=20.0, dt=dt, events=[q_zero])
    exact = np.array([math.pi / 2 + k * math.pi for k in range(6)])
    assert out["t_events"][0].shape == (6,)
    assert np.max(np.abs(out["t_events"][0] - exact)) <= dt**4 / 384 + 1e-9
    assert np.max(np.abs(out["q_events"][0])) <= dt**4 / 384 + 1e-9
    assert out["stopped"] is False and out["t"] == 20.0

    def rising(t, q, p):
        return q[0]
    rising.direction = 1.0

    def stop(t, q, p):
        return q[0]
    stop.terminal = True
    stop.direction = -1
    both = osc.events("blanes_moan_s6", t_end=20.0, dt=dt, events=[rising, stop])
    assert both["t_events"][0].shape == (0,)     # the run stopped at pi/2, before the first rising crossing
    assert both["stopped"] is True
    assert abs(both["t"] - math.pi / 2) <= dt**4 / 384 + 1e-9
    assert abs(both["final_state"][0]) <= dt**4 / 384 + 1e-9
    ups = osc.events("blanes_moan_s6", t_end=20.0, dt=dt, events=[rising])["t_events"][0]
    assert np.max(np.abs(ups - np.array([3 * math.pi / 2 + 2 * k * math.pi for k in range(3)]))) <= dt**4 / 384 + 1e-9

    # The same events on the oscillator written as formulas, and on a Python force.
    mine = sympl.System.from_formulas(T="p[0]^2 / 2", V="q[0]^2 / 2", q0=[1.0], p0=[0.0], name="oscillator_events")
    theirs = sympl.System.from_force(lambda q: -q, q0=[1.0], p0=[0.0])
    for other in (mine, theirs):
        again = other.events("blanes_moan_s6", t_end=20.0, dt=dt, events=[q_zero])
        assert np.max(np.abs(again["t_events"][0] - out["t_events"][0])) <= 1e-12

    def counted(t, q, p):
        return q[0]
    counted.terminal = 3   # SciPy 1.14's "stop after 3": not offered, so refused
    with pytest.raises(ValueError, match=r"events\[0\].terminal = 3; expected True or False"):
        osc.events("leapfrog_kdk", t_end=1.0, dt=dt, events=[counted])
    with pytest.raises(TypeError, match="is not callable; expected callables g"):
        osc.events("blanes_moan_s6", t_end=1.0, dt=dt, events=[1.5])
    with pytest.raises(ValueError, match="g = nan at t = 0; expected a finite value"):
        osc.events("leapfrog_kdk", t_end=1.0, dt=dt, events=[lambda t, q, p: float("nan")])
    with pytest.raises(ZeroDivisionError):  # the callable's own exception, as Python raised it
        osc.events("leapfrog_kdk", t_end=1.0, dt=dt, events=[lambda t, q, p: 1 / 0])


def test_events_over_every_other_kind_on_the_steps_it_takes():
    # Any other kind is observed at its own steps and its crossings read off
    # the cubic Hermite interpolant between them (exact derivatives from H):
    # within h^4/384 max|d^4 g/dt^4| / |dg/dt| in time, plus the method's own
    # error. The oscillator q = cos t crosses q = 0 at pi/2 + k pi (|dq/dt| = 1).
    osc = sympl.System("harmonic_oscillator")
    exact = np.array([math.pi / 2 + k * math.pi for k in range(6)])

    def q_zero(t, q, p):
        return q[0]

    def off(out):
        assert out["t_events"][0].shape == (6,)
        return np.max(np.abs(out["t_events"][0] - exact))

    dt = 0.05
    # Compensated (order 4: phase error 1.4e-9 by the last crossing) and
    # extrapolated (outer steps of dt, order 8): within the interpolant's
    # bound and 2e-9 of the method's own.
    for method in ("compensated(blanes_moan_s6)", "extrapolated(leapfrog_kdk, 4)"):
        assert off(osc.events(method, t_end=20.0, dt=dt, events=[q_zero])) <= dt**4 / 384 + 2e-9, method
    # RK4's local error on a rotation is h^5/120, Gauss-Legendre 4's (the (2,2)
    # Pade approximant of exp) h^5/720: at time t, t h^4/120 and t h^4/720.
    assert off(osc.events("rk4", t_end=20.0, dt=0.01, events=[q_zero])) <= 0.01**4 / 384 + 20 * 0.01**4 / 120
    assert off(osc.events("gauss_4", t_end=20.0, dt=dt, events=[q_zero])) <= dt**4 / 384 + 20 * dt**4 / 720
    # Odeint's dopri5 at tolerance 1e-10: its steps are about equal on a
    # rotation (the longest below twice the mean); each accepted step errs by
    # at most the tolerance, carried on unchanged by a rotation.
    tolerance = 1e-10
    steps = osc.run("odeint_dopri5", t_end=20.0, tolerance=tolerance)["steps"]
    h = 2 * 20.0 / steps
    assert off(osc.events("odeint_dopri5", t_end=20.0, dt=0.1, events=[q_zero], tolerance=tolerance)) <= \
        h**4 / 384 + 2 * (steps + 1) * tolerance

    # LogH on the circular Kepler orbit (G M = 1, r = 1): ds/dt = T + p_t = 1,
    # so its steps are dt long. Its phase error (2.4e-8 a period here) is
    # read off its own runs: at t = 2 pi k the orbit is at angle phi_k past
    # the x axis, so y rises through 0 at 2 pi k - phi_k (angular speed 1),
    # where the events must land within the interpolant's dt^4/384.
    kepler = sympl.System("kepler", parameters={"eccentricity": 0.0})

    def y_rising(t, q, p):
        return q[1]
    y_rising.direction = 1
    out = kepler.events("logh(blanes_moan_s6)", t_end=20.0, dt=dt, events=[y_rising])
    assert out["t_events"][0].shape == (3,)
    for k, t in enumerate(out["t_events"][0], start=1):
        x, y = kepler.run("logh(blanes_moan_s6)", t_end=2 * math.pi * k, dt=dt)["final_state"][:2]
        assert abs(t - (2 * math.pi * k - math.atan2(y, x))) <= dt**4 / 384

    # A stop event ends the observed run at its first crossing, interpolated there.
    def stop(t, q, p):
        return q[0]
    stop.terminal = True
    ended = osc.events("gauss_4", t_end=20.0, dt=dt, events=[stop])
    assert ended["stopped"] is True
    assert abs(ended["t"] - math.pi / 2) <= dt**4 / 384 + 20 * dt**4 / 720
    assert abs(ended["final_state"][0]) <= dt**4 / 384 + 20 * dt**4 / 720
    # A run that blows up says where; Wisdom-Holman's runs have no events.
    with pytest.raises(RuntimeError, match="blew up|diverged"):
        sympl.System("harmonic_oscillator", parameters={"omega": 1e3}).events(
            "rk4", t_end=20.0, dt=0.05, events=[q_zero])
    with pytest.raises(ValueError, match=r"events method 'wh\(saba_2\)' \(wisdom_holman\): its runs are not "
                                         "offered with events"):
        sympl.System("outer_solar_system").events("wh(saba_2)", t_end=1000.0, dt=100.0,
                                                  events=[lambda t, q, p: q[0]])


def test_events_over_rkn_pairs_at_fixed_steps_and_controlled():
    # The oscillator's crossings of q = 0 (pi/2 + k pi) by the RKN pairs. At
    # fixed steps, on the step's cubic Hermite interpolant: within dt^4/384
    # (dprkn8's own error is far below it). Controlled, on the pair's own
    # interpolation: each accepted step's estimate, the embedded lower-order
    # solution's local error, is at most the tolerance per component
    # (absolute + relative, |x| <= 1); the pair goes on with its higher-order
    # solution, whose local error is smaller in the asymptotic range; a
    # rotation carries each step's error on unchanged: q, and the time
    # (|dq/dt| = 1 there), within 2 (steps + 1) tol. A cubic Hermite over the
    # controlled steps (mean h = 20 / steps, about 0.15) would be within
    # h^4/384, about 1e-6: the pair's interpolation is asked to beat it 1e4-fold.
    osc = sympl.System("harmonic_oscillator")
    exact = np.array([math.pi / 2 + k * math.pi for k in range(6)])

    def q_zero(t, q, p):
        return q[0]

    dt = 0.05
    fixed = osc.events("dprkn8", t_end=20.0, dt=dt, events=[q_zero])
    assert fixed["t_events"][0].shape == (6,)
    assert np.max(np.abs(fixed["t_events"][0] - exact)) <= dt**4 / 384
    tolerance = 1e-10
    steps = osc.run("dprkn8_controlled", t_end=20.0, tolerance=tolerance)["steps"]
    controlled = osc.events("dprkn8_controlled", t_end=20.0, dt=0.2, events=[q_zero], tolerance=tolerance)
    assert controlled["t_events"][0].shape == (6,)
    error = np.max(np.abs(controlled["t_events"][0] - exact))
    assert error <= 2 * (steps + 1) * tolerance
    mean_step = 20.0 / steps
    assert error < mean_step**4 / 384 / 1e4   # the pair's interpolation, not a cubic over its long steps

    def stop(t, q, p):
        return q[0]
    stop.terminal = True
    steps = osc.run("dprkn6_controlled", t_end=20.0, tolerance=tolerance)["steps"]
    ended = osc.events("dprkn6_controlled", t_end=20.0, dt=0.2, events=[stop], tolerance=tolerance)
    assert ended["stopped"] is True
    assert abs(ended["t"] - math.pi / 2) <= 2 * (steps + 1) * tolerance
    assert abs(ended["final_state"][0]) <= 2 * (steps + 1) * tolerance

    with pytest.raises(ValueError, match=r"tolerance = 2; expected a value in \(0, 1\)"):
        osc.events("dprkn8_controlled", t_end=1.0, dt=0.2, events=[q_zero], tolerance=2.0)
    # A kinetic energy that is not quadratic: refused by the system's form, as run() refuses it.
    with pytest.raises(ValueError, match="needs a kinetic energy quadratic in p"):
        sympl.System("relativistic_pendulum").events("dprkn8", t_end=1.0, dt=dt, events=[q_zero])
