"""The closed-form functions' docstring examples (their ``Examples`` sections) are exact: each
prints a rounded value of a formula (the sphere's half displaced mass, rho pi a^2, EOS-80's
1025.97 kg/m^3 at 15 degC and S = 35) and doctest checks it.

Outputs are rounded (``round``, ``np.allclose``) so that they hold on any CPU and numpy
version; a module joins :data:`MODULES` when it gains examples."""

import doctest
import importlib

import pytest

#: the modules whose docstrings carry examples
MODULES = (
    "stripcoef.fluid",
    "stripcoef.sections.added_mass",
    "stripcoef.sections.drag",
    "stripcoef.hull.lamb",
)


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE, verbose=False,
                             report=True)
    assert result.attempted > 0, f"{name} has no examples"
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples fail"
