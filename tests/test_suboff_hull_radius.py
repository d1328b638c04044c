"""validation.lift.hull_radius of an array is its value at each number (the Groves et al. 1989
equations element-wise), ends and joins included."""

import numpy as np

from validation.lift import hull_radius, val


def test_array_is_the_numbers_element_wise():
    length = val("hull.L")
    x = np.concatenate([np.linspace(-0.5, length + 0.5, 2001),
                        [0.0, 3.333333, 10.645833, 13.979167, length]])
    one = np.array([hull_radius(float(t)) for t in x])
    many = hull_radius(x)
    assert many.shape == x.shape
    np.testing.assert_allclose(many, one, rtol=4e-15, atol=0.0)
    np.testing.assert_allclose(hull_radius(x.reshape(-1, 2)), one.reshape(-1, 2), rtol=4e-15,
                               atol=0.0)
    assert hull_radius(np.array([])).shape == (0,)
