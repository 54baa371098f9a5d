"""The Python module against the command line (the same library calls) and numpy.

Run from CTest (tests/CMakeLists.txt): PYTHONPATH holds the built module,
IDBENCH the built executable, IDBENCH_VERSION the project's version.
"""
import io
import json
import os
import signal
import subprocess
import sys

import numpy as np
import pytest

import idbench

IDBENCH = os.environ["IDBENCH"]
SOURCE_DIR = os.environ["IDBENCH_SOURCE_DIR"]


def cli(*args, cwd):
    """Runs the idbench executable; returns (exit code, stdout, stderr)."""
    done = subprocess.run([IDBENCH, *args], cwd=cwd, capture_output=True, text=True)
    return done.returncode, done.stdout, done.stderr


@pytest.fixture(scope="module")
def puma():
    return idbench.Robot("puma560")


@pytest.fixture(scope="module")
def puma_log(puma):
    # The general motion for 3 s at 200 Hz, the simulator's exact qd, qdd.
    return idbench.simulate(puma, "general", duration=3.0, rate=200.0)


def test_version_is_the_projects():
    assert idbench.__version__ == os.environ["IDBENCH_VERSION"]
    code, out, _ = cli("--version", cwd=".")
    assert code == 0
    assert out.strip() == f"idbench {idbench.__version__} (git {idbench.__git_revision__})"


def test_robots_load_by_name_and_from_urdf():
    puma = idbench.Robot("puma560")
    assert (puma.name, puma.n_dof) == ("puma560", 6)
    urdf = idbench.Robot(os.path.join(SOURCE_DIR, "engine/robots/paper6r.urdf"))
    assert urdf.n_dof == 6
    assert len(urdf.joint_names) == 6 and len(set(urdf.link_names)) == 6


def test_regressor_times_the_files_parameters_gives_the_simulated_torques(puma, puma_log):
    friction = ["viscous", "coulomb", "rotor"]
    base = idbench.base_parameters(puma, friction)
    names, pi = idbench.standard_parameters(puma, friction)
    assert len(names) == pi.size == base.combination.shape[1]
    beta = base.combination @ pi
    W = idbench.regressor(puma, puma_log["q"], puma_log["qd"], puma_log["qdd"], friction, base=base)
    n, dof = puma_log["q"].shape
    assert W.shape == (n * dof, base.n_base)
    tau = puma_log["tau"].reshape(-1)  # rows sample·n_dof + joint
    # Bullet's torques (computed-torque tracking) against the regressor's RNEA.
    assert np.linalg.norm(W @ beta - tau) / np.linalg.norm(tau) < 1e-8


def test_coulomb_min_speed_zeroes_the_coulomb_column_of_slow_samples(puma, puma_log, tmp_path):
    friction = ["viscous", "coulomb"]
    base = idbench.base_parameters(puma, friction)
    q, qd, qdd = puma_log["q"], puma_log["qd"], puma_log["qdd"]
    W = idbench.regressor(puma, q, qd, qdd, friction, base=base)
    W_min = idbench.regressor(puma, q, qd, qdd, friction, coulomb_min_speed=0.1, base=base)
    slow = (np.abs(qd) < 0.1).reshape(-1)  # rows sample·n_dof + joint
    assert 0 < slow.sum() < slow.size
    for j in range(6):
        col = base.names.index(f"Fc{j + 1}")
        rows = np.arange(j, W.shape[0], 6)
        np.testing.assert_array_equal(W_min[rows, col], np.where(slow[rows], 0.0, W[rows, col]))
        W[rows, col] = W_min[rows, col]
    np.testing.assert_array_equal(W_min, W)  # every other entry as without it

    # identify takes it as --coulomb-min-speed; a negative speed is refused naming the keyword.
    code, _, err = cli("simulate", "--robot", "puma560", "--duration", "3", "--rate", "200", "--out", "log.csv",
                       cwd=tmp_path)
    assert code == 0, err
    code, _, err = cli("identify", "--robot", "puma560", "--data", "log.csv", "--coulomb-min-speed", "0.05",
                       "--out", "id", cwd=tmp_path)
    assert code == 0, err
    expected = json.loads((tmp_path / "id/identified.json").read_text())
    result = idbench.identify(puma, str(tmp_path / "log.csv"), coulomb_min_speed=0.05)
    np.testing.assert_allclose(result.beta, [p["value"] for p in expected["base_parameters"]], rtol=1e-9)
    with pytest.raises(ValueError) as raised:
        idbench.identify(puma, str(tmp_path / "log.csv"), coulomb_min_speed=-1)
    assert str(raised.value) == "coulomb_min_speed: expected >= 0 rad/s, got -1"
    with pytest.raises(ValueError, match=r"^coulomb_min_speed: expected >= 0 rad/s, got nan$"):
        idbench.base_parameters(puma, friction, coulomb_min_speed=float("nan"))


def test_regressor_rejects_arrays_of_the_wrong_shape(puma):
    q = np.zeros((10, 5))
    with pytest.raises(ValueError, match=r"q: expected an array of 10 samples × 6 joints, got 10 × 5"):
        idbench.regressor(puma, q, q, q)


def test_identify_matches_the_command_line(puma, tmp_path):
    code, _, err = cli("simulate", "--robot", "puma560", "--duration", "3", "--rate", "200",
                       "--tau-noise", "0.05", "--seed", "7", "--out", "log.csv", cwd=tmp_path)
    assert code == 0, err
    code, _, err = cli("identify", "--robot", "puma560", "--data", "log.csv", "--estimator", "pc",
                       "--out", "id", cwd=tmp_path)
    assert code == 0, err
    expected = json.loads((tmp_path / "id/identified.json").read_text())
    beta_cli = np.array([np.nan if p["value"] is None else p["value"] for p in expected["base_parameters"]])

    from_file = idbench.identify(puma, str(tmp_path / "log.csv"), estimator="pc")
    assert from_file.base_names == [p["name"] for p in expected["base_parameters"]]
    np.testing.assert_allclose(from_file.beta, beta_cli, rtol=1e-9, equal_nan=True)
    assert from_file.urdf == (tmp_path / "id/identified.urdf").read_text()

    # The same log as arrays (as numpy reads the CSV): the same estimate.
    columns = np.loadtxt(tmp_path / "log.csv", delimiter=",", skiprows=1)
    arrays = {"t": columns[:, 0], "q": columns[:, 1:7], "qd": columns[:, 7:13], "qdd": columns[:, 13:19],
              "tau": columns[:, 19:25]}
    from_arrays = idbench.identify(puma, arrays, estimator="pc")
    np.testing.assert_allclose(from_arrays.beta, from_file.beta, rtol=1e-12, equal_nan=True)
    np.testing.assert_allclose(from_arrays.standard, from_file.standard, rtol=1e-9, atol=1e-12)

    # Measured against predicted torque: the same relative error the result reports.
    torques = from_file.torques
    residual = np.linalg.norm(torques["predicted"] - torques["measured"]) / np.linalg.norm(torques["measured"])
    assert residual == pytest.approx(from_file.fit_relative_error, rel=1e-9)
    np.testing.assert_array_equal(torques["measured"], columns[:, 19:25])


def test_unidentifiable_parameters_are_nan_never_numbers(puma):
    # The paper's motion turns joints 1 and 2 only: the other joints' friction is not excited.
    log = idbench.simulate(puma, "paper", duration=2.0, rate=200.0)
    result = idbench.identify(puma, log, friction=["viscous"])
    status = np.array(result.status)
    assert (status == "not identifiable").any()
    assert np.isnan(result.beta[status == "not identifiable"]).all()
    assert np.isfinite(result.beta[status != "not identifiable"]).all()
    fv6 = result.base_names.index("Fv6")
    assert result.status[fv6] == "not identifiable"


def two_link_urdf(com_x):
    """Two links (z then y hinges), each drawn as a 10 cm cube at x = 0.2 m, its centre of mass at com_x."""
    link = ('<link name="{0}"><inertial><origin xyz="{1} 0 0"/><mass value="2"/><inertia ixx="0.02" ixy="0" '
            'ixz="0" iyy="0.03" iyz="0" izz="0.03"/></inertial><visual><origin xyz="0.2 0 0"/><geometry>'
            '<box size="0.1 0.1 0.1"/></geometry></visual></link>')
    joint = ('<joint name="{0}" type="revolute"><parent link="{1}"/><child link="{2}"/><origin xyz="{3} 0 0"/>'
             '<axis xyz="{4}"/><limit lower="-3" upper="3" effort="100" velocity="5"/></joint>')
    return ('<robot name="two"><link name="base"/>' + link.format("arm", com_x) + link.format("forearm", com_x) +
            joint.format("shoulder", "base", "arm", 0, "0 0 1") + joint.format("elbow", "arm", "forearm", 0.4, "0 1 0") +
            "</robot>")


def test_a_refused_model_is_the_verdict_not_a_urdf(puma, tmp_path):
    # The robot's centres of mass lie 0.4 m beyond the cubes it is drawn with;
    # its file says they are in the cubes (so the load sees no contradiction).
    # The fit is pinned on the boxes far above the OLS optimum and the verdict
    # refuses the model, as the command line does (exit 1, identified.json only).
    (tmp_path / "truth.urdf").write_text(two_link_urdf(0.6))
    (tmp_path / "file.urdf").write_text(two_link_urdf(0.2))
    truth, boxed = idbench.Robot(str(tmp_path / "truth.urdf")), idbench.Robot(str(tmp_path / "file.urdf"))
    assert any("0.35 m outside the box" in w for w in truth.warnings)
    assert not boxed.warnings
    log = idbench.simulate(truth, "general", duration=5.0, rate=100.0, tau_noise=[0.01, 0.01], seed=3)
    header = ["t", "q1", "q2", "qd1", "qd2", "qdd1", "qdd2", "tau1", "tau2"]
    table = np.column_stack([log["t"], log["q"], log["qd"], log["qdd"], log["tau"]])
    np.savetxt(tmp_path / "log.csv", table, delimiter=",", header=",".join(header), comments="", fmt="%.17g")
    code, _, err = cli("identify", "--robot", "file.urdf", "--data", "log.csv", "--estimator", "pc",
                       "--out", "id", cwd=tmp_path)
    assert code == 1, err
    assert "--com-bound none" in err and "link 'forearm'" in err
    assert not (tmp_path / "id/identified.urdf").exists()
    expected = json.loads((tmp_path / "id/identified.json").read_text())["verdict"]

    result = idbench.identify(boxed, log, estimator="pc")
    verdict = result.verdict
    assert not verdict["fit_to_load"] and verdict["status"] == expected["status"]
    assert verdict["cost_excess_percent"] == pytest.approx(expected["cost_excess_percent"], rel=1e-6)
    assert verdict["cost_excess_percent"] > 100.0
    assert "com_bound='none'" in verdict["cause"] and "--" not in verdict["cause"]
    assert any("link 'forearm'" in b and "centre of mass" in b for b in verdict["bounds_at_optimum"])
    assert result.urdf is None and result.joints_yaml is None
    accepted = idbench.identify(boxed, log, estimator="pc", write_unverified=True)
    assert accepted.urdf is not None and "<robot" in accepted.urdf
    assert idbench.identify(boxed, log, estimator="pc", com_bound="none").verdict["fit_to_load"]

    # %sigma is relative to the value returned (here the pc value), NaN where it is within 3 sigma of 0.
    noisy = idbench.simulate(puma, "general", duration=3.0, rate=200.0, tau_noise=[0.05] * 6, seed=7)
    fit = idbench.identify(puma, noisy, estimator="pc")
    assert fit.verdict["fit_to_load"], fit.verdict
    small = np.abs(fit.beta) <= 3 * fit.sigma
    assert np.isnan(fit.rel_sigma_percent[small]).all()
    np.testing.assert_allclose(fit.rel_sigma_percent[~small], 100 * fit.sigma[~small] / np.abs(fit.beta[~small]),
                               rtol=1e-12)


def test_simulate_colours_the_torque_noise_to_its_band(puma):
    # The noise, recovered as noisy minus noise-free torques, keeps sigma and has the lag-1 autocorrelation
    # exp(-2 pi fc / fs) of a first-order low-pass (sensor_model.h); white noise has none.
    clean = idbench.simulate(puma, "general", duration=3.0, rate=1000.0, derivatives=False)
    coloured = idbench.simulate(puma, "general", duration=3.0, rate=1000.0, derivatives=False, tau_noise=[0.1],
                                tau_noise_bandwidth=10.0, seed=5)
    white = idbench.simulate(puma, "general", duration=3.0, rate=1000.0, derivatives=False, tau_noise=[0.1], seed=5)

    def lag1(noise):
        return np.mean([np.corrcoef(noise[1:, j], noise[:-1, j])[0, 1] for j in range(noise.shape[1])])

    noise = coloured["tau"] - clean["tau"]
    assert np.std(noise) == pytest.approx(0.1, rel=0.1)
    assert lag1(noise) == pytest.approx(np.exp(-2 * np.pi * 10.0 / 1000.0), abs=0.02)
    assert abs(lag1(white["tau"] - clean["tau"])) < 0.03
    with pytest.raises(ValueError, match="^tau_noise_bandwidth: expected 0 .white. or a band in .0, 500. Hz"):
        idbench.simulate(puma, "general", duration=1.0, tau_noise=[0.1], tau_noise_bandwidth=600.0)


def test_wrong_types_are_type_errors_naming_the_keyword(puma):
    # Issue 35 item 24: a string where a sequence of numbers goes was a RuntimeError "Unable to cast Python
    # instance..."; now a TypeError naming the keyword, and the next call works.
    log = idbench.simulate(puma, "general", duration=2.0, rate=100.0)
    with pytest.raises(TypeError, match=r"^base_pose: expected a sequence of 6 numbers .* got str$"):
        idbench.identify(puma, log, base_pose="0,0,0,0,0,0")
    with pytest.raises(TypeError, match=r"^base_pose: expected a sequence of 6 numbers .* got dict$"):
        idbench.identify(puma, log, base_pose={"x": 0})
    with pytest.raises(TypeError, match=r"\['q'\]: expected an array of numbers, got str$"):
        idbench.identify(puma, dict(log, q="nope"))
    assert idbench.identify(puma, log, base_pose=(0, 0, 0, 0, 0, 0)).fit_relative_error < 1e-3


def test_errors_carry_the_command_lines_messages_in_keywords(puma, tmp_path):
    code, _, err = cli("identify", "--robot", "puma560", "--data", "missing.csv", cwd=tmp_path)
    assert code != 0
    message = err.strip().splitlines()[-1].removeprefix("idbench: error: ")
    with pytest.raises(ValueError) as raised:
        idbench.identify(puma, "missing.csv")
    assert str(raised.value) == message

    code, _, err = cli("identify", "--robot", "puma560", "--data", "x.csv", "--estimator", "best", cwd=tmp_path)
    assert code == 2
    with pytest.raises(ValueError) as raised:
        idbench.identify(puma, "x.csv", estimator="best")
    # The same message, the option named as its keyword rather than its flag.
    assert err.strip().splitlines()[-1] == "idbench: error: --estimator: expected ols, wls, pc, tls, irls, iv or didim, got 'best'"
    assert str(raised.value) == "estimator: expected ols, wls, pc, tls, irls, iv or didim, got 'best'"

    # Fields whose keyword differs from the field are spelled as the keyword.
    with pytest.raises(ValueError) as raised:
        idbench.identify(puma, "x.csv", total_mass=-1)
    assert str(raised.value).startswith("total_mass: expected 0 (none) to 1e6 kg"), str(raised.value)
    with pytest.raises(ValueError) as raised:
        idbench.design(puma, ramp=-1)
    assert str(raised.value) == "ramp: must be in [0, 600] s, got -1", str(raised.value)


def test_design_reports_progress_and_a_feasible_trajectory(puma, tmp_path):
    # The PUMA's velocity and acceleration limits (design_cli_test.cc), a small quick design.
    limits = [{"qd_max": 1.5, "qdd_max": 4}] * 3 + [{"qd_max": 3, "qdd_max": 8}] * 3
    (tmp_path / "limits.json").write_text(json.dumps({"joints": limits}))
    calls = []
    result = idbench.design(puma, harmonics=2, f0=0.5, samples=40, starts=1, max_evaluations=25, clearance=-1,
                            friction=["viscous"], limits=str(tmp_path / "limits.json"),
                            progress=lambda *args: calls.append(args))
    assert result.feasible and not result.stopped
    assert result.usable == (result.value < result.initial_value) and result.rejection == ""
    assert calls and all(start == 0 for start, *_ in calls)
    assert np.isfinite(result.cond) and result.value <= result.initial_value
    design = json.loads(result.design_json)
    assert design["trajectory"]["harmonics"] == 2
    assert design["after"]["criterion"] == pytest.approx(result.value, rel=1e-12)
    assert isinstance(json.loads(result.trajectory_json), dict)
    # Ready for the robot, as `idbench design`: positions only, ramps from and to the given home.
    home = design["home"]["q"]
    ramped = idbench.design(puma, harmonics=2, f0=0.5, samples=40, starts=1, max_evaluations=25, clearance=-1,
                            friction=["viscous"], limits=str(tmp_path / "limits.json"), rate=100,
                            csv_columns="q", ramp=12.0, home=home)
    rows = np.genfromtxt(io.StringIO(ramped.trajectory_csv), delimiter=",", names=True)
    assert rows.dtype.names == ("t",) + tuple(f"qjoint{j}" for j in range(1, 7))  # q.joint1: numpy drops the dot
    assert len(rows) == 26 * 100 + 1
    first, last = np.array(list(rows[0]))[1:], np.array(list(rows[-1]))[1:]
    assert np.array_equal(first, home) and np.array_equal(last, home)
    with pytest.raises(ValueError, match="^home: expected 6 joint angles"):
        idbench.design(puma, home=[0.0, 0.0], limits=str(tmp_path / "limits.json"))


def test_design_progress_callbacks_that_fail_raise_in_python(puma, tmp_path):
    # 6ab1a0b aborted the interpreter (SIGABRT, terminate … error_already_set) in each case; run in a child
    # so that an abort shows as a return code, not as a dead test session.
    script = tmp_path / "callbacks.py"
    script.write_text("""
import json, time, idbench
limits = [{"qd_max": 1.5, "qdd_max": 4}] * 3 + [{"qd_max": 3, "qdd_max": 8}] * 3
open("limits.json", "w").write(json.dumps({"joints": limits}))
puma = idbench.Robot("puma560")
kw = dict(harmonics=2, f0=0.5, samples=40, starts=2, max_evaluations=400, clearance=-1, limits="limits.json")
class Boom(Exception):
    pass
calls = []
def raises(start, evaluations, best, feasible):
    calls.append(evaluations)
    raise Boom("from progress")
def interrupts(start, evaluations, best, feasible):
    raise KeyboardInterrupt
for name, progress in [("not callable", 42), ("wrong arity", lambda start: None), ("raises", raises),
                       ("interrupts", interrupts)]:
    began = time.perf_counter()
    try:
        idbench.design(puma, progress=progress, **kw)
        print(name, "returned")
    except BaseException as e:
        print(name, type(e).__name__, str(e).splitlines()[0] if str(e) else "", round(time.perf_counter() - began, 3))
print("calls", len(calls))
""")
    child = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert child.returncode == 0, child.stderr
    lines = {line.split(" ", 1)[0] if not line.startswith(("not ", "wrong ")) else " ".join(line.split(" ", 2)[:2]):
             line for line in child.stdout.splitlines()}
    assert lines["not callable"].startswith("not callable TypeError progress: expected a callable")
    assert "int" in lines["not callable"]
    assert lines["wrong arity"].startswith("wrong arity TypeError progress: expected a callable taking")
    # TypeError before any work: no design ran (well under the time of one).
    for name in ("not callable", "wrong arity"):
        assert float(lines[name].rsplit(" ", 1)[1]) < 0.5
    assert lines["raises"].startswith("raises Boom from progress")
    assert lines["interrupts"].startswith("interrupts KeyboardInterrupt")
    # The first exception stopped the design: progress was not called again after it raised.
    assert lines["calls"] == "calls 1"


def test_render_gives_the_figure_as_an_array_and_png(tmp_path):
    robot = idbench.Robot("paper6r")
    png = tmp_path / "figure.png"
    image = idbench.render(robot, "paper", times=[0.0, 1.0], size="64x48", layout="strip", png=str(png))
    assert image.shape == (48, 128, 3) and image.dtype == np.uint8
    assert image.std() > 1.0  # the robot is drawn, not a blank panel
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_ctrl_c_stops_a_design_and_keeps_the_best(tmp_path):
    # A design far longer than the test, interrupted by SIGINT once a start has a feasible point.
    script = tmp_path / "design.py"
    script.write_text("""
import json, sys, idbench
limits = [{"qd_max": 1.5, "qdd_max": 4}] * 3 + [{"qd_max": 3, "qdd_max": 8}] * 3
open("limits.json", "w").write(json.dumps({"joints": limits}))
def progress(start, evaluations, best, feasible):
    if feasible:
        print("feasible", flush=True)
r = idbench.design(idbench.Robot("puma560"), harmonics=3, f0=0.5, samples=40, starts=1, threads=1,
                   max_evaluations=1000000, clearance=-1, limits="limits.json", progress=progress)
print("result", r.stopped, r.feasible, r.value <= r.initial_value, flush=True)
""")
    env = dict(os.environ)
    child = subprocess.Popen([sys.executable, str(script)], cwd=tmp_path, stdout=subprocess.PIPE, text=True, env=env)
    assert child.stdout.readline().strip() == "feasible"
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=60)
    assert child.returncode == 0
    assert out.strip().splitlines()[-1] == "result True True True"


def test_a_cell_without_room_is_a_runtime_error_as_the_command_lines_exit_1(tmp_path):
    # A pillar around the UR10e-like arm's base (mounting_cli_test): the design ran into the cell, which is
    # where the robot stands, not a wrong option: exit 1 on the command line, RuntimeError here, the same
    # explanation per obstacle, its options spelled as keywords.
    ur = os.path.join(SOURCE_DIR, "tests/data/ur10e_like/")
    (tmp_path / "scene.json").write_text(json.dumps({"obstacles": [
        {"type": "cylinder", "name": "pillar", "radius": 0.4, "length": 2, "pose": [0, 0, 1, 0, 0, 0]}]}))
    quick = ["--harmonics", "3", "--f0", "0.2", "--samples", "60", "--starts", "1"]
    code, _, err = cli("design", "--robot", ur + "ur10e_like.urdf", "--limits", ur + "lim_acc.json", *quick,
                       "--scene", "scene.json", "--quiet", "--out", "d", cwd=tmp_path)
    assert code == 1, err
    robot = idbench.Robot(ur + "ur10e_like.urdf")
    with pytest.raises(RuntimeError) as raised:
        idbench.design(robot, limits=ur + "lim_acc.json", harmonics=3, f0=0.2, samples=60, starts=1,
                       scene=str(tmp_path / "scene.json"))
    assert "the scene's obstacle 'pillar' (obstacles[0], a cylinder of radius 0.4 m" in str(raised.value)
    assert "or a base_pose further from it" in str(raised.value)
    assert "--base-pose" in err and "--base-pose" not in str(raised.value)


def test_an_impossible_design_is_a_value_error_with_the_command_lines_explanation(tmp_path):
    # The UR10e-like arm with a shoulder range that holds the upper arm in the floor (home_pose_test):
    # the settings admit no motion, seen before the search (exit 2 on the command line).
    urdf = os.path.join(SOURCE_DIR, "tests/data/ur10e_like/ur10e_like.urdf")
    robot = idbench.Robot(urdf)
    limits = [{"qdd_max": 3.0}] * robot.n_dof
    limits[1] = {"q_min": 0.3, "q_max": 0.5, "qdd_max": 3.0}
    (tmp_path / "limits.json").write_text(json.dumps({"joints": limits}))
    code, _, err = cli("design", "--robot", urdf, "--limits", "limits.json", "--quiet", "--out", "d", cwd=tmp_path)
    assert code == 2, err
    with pytest.raises(ValueError) as raised:
        idbench.design(robot, limits=str(tmp_path / "limits.json"))
    # The command line's explanation, its options spelled as keywords, not flags.
    cli_message = err.strip().split("idbench: error: ", 1)[1]
    assert "--clearance (now 0.01 m), a --home pose or a --base-pose with" in cli_message
    as_keywords = cli_message.replace("--clearance", "`clearance`").replace("--home", "`home`")
    assert str(raised.value) == as_keywords.replace("--base-pose", "base_pose")
    assert "ground" in str(raised.value)


def test_a_design_that_leaves_parameters_unexcited_is_a_runtime_error_as_the_command_lines_exit_1(tmp_path):
    # Joint 6 held still by its limits: every limit is met, but its viscous friction and rotor inertia are
    # never excited. Exit 1 on the command line with nothing written, RuntimeError here, the same message.
    limits = [{"q_min": -2.5, "q_max": 2.5, "qd_max": 1.5, "qdd_max": 4.0}] * 5
    limits.append({"q_min": -2.5, "q_max": 2.5, "qd_max": 1e-12, "qdd_max": 1e-12})
    (tmp_path / "limits.json").write_text(json.dumps({"joints": limits}))
    code, out, err = cli("design", "--limits", "limits.json", "--starts", "1", "--max-evaluations", "5", "--quiet",
                         "--out", "d", cwd=tmp_path)
    assert code == 1, err
    assert out == "" and not (tmp_path / "d").exists()
    with pytest.raises(RuntimeError) as raised:
        idbench.design(idbench.Robot("puma560"), limits=str(tmp_path / "limits.json"), starts=1, max_evaluations=5)
    cli_message = err.split("idbench: error: ", 1)[1].rstrip("\n")
    assert str(raised.value) == cli_message
    assert cli_message.startswith("no design within these limits excites every parameter (rank 50 of 52)")
    assert "\n  column of Fv6 is zero: the data do not excite it" in cli_message


def test_tls_and_irls_estimators_recover_a_noise_free_log(puma):
    # identify(estimator="tls" | "irls"), as `identify --estimator`: the robot
    # file's base parameters to rounding, with the passes and verdict in the JSON.
    log = idbench.simulate(puma, "general", duration=4.0, rate=100.0)
    for estimator in ("tls", "irls"):
        result = idbench.identify(puma, log, estimator=estimator)
        solve = json.loads(result.json)["solve"]
        assert solve["converged"], solve
        error = np.linalg.norm(result.beta - result.beta_model) / np.linalg.norm(result.beta_model)
        assert error < 1e-9, (estimator, error)


def test_identify_takes_several_logs_as_the_command_line_does(puma, tmp_path):
    # identify(data=[a, b]) stacks the logs' equations as `identify --data a
    # --data b`: the same base parameters and per-log parts, to the digit.
    for name, seed, duration in (("a.csv", "3", "3"), ("b.csv", "4", "2")):
        code, _, err = cli("simulate", "--robot", "puma560", "--duration", duration, "--rate", "200",
                           "--tau-noise", "0.05", "--seed", seed, "--out", name, cwd=tmp_path)
        assert code == 0, err
    code, _, err = cli("identify", "--robot", "puma560", "--data", "a.csv", "--data", "b.csv", "--out", "id",
                       cwd=tmp_path)
    assert code == 0, err
    expected = json.loads((tmp_path / "id" / "identified.json").read_text())
    result = idbench.identify(puma, [str(tmp_path / "a.csv"), str(tmp_path / "b.csv")])
    got = json.loads(result.json)
    beta = {p["name"]: p["value"] for p in expected["base_parameters"] if p["value"] is not None}
    assert beta, expected["base_parameters"][:2]
    for k, name in enumerate(result.base_names):
        if name in beta:
            assert result.beta[k] == pytest.approx(beta[name], rel=1e-12, abs=1e-12), name
    assert [(p["n_samples"], p["cond"]) for p in got["data_logs"]] == \
        [(p["n_samples"], p["cond"]) for p in expected["data_logs"]]
    assert len(got["data_logs"]) == 2
    # One log alone is another fit.
    alone = idbench.identify(puma, str(tmp_path / "a.csv"))
    assert np.max(np.abs(alone.beta - result.beta)) > 1e-6
    with pytest.raises(ValueError, match="data: expected a log, or a list of logs, got an empty list"):
        idbench.identify(puma, [])


def test_closed_loop_estimators_take_the_controller_and_reference(puma, tmp_path):
    # identify(estimator="iv" | "didim", controller=, reference=) as `identify
    # --estimator iv --controller --reference`: a noise-free closed-loop log
    # gives the robot file's base parameters; without the controller, the
    # command line's message (in the library's terms).
    (tmp_path / "pid.json").write_text('{"kp": [2000, 2000, 1000, 200, 200, 200], "kd": [40, 40, 20, 4, 4, 4], '
                                       '"ki": 50, "feedforward": "model"}')
    code, _, err = cli("simulate", "--robot", "puma560", "--duration", "4", "--controller", "pid.json",
                       "--out", "closed.csv", cwd=tmp_path)
    assert code == 0, err
    for estimator in ("iv", "didim"):
        result = idbench.identify(puma, str(tmp_path / "closed.csv"), estimator=estimator,
                                  controller=str(tmp_path / "pid.json"), reference="general")
        document = json.loads(result.json)
        assert document["estimator"] == estimator and document["closed_loop"]["converged"]
        error = np.linalg.norm(result.beta - result.beta_model) / np.linalg.norm(result.beta_model)
        assert error < 1e-9, (estimator, error)
    with pytest.raises(ValueError, match="controller: the estimator didim re-simulates the closed loop"):
        idbench.identify(puma, str(tmp_path / "closed.csv"), estimator="didim", reference="general")
