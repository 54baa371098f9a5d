"""idbench.payload against a payload of known mass, centre of mass and inertia,
pasted into the robot file as payload.urdf.xml would be. Run by ctest with
PYTHONPATH at the module, IDBENCH_SOURCE_DIR the source tree."""
import os

import numpy as np
import pytest

import idbench

SOURCE_DIR = os.environ["IDBENCH_SOURCE_DIR"]


def test_payload_from_simulated_arrays(tmp_path):
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
    loaded = idbench.Robot(str(tmp_path / "loaded.urdf"))
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
