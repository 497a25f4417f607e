"""Loading scenes from files and dicts, overrides, and the errors a user sees."""
import json
import os

import pytest

import plab

SOURCE = os.environ.get("PLAB_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def test_a_scene_file_loads_as_plab_run_loads_it():
    sim = plab.load(os.path.join(SOURCE, "examples", "teaching", "bounce.json"))
    assert sim.dim == 2 and len(sim) == 1 and sim.step == 0
    assert sim.model_names == ["linear"]
    assert sim.positions[0, 1] == pytest.approx(0.1)


def test_a_dict_loads_with_the_same_schema_and_the_same_state_as_its_file(tmp_path, scenes):
    scene = scenes.pile()
    path = tmp_path / "pile.json"
    path.write_text(json.dumps(scene))
    from_file, from_dict = plab.load(path), plab.load(scene)
    assert len(from_file) == len(from_dict) == 150
    from_file.cycle(50)
    from_dict.cycle(50)
    assert from_file.state_hash() == from_dict.state_hash()


def test_overrides_from_a_dict_and_from_keywords_change_the_value_at_their_path(scenes):
    by_dict = plab.load(scenes.pile(), set={"contact_models.0.properties.kn": 2e6})
    by_keyword = plab.load(scenes.pile(), contact_models__0__properties__kn=2e6)
    for sim in (by_dict, by_keyword):
        assert sim.scene["contact_models"][0]["properties"]["kn"] == 2e6
    assert plab.load(scenes.pile()).scene["contact_models"][0]["properties"]["kn"] == 1e5


def test_a_value_out_of_range_raises_input_error_naming_the_json_path_and_the_range(scenes):
    scene = scenes.pile()
    scene["contact_models"][0]["properties"]["fric"] = -1
    with pytest.raises(plab.InputError) as e:
        plab.load(scene)
    assert "scene.contact_models[0].properties.fric" in str(e.value) or \
        "scene.contact_models.0.properties.fric" in str(e.value)
    assert "-1" in str(e.value)
    assert e.value.path.startswith("scene.contact_models")


def test_an_override_of_a_missing_path_is_refused_by_name(scenes):
    with pytest.raises(plab.InputError) as e:
        plab.load(scenes.pile(), set={"contact_models.0.propertys.kn": 1})
    assert "propertys" in str(e.value)


def test_a_missing_file_names_the_file(tmp_path):
    missing = tmp_path / "nowhere.json"
    with pytest.raises(plab.InputError) as e:
        plab.load(missing)
    assert str(missing) in str(e.value)


def test_an_unknown_plugin_is_an_input_error_listing_the_plugins_found(scenes):
    scene = scenes.pile()
    scene["plugins"] = ["linaer"]
    with pytest.raises(plab.InputError) as e:
        plab.load(scene)
    assert "scene.plugins" in str(e.value) and "linear" in str(e.value)


def test_the_errors_are_the_cli_s_messages(tmp_path, scenes):
    """The same bad scene gives the same message from Python and from plab check."""
    import subprocess
    exe = os.environ.get("PLAB_EXE")
    if not exe:
        pytest.fail("PLAB_EXE is not set: the CTest entry python_pytest sets it")
    scene = scenes.pile()
    scene["bodies"][0]["radius"] = [0.004, 0.002]
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(scene))
    cli = subprocess.run([exe, "check", str(path)], capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(plab.InputError) as e:
        plab.load(path)
    assert cli.stderr.strip() == "error: " + str(e.value)


def test_summary_is_a_dict_with_the_state_hash_and_histories_are_numpy_columns(scenes):
    sim = plab.load(scenes.pile())
    sim.cycle(100)
    s = sim.summary()
    assert s["steps"] == 100 and s["bodies"] == 150
    assert int(s["state_hash"], 16) == sim.state_hash()
    h = sim.history(as_dict=True)
    assert list(h) == ["time", "ke"]
    assert len(h["time"]) == 3  # steps 0, 50, 100
    assert h["time"][-1] == pytest.approx(sim.time)
