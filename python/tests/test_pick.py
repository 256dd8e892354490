"""Renderer.pick (oit_offscreen_pick): the layers of a pixel, front to back.
They compose to the rendered pixel, the reference's (Embree) list is the
walk's, a part file names parts and the same source triangles, and a pixel
outside the view is refused.

Run with the build's library: OIT_LIBRARY=build/lib/liboit.so
"""
import os

import numpy as np
import pytest

import oit

HERE = os.path.dirname(os.path.abspath(__file__))
ASSEMBLY = os.path.join(HERE, "..", "..", "tests", "corpus", "obj", "assembly.obj")
VIEW = {"eye": (0.7, 0.5, 6), "target": (0, 0, 0), "fovy": 45}
SIZE = (48, 36)


def compose(layers):
    """C += T a c, T *= 1 - a over white, checking each layer's T."""
    C, T = np.zeros(3), np.ones(3)
    for l in layers:
        assert np.allclose(l["transmittance"], T, atol=1e-5)
        C += T * l["alpha"] * np.array(l["colour"])
        T *= 1.0 - l["alpha"]
    return C + T


def test_layers_compose_to_the_pixel_and_match_embree():
    with oit.Scene.open(ASSEMBLY) as scene, oit.Renderer(method="reference") as ref, \
            oit.Renderer(method="dfb") as walk:
        image = ref.render(scene, size=SIZE, view=VIEW, dtype=np.float32)
        deep = 0
        for y in range(0, SIZE[1], 3):
            for x in range(0, SIZE[0], 3):
                a = walk.pick(scene, x, y, size=SIZE, view=VIEW)
                b = ref.pick(scene, x, y, size=SIZE, view=VIEW)
                key = lambda ls: [(l["source_triangle"], round(l["depth"], 4)) for l in ls]
                if key(a) != key(b):  # an edge pixel, where rays may differ
                    continue
                assert all(l["part"] is None and l["group"] is None for l in a)
                assert np.allclose(compose(a), image[y, x, :3], atol=1e-4), (x, y)
                deep = max(deep, len(a))
        assert deep >= 3


def test_part_file_names_parts(tmp_path):
    parts = str(tmp_path / "assembly.oitp")
    oit.prep(ASSEMBLY, parts)
    with oit.Scene.open(ASSEMBLY) as mesh, oit.Scene.open(parts) as pf, oit.Renderer() as r:
        compared = 0
        for y in range(1, SIZE[1], 4):
            for x in range(1, SIZE[0], 4):
                a = r.pick(mesh, x, y, size=SIZE, view=VIEW)
                b = r.pick(pf, x, y, size=SIZE, view=VIEW)
                if len(a) < 2:
                    continue
                assert [l["source_triangle"] for l in a] == [l["source_triangle"] for l in b]
                assert all(isinstance(l["part"], int) for l in b)
                compared += 1
        assert compared >= 5


def test_outside_the_view_is_refused():
    with oit.Scene.open(ASSEMBLY) as scene, oit.Renderer() as r:
        with pytest.raises(oit.OitError, match="outside"):
            r.pick(scene, SIZE[0], 0, size=SIZE, view=VIEW)
