"""Similitude (Eng et al. 2009, eqs. 8-10): ROV II Table II scaled by lambda = 1/0.3 vs Tables III/IV."""

import pytest

from stripcoef.errors import InputError
from stripcoef.identify.scaling import scale_result, scale_value
from validation.reference import agrees, reference_value

LAMBDA = 1.0 / reference_value("rov2", "scale.length_ratio_model")["value"]


def _table_ii(row):
    names = {"m_a": f"surge.{row}.m_a", "K_L": f"surge.{row}.K_L", "K_Q": f"surge.{row}.K_Q"}
    return {"method": "pendulum", "dof": "surge",
            "parameters": {k: reference_value("rov2", v)["value"] for k, v in names.items()},
            "std": {k: None for k in names}}


def _scaled(row="average"):
    return scale_result(_table_ii(row), LAMBDA)["parameters"]


def test_surge_linear_drag_reproduces_table_iv():
    """1.5515 x (1/0.3)^2 = 17.24 (Table IV, experiment)."""
    assert agrees(reference_value("rov2", "surge.K_L.experiment"), _scaled()["K_L"])


@pytest.mark.xfail(strict=True, reason="Table II average m_a = 0.5800 kg x (1/0.3)^3 = 21.48 kg; "
                   "Table III prints 21.42 (= 0.58 x 3.33^3: the ratio was rounded to 3.33)")
def test_surge_added_mass_reproduces_table_iii():
    assert agrees(reference_value("rov2", "surge.experiment"), _scaled()["m_a"])


@pytest.mark.xfail(strict=True, reason="Table II average K_Q = 9.5439 x (1/0.3)^2 = 106.04; "
                   "Table IV prints 106.03 (= 9.5439 x 11.11, a rounded factor)")
def test_surge_quadratic_drag_reproduces_table_iv():
    assert agrees(reference_value("rov2", "surge.K_Q.experiment"), _scaled()["K_Q"])


def test_rounded_ratio_explains_the_mismatches():
    assert agrees(reference_value("rov2", "surge.experiment"),
                  scale_result(_table_ii("average"), 3.33)["parameters"]["m_a"])
    assert agrees(reference_value("rov2", "surge.K_Q.experiment"),
                  _table_ii("average")["parameters"]["K_Q"] * 11.11)


def test_each_test_scales_and_average_commutes():
    """Scaling is linear: the mean of the scaled tests equals the scaled average."""
    tests = [_scaled(f"test{i}") for i in (1, 2, 3)]
    for k in ("m_a", "K_L", "K_Q"):
        mean = sum(t[k] for t in tests) / 3
        assert mean == pytest.approx(_scaled()[k], rel=2e-4)   # Table II average is rounded


def test_exponents_and_std():
    r = {"method": "torsion", "dof": "yaw", "parameters": {"I_a": 1.0, "K_Q": 2.0, "a": -3.0},
         "std": {"I_a": 0.1, "K_Q": 0.2, "a": 0.3}}
    out = scale_result(r, 2.0)
    assert out["rotational"] and out["parameters"] == {"I_a": 32.0, "K_Q": 64.0}
    assert out["std"]["I_a"] == pytest.approx(3.2) and "Reynolds" in out["caveat"]
    assert scale_value(1.0, "m_a", 2.0) == 8.0 and scale_value(1.0, "K_L", 2.0) == 4.0
    assert scale_value(1.0, "m_a", 2.0, rotational=True) == 32.0


def test_bad_input():
    with pytest.raises(InputError, match="ratio"):
        scale_value(1.0, "m_a", -1.0)
    with pytest.raises(InputError, match="alpha"):
        scale_value(1.0, "alpha", 2.0)
    with pytest.raises(InputError, match="parameters"):
        scale_result({"method": "x"}, 2.0)
    with pytest.raises(InputError, match="no scalable"):
        scale_result({"parameters": {"alpha": 1.0}, "std": {"alpha": 0.1}}, 2.0, rotational=False)
