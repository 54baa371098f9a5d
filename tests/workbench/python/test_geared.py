"""identify's friction_side and base_pose keyword arguments against their truth.

Run from CTest as test_idbench.py (IDBENCH the built executable, which writes
the motor-side log: the Python module's simulate gives joint-side arrays).
"""
import json
import os
import subprocess

import numpy as np
import pytest

import idbench

IDBENCH = os.environ["IDBENCH"]

# The TX40's coupled wrist (motor 6 turns with joint 5), each motor's own friction and rotor inertia.
A = [[32, 0, 0, 0, 0, 0], [0, 32, 0, 0, 0, 0], [0, 0, 45, 0, 0, 0],
     [0, 0, 0, -48, 0, 0], [0, 0, 0, 0, 45, 0], [0, 0, 0, 0, 32, 32]]
FV = [1.5e-3, 2e-3, 1e-3, 4e-4, 3e-4, 2.5e-4]
FC = [0.05, 0.08, 0.04, 0.02, 0.015, 0.012]
IA = [3e-4, 2.5e-4, 1.2e-4, 4e-5, 3.5e-5, 3e-5]


def csv(values):
    return ",".join(repr(v) for v in values)


@pytest.fixture(scope="module")
def motor_side_log(tmp_path_factory):
    folder = tmp_path_factory.mktemp("geared")
    (folder / "wrist.json").write_text(json.dumps({"actuator_from_joint": A}))
    done = subprocess.run([IDBENCH, "simulate", "--robot", "paper6r", "--transmission", "wrist.json",
                           "--duration", "10", "--motor-viscous", csv(FV), "--motor-coulomb", csv(FC),
                           "--motor-rotor-inertia", csv(IA), "--out", "log.csv"],
                          cwd=folder, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return str(folder / "log.json")


def test_friction_side_actuator_recovers_each_motors_friction(motor_side_log):
    robot = idbench.Robot("paper6r")
    result = idbench.identify(robot, motor_side_log, friction=["viscous", "coulomb", "rotor"],
                              friction_side="actuator")
    assert result.fit_relative_error < 1e-9
    beta = dict(zip(result.base_names, result.beta))
    for k in range(6):
        assert beta[f"Fvm{k + 1}"] == pytest.approx(FV[k], rel=1e-8)
        assert beta[f"Fcm{k + 1}"] == pytest.approx(FC[k], rel=1e-8)
    # The coupled wrist's joint-side values are null, never 0; joint 1's are Fv·N², Fc·|N|.
    joint_side = json.loads(result.json)["joint_side"]
    assert joint_side["Fv"][4] is None and joint_side["Fv"][5] is None
    assert joint_side["Fv"][0] == pytest.approx(FV[0] * 32 ** 2, rel=1e-6)
    assert joint_side["Fc"][0] == pytest.approx(FC[0] * 32, rel=1e-6)
    # On the joint side the coupled motor's terms cannot be modelled.
    joint = idbench.identify(robot, motor_side_log, friction=["viscous", "coulomb", "rotor"])
    assert joint.fit_relative_error > 1e3 * result.fit_relative_error


def test_friction_side_is_checked_by_its_field_name():
    with pytest.raises(ValueError, match="friction_side"):
        idbench.identify(idbench.Robot("paper6r"), {"t": np.zeros(1)}, friction_side="motor")


def test_base_pose_mounts_the_robot_as_simulate_did():
    robot = idbench.Robot("puma560")
    ceiling = (0.0, 0.0, 2.0, np.pi, 0.0, 0.0)
    log = idbench.simulate(robot, "general", duration=3.0, rate=200.0, base_pose=ceiling)
    upright = idbench.simulate(robot, "general", duration=3.0, rate=200.0)
    assert np.abs(log["tau"] - upright["tau"]).max() > 1.0  # gravity turned over
    mounted = idbench.identify(robot, log, base_pose=ceiling)
    assert mounted.fit_relative_error < 1e-8
    # Unmounted, gravity is upside down and the fit is clearly worse (the base
    # parameters absorb part of it).
    assert idbench.identify(robot, log).fit_relative_error > 1e-4
    with pytest.raises(ValueError, match="base_pose"):
        idbench.identify(robot, log, base_pose=(0.0, 0.0, 0.0))


def test_simulate_through_a_transmission_returns_the_motor_side(tmp_path):
    """The motor-side arrays against the joint-side ones: taum by virtual work
    (Aᵀ·taum = tau), qm = A·(q − q0), qdm = A·qd, with the TX40's offsets."""
    q0 = [0.0, -np.pi / 2, np.pi / 2, 0.0, 0.0, 0.0]
    (tmp_path / "wrist.json").write_text(json.dumps({"actuator_from_joint": A, "joint_offset": q0}))
    log = idbench.simulate(idbench.Robot("paper6r"), "general", duration=2.0,
                           transmission=str(tmp_path / "wrist.json"), motor_viscous=FV, motor_coulomb=FC,
                           motor_rotor_inertia=IA)
    a = np.array(A, dtype=float)
    n = log["t"].shape[0]
    assert n == 2000  # 2 s at 1 kHz
    for key in ("q", "qd", "qdd", "tau", "qm", "qdm", "taum"):
        assert log[key].shape == (n, 6), key
    np.testing.assert_allclose(log["taum"] @ a, log["tau"], rtol=1e-12, atol=1e-12 * np.abs(log["tau"]).max())
    np.testing.assert_allclose(log["qm"], (log["q"] - np.array(q0)) @ a.T, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(log["qdm"], log["qd"] @ a.T, rtol=1e-12, atol=1e-12)
    # The motors' own terms are in tau: the plain joint-side simulation differs by Aᵀ·(their torque).
    plain = idbench.simulate(idbench.Robot("paper6r"), "general", duration=2.0)
    thd, thdd = log["qd"] @ a.T, log["qdd"] @ a.T
    own = np.array(IA) * thdd + np.array(FV) * thd + np.array(FC) * np.sign(thd)
    np.testing.assert_allclose(log["tau"], plain["tau"] + own @ a, rtol=1e-9, atol=1e-9)
    with pytest.raises(ValueError, match="motor_viscous"):
        idbench.simulate(idbench.Robot("paper6r"), "general", duration=1.0, motor_viscous=[1.0])


def test_design_keeps_a_motor_limit_through_its_transmission(tmp_path):
    """design(transmission=...) keeps the limits file's "actuators"; without one they are refused by field."""
    (tmp_path / "wrist.json").write_text(json.dumps({"actuator_from_joint": A}))
    joints = [{"q_min": -3, "q_max": 3, "qd_max": 1, "qdd_max": 3}] * 6
    (tmp_path / "limits.json").write_text(json.dumps({"joints": joints, "actuators": [{}] * 5 + [{"qd_max": 20}]}))
    robot = idbench.Robot("paper6r")
    quick = dict(harmonics=2, f0=0.5, samples=40, starts=1, max_evaluations=25, clearance=-1,
                 limits=str(tmp_path / "limits.json"))
    with pytest.raises(ValueError, match="^transmission: "):
        idbench.design(robot, **quick)
    result = idbench.design(robot, transmission=str(tmp_path / "wrist.json"), **quick)
    assert result.feasible
    design = json.loads(result.design_json)
    assert design["actuators"][5]["qd_max"] == 20
    rows = np.loadtxt(result.trajectory_csv.splitlines()[1:], delimiter=",")
    qd = rows[:, 7:13]
    assert np.abs(qd @ np.array(A, dtype=float).T)[:, 5].max() <= 20
