"""Scene.info["up"] and the default view (oit_scene_info.up_axis): a STEP
file is Z-up and its default view is render(up="z")'s; a glTF is Y-up;
up= still overrides.

Run with the build's library: OIT_LIBRARY=build/lib/liboit.so
"""
import os

import numpy as np

import oit

CORPUS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "corpus")
SIZE = (64, 48)


def test_step_is_z_up():
    with oit.Scene.open(os.path.join(CORPUS, "step", "parts.step")) as scene, \
            oit.Renderer() as r:
        assert scene.info["up"] == "z"
        default = r.render(scene, size=SIZE)
        z = r.render(scene, size=SIZE, up="z")
        y = r.render(scene, size=SIZE, up="y")
    assert np.array_equal(default, z)
    assert not np.array_equal(default, y)


def test_gltf_is_y_up():
    with oit.Scene.open(os.path.join(CORPUS, "gltf", "scene.gltf")) as scene:
        assert scene.info["up"] == "y"
