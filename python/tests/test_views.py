"""State as NumPy arrays over the kernel's columns: no copies, writes seen by
the next cycle, and views refused once a cycle moved their storage."""
import gc

import numpy as np
import pytest

import plab


def address(a):
    return np.asarray(a).__array_interface__["data"][0]


def test_views_show_the_kernel_s_memory_without_a_copy(scenes):
    sim = plab.load(scenes.pile())
    a, b = sim.positions, sim.positions
    assert address(a) == address(b)  # the same memory, twice
    assert np.shares_memory(np.asarray(a), np.asarray(b))
    sim.cycle(10)
    assert address(sim.positions) == address(a)  # a cycle without new balls keeps the storage
    # the view follows the state: it is not a snapshot
    assert np.array_equal(np.asarray(a), np.asarray(sim.positions))
    before = np.array(a)
    sim.cycle(20)
    assert not np.array_equal(before, np.asarray(a))
    assert np.array_equal(np.asarray(a), np.asarray(sim.positions))


def test_2d_columns_are_n_by_2_and_spins_are_about_z(scenes):
    sim = plab.load(scenes.pile())
    n = len(sim)
    assert sim.positions.shape == (n, 2) and sim.velocities.shape == (n, 2) and sim.forces.shape == (n, 2)
    assert sim.spins.shape == (n,) and sim.radii.shape == (n,) and sim.masses.shape == (n,)
    r = np.asarray(sim.radii)
    assert np.allclose(sim.masses, 2500 * np.pi * r ** 2)  # discs of unit thickness
    sim3 = plab.load(scenes.free_ball(dim=3))
    assert sim3.positions.shape == (1, 3) and sim3.spins.shape == (1, 3)


def test_a_velocity_written_through_numpy_moves_the_ball_in_the_next_cycle(scenes):
    sim = plab.load(scenes.free_ball(dim=3, g=0.0, dt=1e-3))
    v = sim.velocities
    v[0] = [2.0, 0.0, -1.0]
    x0 = np.array(sim.positions[0])
    sim.cycle(10)
    assert sim.positions[0] == pytest.approx(x0 + 10 * 1e-3 * np.array([2.0, 0.0, -1.0]), abs=1e-15)
    assert sim.velocities[0] == pytest.approx([2.0, 0.0, -1.0])


def test_fixity_written_through_numpy_holds_a_ball_in_the_next_cycle(scenes):
    sim = plab.load(scenes.free_ball(dim=2))
    sim.fixity[0] = 1 | 2  # x and y
    y0 = sim.positions[0, 1]
    sim.cycle(100)
    assert sim.positions[0, 1] == y0
    sim.fixity[0] = 0
    sim.cycle(100)
    assert sim.positions[0, 1] < y0


def test_a_velocity_prescribed_through_numpy_is_held_against_gravity(scenes):
    # PFC's `ball fix velocity`: a fixed degree of freedom keeps the velocity written to it
    sim = plab.load(scenes.free_ball(dim=3, dt=1e-4))
    x0, z0 = sim.positions[0, 0], sim.positions[0, 2]
    sim.fixity[0] = 1 | 4          # x and z prescribed, y free
    sim.velocities[0] = (0.5, 0.0, -0.2)
    sim.cycle(1000)                # 0.1 s
    assert sim.velocities[0, 0] == 0.5 and sim.velocities[0, 2] == -0.2
    assert sim.positions[0, 0] - x0 == pytest.approx(0.05, rel=1e-12)
    assert sim.positions[0, 2] - z0 == pytest.approx(-0.02, rel=1e-12)
    assert sim.positions[0, 1] == 0.0 and sim.velocities[0, 1] == 0.0  # no force along y


def test_read_only_columns_refuse_writes(scenes):
    sim = plab.load(scenes.pile())
    for view in (sim.positions, sim.radii, sim.masses, sim.forces, sim.groups, sim.ids):
        assert not view.writeable
        with pytest.raises(ValueError):
            view[0] = 0
    assert sim.velocities.writeable and sim.fixity.writeable


def test_a_view_after_a_cycle_that_added_balls_raises_and_never_reads_freed_memory(scenes):
    sim = plab.load(scenes.fed_box())
    assert len(sim) == 1
    view = sim.positions
    taken = np.asarray(view)      # a plain array from the view: it keeps its storage alive
    first = taken.copy()
    sim.cycle(400)                # the inlet adds balls: the columns reallocate
    assert len(sim) > 1
    with pytest.raises(plab.StaleViewError) as e:
        view[0]
    assert "positions" in str(e.value) and "again" in str(e.value)
    with pytest.raises(plab.StaleViewError):
        np.asarray(view)
    # the array taken before still reads the storage it showed (kept alive, not
    # freed): its values are the old ones
    junk = [np.ones(10_000) for _ in range(50)]  # would reuse freed memory if there were any
    assert np.array_equal(taken, first)
    del junk
    fresh = sim.positions
    assert fresh.shape == (len(sim), 2)
    assert address(fresh) != address(taken)


def test_on_a_fed_scene_views_stay_valid_over_cycles_that_add_no_ball(scenes):
    sim = plab.load(scenes.fed_box())
    view = sim.velocities
    sim.cycle(5)  # the inlet acts every 20 steps: no ball yet
    assert len(sim) == 1
    assert view.shape == (1, 2)
    view[0] = [0.0, 0.0]
    sim.cycle(1)
    assert sim.velocities[0, 1] == pytest.approx(-9.81 * 2e-5)


def test_views_of_a_dropped_simulation_keep_it_alive(scenes):
    view = plab.load(scenes.pile()).positions
    gc.collect()
    assert view.shape == (150, 2) and np.isfinite(np.asarray(view)).all()


def test_a_plugin_field_is_a_view_by_name(scenes):
    scene = scenes.pile()
    scene["plugins"].append("coordination_number")
    scene["passes"] = [{"name": "coordination_number", "properties": {}}]
    sim = plab.load(scene)
    assert "coordination_number" in sim.field_names
    sim.cycle(400)
    z = sim.field("coordination_number")
    assert z.shape == (len(sim),)
    c = sim.contacts()
    ball_ball = ~c["with_wall"]
    # every ball–ball contact counts at both ends (walls count at one)
    expected = np.bincount(np.concatenate([c["end1"], c["end2"][ball_ball]]), minlength=len(sim))
    assert np.array_equal(np.asarray(z), expected)
    with pytest.raises(KeyError):
        sim.field("voidage")


def test_contacts_carry_the_weight_of_a_resting_pile(scenes):
    sim = plab.load(scenes.pile(count=60))
    sim.cycle(6000)
    c = sim.contacts()
    assert len(c["overlap"]) > 0 and (c["overlap"] >= 0).all()
    assert np.allclose(np.linalg.norm(c["normal"], axis=1), 1.0)
    floor = c["with_wall"] & (np.abs(c["normal"][:, 1]) > 0.99)
    # the pile is nearly at rest: the floor carries its weight (force on end 2, the wall)
    weight = 9.81 * np.sum(sim.masses)
    assert -np.sum(c["force"][floor, 1]) == pytest.approx(weight, rel=0.05)
