"""The contact-law contract (plab.contract, the rules of
tests/contact_models/contract_test.cpp) on the laws written in Python, and
on broken laws, each of which it must catch."""
import numpy as np
import pytest

import plab

LINEAR_VALUES = {"kn": 1e5, "ks": 5e4, "fric": 0.5, "dp_nratio": 0.2, "dp_sratio": 0.1, "rgap": 1e-5}


def check(law):
    return plab.contract.check(law, plab.laws.LINEAR_PROPERTIES, plab.laws.LINEAR_HISTORY, range="rgap",
                               values=LINEAR_VALUES)


def test_the_numpy_linear_law_keeps_the_contract():
    assert check(plab.laws.linear) == []


def no_tension(batch):
    """examples/python/python_law.py's change: the normal dashpot never pulls."""
    plab.laws.linear(batch)
    n, f = batch["normal"], batch["force"]
    fn = np.einsum("ij,ij->i", f, n)
    f[fn < 0.0] -= fn[fn < 0.0, None] * n[fn < 0.0]


def test_the_teaching_example_s_changed_law_keeps_it_too():
    assert check(no_tension) == []


def pushes_along_x(batch):  # not objective: the force ignores the normal's direction
    plab.laws.linear(batch)
    batch["force"][:] = np.abs(batch["force"]).sum(axis=1)[:, None] * np.array([1.0, 0.0, 0.0])


def reaches_out(batch):  # a force beyond the activity range
    plab.laws.linear(batch)
    batch["force"][:, 0] += 1e-3


def batch_mean(batch):  # each row depends on the others: a batch of one differs
    plab.laws.linear(batch)
    batch["force"][:] = batch["force"] + batch["force"].mean(axis=0)


def divides_by_mass(batch):  # NaN/inf at extreme masses
    plab.laws.linear(batch)
    with np.errstate(divide="ignore", invalid="ignore"):
        batch["force"][:] /= (batch["eff_mass"] - 1e-12)[:, None]


def no_stiffness(batch):
    plab.laws.linear(batch)
    batch["stiffness"][:] = 0.0


@pytest.mark.parametrize("law, rule", [(pushes_along_x, "objectivity"), (reaches_out, "outside the range"),
                                       (batch_mean, "batch size"), (divides_by_mass, "extreme inputs"),
                                       (no_stiffness, "stable step"), (pushes_along_x, "ends swapped")])
def test_a_law_that_breaks_a_rule_is_caught_by_it(law, rule):
    failures = check(law)
    assert any(f.startswith(rule) for f in failures), failures


def test_a_description_without_units_or_with_a_default_out_of_range_is_refused():
    props = [list(p) for p in plab.laws.LINEAR_PROPERTIES]
    props[0][2] = ""            # kn without a unit
    props[3][3] = 2.0           # dp_nratio default 2 in [0, 1]
    failures = plab.contract.check(plab.laws.linear, [tuple(p) for p in props], plab.laws.LINEAR_HISTORY,
                                   range="rgap", values=LINEAR_VALUES)
    assert any("kn has no unit" in f for f in failures)
    assert any("dp_nratio's default" in f for f in failures)
