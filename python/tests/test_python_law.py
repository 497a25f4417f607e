"""A contact law written in NumPy (plab.laws), registered from Python and used
in a scene like a plug-in's model."""
import copy

import numpy as np
import pytest

import plab
from conftest import pile


@pytest.fixture(scope="module")
def py_linear():
    if "py_linear" not in plab._plab.law_names():
        plab.register_model("py_linear", plab.laws.linear, plab.laws.LINEAR_PROPERTIES, plab.laws.LINEAR_HISTORY,
                            range="rgap")
    return "py_linear"


def with_model(scene, model):
    scene = copy.deepcopy(scene)
    scene["contact_models"][0]["model"] = model
    if model != "linear":
        scene["plugins"] = []
    return scene


def test_the_numpy_linear_law_gives_the_c_plus_plus_law_s_bits_in_a_settling_pile(py_linear):
    scene = pile(count=60)
    scene["contact_models"][0]["properties"].update({"dp_sratio": 0.1, "fric": 0.3})
    cxx, py = plab.load(with_model(scene, "linear")), plab.load(with_model(scene, py_linear))
    cxx.cycle(3000)
    py.cycle(3000)
    c, p = cxx.contacts(), py.contacts()
    assert len(c["overlap"]) > 60  # a pile: friction and shear springs at work
    assert py.state_hash() == cxx.state_hash()
    assert np.array_equal(c["force"], p["force"])
    e_c, e_p = cxx.summary()["energies"], py.summary()["energies"]
    assert e_c["slip"] > 0 and e_p["slip"] == e_c["slip"] and e_p["dashpot"] == e_c["dashpot"]


def test_a_python_law_that_raises_is_refused_at_load_naming_the_model(capfd):
    def broken(batch):
        raise ValueError("a student's typo")
    if "py_broken" not in plab._plab.law_names():
        plab.register_model("py_broken", broken, plab.laws.LINEAR_PROPERTIES, plab.laws.LINEAR_HISTORY)
    # the host tries every model on a nominal touching contact before the first step
    with pytest.raises(plab.InputError) as e:
        plab.load(with_model(pile(count=20), "py_broken"))
    assert "py_broken" in str(e.value)
    assert "a student's typo" in capfd.readouterr().err


def test_a_python_law_that_raises_during_the_run_stops_it_with_run_error():
    def late(batch):
        if batch["dt"] > 0 and (batch["gap"] < -1e-4).any():  # not on the nominal contact
            raise FloatingPointError("overlap too deep for this law")
        plab.laws.linear(batch)
    if "py_late" not in plab._plab.law_names():
        plab.register_model("py_late", late, plab.laws.LINEAR_PROPERTIES, plab.laws.LINEAR_HISTORY)
    sim = plab.load(with_model(pile(count=60), "py_late"))
    with pytest.raises(plab.RunError) as e:
        sim.cycle(3000)
    assert "py_late" in str(e.value)


def test_a_law_with_a_default_outside_its_range_is_refused_naming_the_property():
    props = [("kn", "normal stiffness", "N/m", -1.0, 0.0, np.inf, "normal spring")]
    with pytest.raises(plab.InputError) as e:
        plab.register_model("py_bad", plab.laws.linear, props)
    assert "kn" in str(e.value)
    assert "py_bad" not in plab._plab.law_names()


def test_a_run_with_a_python_law_restarts_from_its_checkpoint_to_the_same_bits(tmp_path, py_linear):
    scene = with_model(pile(count=60), py_linear)
    whole = plab.load(scene)
    whole.cycle(300)
    half = plab.load(scene)
    half.cycle(150)
    half.checkpoint(tmp_path / "half.plab")
    again = plab.restart(tmp_path / "half.plab")
    again.cycle(150)
    assert again.state_hash() == whole.state_hash()
