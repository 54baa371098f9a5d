"""ROS 2 bags in Python's identify (issue 24): a bag identifies as the CSV of
the same samples (tests/data/bags/expected.csv), topic= picks the topic.

Run from CTest with the rest of this directory (PYTHONPATH holds the module).
"""
import os
import pathlib

import numpy as np
import pytest

import idbench

BAGS = pathlib.Path(os.environ.get("IDBENCH_SOURCE_DIR", pathlib.Path(__file__).parents[3])) / "tests" / "data" / "bags"


@pytest.fixture(scope="module")
def puma():
    return idbench.Robot("puma560")


def test_a_bag_identifies_as_its_csv(puma, tmp_path):
    # A bag's time starts at 0 at its first message (integer nanoseconds from it); expected.csv's at 1 s: the
    # same samples on the bag's time axis, t = k / 100 Hz as the bag's nanoseconds give it.
    lines = (BAGS / "expected.csv").read_text().splitlines()
    from_zero = tmp_path / "expected_from_0.csv"
    from_zero.write_text("\n".join([lines[0]] + [f"{k / 100.0!r}{line[line.index(','):]}"
                                                   for k, line in enumerate(lines[1:])]) + "\n")
    reference = idbench.identify(puma, str(from_zero), estimator="ols")
    for bag in ("bag_db3", "joint_states_zstd.mcap"):
        result = idbench.identify(puma, str(BAGS / bag), estimator="ols", topic="/joint_states")
        np.testing.assert_array_equal(result.standard, reference.standard)
        assert result.fit_relative_error == reference.fit_relative_error
        assert any("gripper_finger_joint" in note for note in result.notes)


def test_topic_of_another_type_is_refused(puma):
    with pytest.raises(ValueError, match="topic: '/other' has type std_msgs/msg/String"):
        idbench.identify(puma, str(BAGS / "bag_db3"), topic="/other")
