"""Scenes the tests share, as dicts: small enough that the whole suite runs
in a few seconds on one core."""
import copy

import pytest


def free_ball(dim=3, dt=1e-4, g=-9.81):
    """One ball, no contacts, a fixed step: a free fall."""
    return {
        "dimension": dim,
        "gravity": [0, 0, g] if dim == 3 else [0, g],
        "bodies": [{"type": "ball", "group": "ball", "position": [0, 0, 1] if dim == 3 else [0, 1],
                    "radius": 0.01, "density": 2500}],
        "timestep": {"fixed": dt},
    }


def pile(count=150, seed=7):
    """Discs settling in a box (2D, linear model), with a history."""
    return {
        "dimension": 2,
        "gravity": [0, -9.81],
        "plugins": ["linear"],
        "bodies": [{"type": "random_fill", "group": "grains", "box": {"min": [0, 0], "max": [0.1, 0.1]},
                    "radius": [0.002, 0.004], "density": 2500, "count": count, "seed": seed}],
        "walls": [{"type": "box", "min": [0, 0], "max": [0.1, 0.2]}],
        "contact_models": [{"groups": ["*", "*"], "model": "linear",
                            "properties": {"kn": 1e5, "ks": 5e4, "fric": 0.5, "dp_nratio": 0.2}}],
        "histories": {"every": 50, "record": [{"quantity": "time"}, {"name": "ke", "quantity": "energy.kinetic"}]},
        "commands": [{"cycle": 400}],
    }


def fed_box():
    """A box fed by an inlet: the run adds balls, so the columns reallocate."""
    return {
        "dimension": 2,
        "gravity": [0, -9.81],
        "plugins": ["linear"],
        "bodies": [{"type": "ball", "group": "grains", "position": [0.05, 0.01], "radius": 0.003, "density": 2500}],
        "walls": [{"type": "box", "min": [0, 0], "max": [0.1, 0.3]}],
        "contact_models": [{"groups": ["*", "*"], "model": "linear",
                            "properties": {"kn": 1e5, "ks": 5e4, "fric": 0.5, "dp_nratio": 0.2}}],
        "inlets": [{"name": "feed", "box": {"min": [0.01, 0.2], "max": [0.09, 0.25]}, "radius": 0.002,
                    "density": 2500, "group": "grains", "rate": {"count_per_second": 4000}, "total": 200,
                    "every": 20, "seed": 3}],
        "timestep": {"fixed": 2e-5},
    }


@pytest.fixture
def scenes():
    class Scenes:
        pass
    s = Scenes()
    s.free_ball = lambda **kw: copy.deepcopy(free_ball(**kw))
    s.pile = lambda **kw: copy.deepcopy(pile(**kw))
    s.fed_box = lambda: copy.deepcopy(fed_box())
    return s
