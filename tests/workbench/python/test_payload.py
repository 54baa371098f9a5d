"""idbench.payload against a payload of known mass, centre of mass and inertia,
pasted into the robot file as payload.urdf.xml would be. Run by ctest with
PYTHONPATH at the module, IDBENCH_SOURCE_DIR the source tree."""
import os

import numpy as np
import pytest

import idbench

SOURCE_DIR = os.environ["IDBENCH_SOURCE_DIR"]


def robots_with_and_without_tool(tmp_path):
    """paper6r and paper6r with a 2.5 kg tool on its last link, as payload.urdf.xml would paste it."""
    path = os.path.join(SOURCE_DIR, "engine/robots/paper6r.urdf")
    robot = idbench.Robot(path)
    link = robot.link_names[-1]
    fragment = (f'<joint name="tool_joint" type="fixed"><parent link="{link}"/><child link="tool"/>'
                '<origin xyz="0 0 0" rpy="0 0 0"/></joint><link name="tool"><inertial>'
                '<origin xyz="0.02 -0.03 0.08" rpy="0 0 0"/><mass value="2.5"/>'
                '<inertia ixx="0.02" ixy="0.001" ixz="-0.0005" iyy="0.025" iyz="0.0015" izz="0.015"/>'
                '</inertial></link>')
    text = open(path).read()
    end = text.rfind("</robot>")
    (tmp_path / "loaded.urdf").write_text(text[:end] + fragment + text[end:])
    return robot, idbench.Robot(str(tmp_path / "loaded.urdf")), link


def test_payload_from_simulated_arrays(tmp_path):
    robot, loaded, link = robots_with_and_without_tool(tmp_path)
    # The same motion with and without the payload (the simulator's exact qd, qdd).
    with_payload = idbench.simulate(loaded, "general", duration=5.0, rate=200.0)
    without = idbench.simulate(robot, "general", duration=5.0, rate=200.0)

    result = idbench.payload(robot, with_payload, unloaded=without)
    assert result["verdict"]["status"] == "estimated", result["tables"]
    assert result["link"] == link
    assert result["mass"] == pytest.approx(2.5, rel=1e-5)
    np.testing.assert_allclose(result["com"], [0.02, -0.03, 0.08], atol=1e-6)
    np.testing.assert_allclose(result["inertia"], [0.02, 0.001, -0.0005, 0.025, 0.0015, 0.015], atol=1e-6)
    assert f'<child link="{link}_payload"/>' in result["urdf"]

    # An unknown link is wrong input (ValueError), named by its field.
    with pytest.raises(ValueError, match="payload_link: .* no link 'tool0'"):
        idbench.payload(robot, with_payload, link="tool0")


def test_payload_reads_currents_on_a_tilted_base_as_identify_does(tmp_path):
    """Item 33 of issue 35: payload() takes identify's log options (drive_gains, base_pose).
    Truth: the 2.5 kg tool pasted into the URDF, simulated on a base rolled by 0.4 rad;
    the logs carry motor currents i = tau / k instead of tau."""
    robot, loaded, link = robots_with_and_without_tool(tmp_path)
    pose = (0.1, -0.2, 0.3, 0.4, 0.0, 0.2)
    gains = np.array([2.0, 3.0, 1.5, 0.5, 0.25, 0.2])

    def as_currents(log):
        return {"t": log["t"], "q": log["q"], "qd": log["qd"], "qdd": log["qdd"], "i": log["tau"] / gains}

    with_payload = as_currents(idbench.simulate(loaded, "general", duration=5.0, rate=200.0, base_pose=pose))
    without = as_currents(idbench.simulate(robot, "general", duration=5.0, rate=200.0, base_pose=pose))

    result = idbench.payload(robot, with_payload, unloaded=without, drive_gains=list(gains), base_pose=pose)
    assert result["verdict"]["status"] == "estimated", result["tables"]
    assert result["mass"] == pytest.approx(2.5, rel=1e-5)
    np.testing.assert_allclose(result["com"], [0.02, -0.03, 0.08], atol=1e-6)
    # Read as if the base stood upright, the same logs give another mass: the pose is used.
    upright = idbench.payload(robot, with_payload, unloaded=without, drive_gains=list(gains))
    assert abs(upright["mass"] - 2.5) > 0.01
    # Currents without gains are wrong input, named by their field.
    with pytest.raises(ValueError, match="drive_gains"):
        idbench.payload(robot, with_payload, unloaded=without, base_pose=pose)
