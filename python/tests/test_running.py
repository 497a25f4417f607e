"""Running from Python: callbacks, solve, checkpoint and restart, and the
physics of a free fall."""
import json
import os
import subprocess

import numpy as np
import pytest

import plab


def test_a_callback_runs_every_k_cycles_with_the_simulation(scenes):
    sim = plab.load(scenes.free_ball())
    seen = []
    done = sim.cycle(100, every=30, callback=lambda s: seen.append((s.step, float(s.positions[0, 2]))))
    assert done == 100
    assert [step for step, _ in seen] == [30, 60, 90, 100]
    heights = [z for _, z in seen]
    assert all(a > b for a, b in zip(heights, heights[1:]))  # falling


def test_a_callback_that_returns_false_stops_the_run(scenes):
    sim = plab.load(scenes.free_ball())
    done = sim.cycle(1000, every=10, callback=lambda s: s.positions[0, 2] > 0.9999)
    assert done < 1000 and sim.step == done
    assert sim.positions[0, 2] <= 0.9999


def test_a_free_ball_falls_g_t_squared_over_two(scenes):
    dt, g = 1e-4, 9.81
    sim = plab.load(scenes.free_ball(dim=3, dt=dt, g=-g))
    sim.solve(time=0.25)
    t = sim.time
    assert sim.step == 2500 and t == pytest.approx(0.25)
    # the leapfrog is exact for a constant force: round-off only
    assert sim.positions[0, 2] == pytest.approx(1 - g * t * t / 2, abs=1e-12)
    assert sim.velocities[0, 2] == pytest.approx(-g * t, abs=1e-12)
    assert sim.forces[0, 2] == pytest.approx(-g * sim.masses[0], rel=1e-12)


def test_checkpoint_and_restart_from_python_give_the_uninterrupted_bits(tmp_path, scenes):
    whole = plab.load(scenes.pile())
    whole.cycle(300)
    half = plab.load(scenes.pile())
    half.cycle(120)
    path = tmp_path / "half.plab"
    half.checkpoint(path)
    assert half.state_hash() != whole.state_hash()
    again = plab.restart(path)
    assert again.step == 120 and again.state_hash() == half.state_hash()
    again.cycle(180)
    assert again.state_hash() == whole.state_hash()
    # the history rows of the first part came back with the checkpoint
    assert np.array_equal(again.history(as_dict=True)["ke"], whole.history(as_dict=True)["ke"])


def test_a_damaged_checkpoint_raises_checkpoint_error(tmp_path, scenes):
    sim = plab.load(scenes.pile())
    path = tmp_path / "c.plab"
    sim.checkpoint(path)
    data = bytearray(path.read_bytes())
    data[len(data) // 2] ^= 0xFF
    path.write_bytes(bytes(data))
    with pytest.raises(plab.CheckpointError):
        plab.restart(path)


def test_run_from_python_ends_in_the_cli_s_state(tmp_path, scenes):
    exe = os.environ.get("PLAB_EXE")
    if not exe:
        pytest.fail("PLAB_EXE is not set: the CTest entry python_pytest sets it")
    scene = scenes.pile()
    path = tmp_path / "pile.json"
    path.write_text(json.dumps(scene))
    out = tmp_path / "out"
    subprocess.run([exe, "run", str(path), "--quiet", "--out", str(out)], check=True)
    cli = json.loads((out / "summary.json").read_text())
    sim = plab.load(path)
    sim.run()
    assert sim.summary()["state_hash"] == cli["state_hash"]
    # and cycled in pieces, with views read between them
    pieces = plab.load(path)
    pieces.cycle(400, every=37, callback=lambda s: np.asarray(s.positions).sum())
    assert pieces.summary()["state_hash"] == cli["state_hash"]


def test_an_unstable_run_raises_run_error_naming_the_quantity(scenes):
    scene = scenes.pile()
    scene["timestep"] = {"fixed": 5e-3, "allow_unstable": True}  # far above the stable step
    sim = plab.load(scene)
    with pytest.raises(plab.RunError) as e:
        sim.cycle(2000)
    assert e.value.quantity != ""


def test_the_restitution_example_gives_the_closed_form_of_the_linear_dashpot():
    import importlib.util
    source = os.environ.get("PLAB_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
    spec = importlib.util.spec_from_file_location(
        "restitution_study", os.path.join(source, "examples", "python", "restitution_study.py"))
    study = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(study)
    for beta in (0.1, 0.3):
        assert study.restitution(beta) == pytest.approx(study.closed_form(beta), rel=0.01)
