"""Python dict logs read as a file is (issue 20): angle_unit and drive_gains
are honoured, errors name the array at fault, validate_window scores a part of
the held-out log.

Run from CTest with the rest of this directory (PYTHONPATH holds the module).
"""
import json

import numpy as np
import pytest

import idbench


@pytest.fixture(scope="module")
def puma():
    return idbench.Robot("puma560")


@pytest.fixture(scope="module")
def exact(puma):
    # The general motion for 3 s at 200 Hz with the simulator's qd, qdd: the
    # fit in radians is the reference the other readings must match.
    log = idbench.simulate(puma, "general", duration=3.0, rate=200.0)
    return log, idbench.identify(puma, log)


def test_dict_in_degrees_is_converted(puma, exact):
    # 6ab1a0b ignored angle_unit for dicts: degrees were read as radians
    # (a 60 % fit error). Now the degree log gives the radian log's fit.
    log, reference = exact
    degrees = {k: (np.degrees(v) if k in ("q", "qd", "qdd") else v) for k, v in log.items()}
    result = idbench.identify(puma, degrees, angle_unit="deg")
    assert result.fit_relative_error == pytest.approx(reference.fit_relative_error, rel=1e-6, abs=1e-9)
    np.testing.assert_allclose(result.standard, reference.standard, rtol=1e-6, atol=1e-9)


def test_dict_with_currents_and_drive_gains_is_scaled(puma, exact):
    # 6ab1a0b ignored drive_gains for dicts. Currents i = tau / K with one
    # drive logged with the opposite sign: tau = K i recovers the same fit.
    log, reference = exact
    gains = np.array([31.5, 55.0, 28.0, 7.5, -6.2, 4.1])
    currents = {k: v for k, v in log.items() if k != "tau"}
    currents["i"] = log["tau"] / gains
    result = idbench.identify(puma, currents, drive_gains=list(gains))
    assert result.fit_relative_error == pytest.approx(reference.fit_relative_error, rel=1e-6, abs=1e-9)
    np.testing.assert_allclose(result.standard, reference.standard, rtol=1e-6, atol=1e-9)
    assert any("tau = K·i" in note for note in result.notes)
    # Currents without gains, gains without currents: refused, naming what.
    with pytest.raises(ValueError, match="currents 'i' but no 'tau': give drive_gains"):
        idbench.identify(puma, currents)
    with pytest.raises(ValueError, match="drive_gains given but there is no array 'i'"):
        idbench.identify(puma, log, drive_gains=list(gains))
    with pytest.raises(ValueError, match="drive_gains: every gain is negative"):
        idbench.identify(puma, currents, drive_gains=list(-abs(gains)))


def test_dict_errors_name_the_right_array(puma, exact):
    log, _ = exact
    short_t = dict(log, t=log["t"][:-1])
    # 6ab1a0b blamed the array q for a short t.
    with pytest.raises(ValueError, match=r"q: 600 rows but t has 599 samples"):
        idbench.identify(puma, short_t)
    with pytest.raises(ValueError, match=r"unknown array 'tua'"):
        idbench.identify(puma, dict(log, tua=log["tau"]))
    with pytest.raises(ValueError, match=r"columns: applies to CSV files"):
        idbench.identify(puma, log, columns=["t", "q1..q6", "tau1..tau6"])


def test_validate_window_scores_part_of_the_held_out_log(puma, exact):
    # The held-out log is the identification log with a torque error on its
    # second half; the prediction on its rows is the identification's own
    # (result.torques), so both errors can be computed here from the rows.
    log, _ = exact
    held = {k: np.array(v, copy=True) for k, v in log.items()}
    second = held["t"] > 1.5
    held["tau"][second] += 0.5
    result = idbench.identify(puma, log, validate=held, validate_window=[0.0, 1.5])
    predicted = result.torques["predicted"]
    assert predicted.shape == held["tau"].shape
    window = ~second
    expected_window = np.linalg.norm(predicted[window] - held["tau"][window]) / np.linalg.norm(held["tau"][window])
    expected_whole = np.linalg.norm(predicted - held["tau"]) / np.linalg.norm(held["tau"])
    assert result.validation_relative_error == pytest.approx(expected_window, rel=1e-6)
    assert result.validation_whole_file_relative_error == pytest.approx(expected_whole, rel=1e-6)
    assert expected_whole > 10 * expected_window
    validation = json.loads(result.json)["validation"]
    assert validation["window"] == [0.0, 1.5]
    with pytest.raises(ValueError, match="validate_window: given without a held-out log"):
        idbench.identify(puma, log, validate_window=[0.0, 1.5])


def test_log_description_is_read_where_a_log_is(puma, exact, tmp_path):
    # A description of two files (one number per line for q, a CSV for the
    # rest, no time column: a rate) identifies as the arrays do.
    log, reference = exact
    n = len(log["t"])
    (tmp_path / "q.txt").write_text("".join(f"{v!r}\n" for v in log["q"].reshape(-1)))
    rows = np.hstack([log["qd"], log["qdd"], log["tau"]])
    (tmp_path / "rest.csv").write_text("".join(",".join(repr(v) for v in row) + "\n" for row in rows))
    description = {"rate": 200.0,
                   "files": [{"path": "q.txt", "layout": "one-value-per-line", "stride": 6, "columns": "q1..q6"},
                             {"path": "rest.csv", "columns": ["qd1..qd6", "qdd1..qdd6", "tau1..tau6"]}]}
    path = tmp_path / "log.json"
    path.write_text(json.dumps(description))
    result = idbench.identify(puma, str(path))
    assert json.loads(result.json)["n_samples"] == n
    np.testing.assert_allclose(result.standard, reference.standard, rtol=1e-9, atol=1e-12)
    description["stide"] = 6
    path.write_text(json.dumps(description))
    with pytest.raises(ValueError, match=r"log.json: .stide: unknown key"):
        idbench.identify(puma, str(path))
