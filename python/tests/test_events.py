"""Callbacks at events: a bond that breaks, a run that goes unstable."""
import os

import numpy as np
import pytest

import plab

SOURCE = os.environ.get("PLAB_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def pulled_pair(speed):
    """Two discs bonded (linear_pbond, 1 MPa tensile strength), the right one
    pulled away at `speed`: the bond stretches until it breaks in tension."""
    return {
        "dimension": 2, "plugins": ["linear_pbond"],
        "bodies": [{"type": "ball", "group": "a", "position": [0, 0], "radius": 0.001, "density": 2500, "fix": ["all"]},
                   {"type": "ball", "group": "b", "position": [0.002, 0], "radius": 0.001, "density": 2500,
                    "velocity": [speed, 0], "fix": ["all"]}],
        "contact_models": [{"groups": ["a", "b"], "model": "linear_pbond",
                            "properties": {"kn": 1e6, "pb_kn": 1e12, "pb_ks": 1e12, "pb_ten": 1e6, "pb_coh": 1e6}}],
        "timestep": {"fixed": 1e-6},
        "commands": [{"bond": {"groups": ["a", "b"]}}],
    }


def test_a_bond_break_calls_the_handler_once_after_the_cycle_in_which_it_broke():
    sim = plab.load(pulled_pair(0.01))
    sim.run()  # the bond command
    seen = []
    ran = sim.cycle(5000, on_bond_break=lambda s, breaks: seen.append((s.step, breaks)))
    assert ran == 5000
    assert len(seen) == 1
    step, breaks = seen[0]
    assert len(breaks) == 1 and breaks[0]["mode"] == "tension" and breaks[0]["step"] == step
    # sigma = pb_kn * stretch reaches pb_ten at a stretch of 1e-6 m: after 1e-6 / (0.01 m/s * 1e-6 s) = 100 steps
    assert abs(step - 100) <= 2


def test_a_bond_break_handler_that_returns_false_stops_the_run_there():
    sim = plab.load(pulled_pair(0.01))
    sim.run()
    ran = sim.cycle(5000, on_bond_break=lambda s, breaks: False)
    assert ran == sim.step and abs(ran - 100) <= 2


def test_an_unstable_run_calls_the_handler_at_its_last_good_state_then_raises():
    sim = plab.load(os.path.join(SOURCE, "examples", "unstable", "linear_timestep.json"))
    seen = []
    with pytest.raises(plab.RunError) as raised:
        sim.cycle(200000, every=1000,
                  on_instability=lambda s, e: seen.append((s.step, np.isfinite(s.velocities).all(), str(e))))
    assert len(seen) == 1
    step, finite, message = seen[0]
    assert message == str(raised.value)
    assert finite and step == sim.step  # the handler saw the state the run stopped in: the last good one
    assert step < 200000  # (the run stopped early)
