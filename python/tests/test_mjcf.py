"""reeve.import_mjcf and reeve.load of a MuJoCo model: the Atwood machine of
tests/mjcf/models/atwood.xml meets its closed form with fixed and with
turning pulleys, and what the scene does not carry is one warning."""
import pathlib

import numpy as np
import pytest

import reeve

MODELS = pathlib.Path(__file__).resolve().parents[2] / "tests" / "mjcf" / "models"
G = 9.81


def heavy_speed(scene, frames=20):
    scene.step(frames)
    heavy = scene.bodies.names.index("heavy")
    return scene.bodies.linear_velocities_m_per_s[heavy][2], scene.time_s


@pytest.mark.parametrize("wheels", ["fixed", "turning"])
def test_the_imported_atwood_machine_meets_its_closed_form(wheels):
    scene_dict = reeve.import_mjcf(MODELS / "atwood.xml", wheels=wheels)
    wheel = 1000 * np.pi * 0.1**2 * 0.1 if wheels == "turning" else 0.0  # kg, I / r^2 = wheel / 2
    a = (2.0 - 1.0) * G / (1.0 + 2.0 + wheel / 2)
    v, t = heavy_speed(reeve.load(scene_dict))
    assert v == pytest.approx(-a * t, rel=1e-7)


def test_loading_the_xml_is_importing_it_with_fixed_pulleys():
    from_xml = heavy_speed(reeve.load(MODELS / "atwood.xml"))
    from_dict = heavy_speed(reeve.load(reeve.import_mjcf(str(MODELS / "atwood.xml"))))
    assert from_xml == from_dict


def test_what_is_not_imported_is_one_warning_naming_lines(tmp_path):
    model = tmp_path / "damped.xml"
    model.write_text('<mujoco>\n<worldbody>\n<body>\n<joint type="hinge" frictionloss="1"/>\n<geom size="0.1"/>\n'
                     '</body>\n</worldbody>\n</mujoco>\n')
    with pytest.warns(UserWarning) as caught:
        reeve.import_mjcf(model)
    assert len(caught) == 1
    assert f"{model}:4: <joint>: frictionloss not imported" in str(caught[0].message)


def test_a_malformed_model_raises_scene_error_with_its_line(tmp_path):
    model = tmp_path / "bad.xml"
    model.write_text('<mujoco>\n<worldbody>\n<body pos="1 2">\n</body>\n</worldbody>\n</mujoco>\n')
    with pytest.raises(reeve.SceneError) as caught:
        reeve.import_mjcf(model)
    assert str(caught.value).startswith(f"{model}:3: <body>: expected pos of 3 numbers")
    with pytest.raises(ValueError):
        reeve.import_mjcf(MODELS / "atwood.xml", wheels="square")


def test_controls_are_held_constant():
    # models/actuators.xml: a motor of gear 2 on a disc of 1 kg and radius
    # 0.2 m (I = 0.02 kg m^2): at control 0.5 it turns it with 1 N m.
    scene = reeve.load(reeve.import_mjcf(MODELS / "actuators.xml", controls={"spin": 0.5}))
    scene.step(10)
    spin = scene.bodies.names.index("spin")
    assert scene.bodies.angular_velocities_rad_per_s[spin][2] == pytest.approx(1.0 * scene.time_s / 0.02, rel=1e-9)
    with pytest.raises(ValueError):
        reeve.import_mjcf(MODELS / "actuators.xml", controls={"spin": float("nan")})
