"""method (oitstream --method; liboit oit_renderer_desc.method): every method
liboit runs is a Renderer's, the exact ones agree with the Embree reference,
and a wrong name or the wrong kind of scene is refused.

Run with the build's library: OIT_LIBRARY=build/lib/liboit.so
"""
import os

import numpy as np
import pytest

import oit

HERE = os.path.dirname(os.path.abspath(__file__))
ASSEMBLY = os.path.join(HERE, "..", "..", "tests", "corpus", "obj", "assembly.obj")
VIEW = {"eye": (0, 0, 6), "target": (0, 0, 0), "fovy": 45}
SIZE = (96, 72)


def test_methods_are_liboits():
    names = oit.methods()
    assert names[:2] == ["dfb", "reference"] and "stream" in names and len(set(names)) == 15


def test_exact_methods_agree_with_the_reference():
    with oit.Scene.open(ASSEMBLY) as scene:
        images, stats = {}, {}
        for m in ("reference", "dfb", "array", "compute"):
            with oit.Renderer(method=m, see_through=True) as r:
                images[m] = r.render(scene, size=SIZE, view=VIEW)
                stats[m] = r.stats
    assert stats["reference"]["method"] == "reference"
    assert "Embree" in stats["reference"]["device"]
    for m in ("dfb", "array", "compute"):
        assert stats[m]["method"] == m
        # the GL methods and the rays agree but for edge pixels (ties.md)
        diff = np.abs(images[m][..., :3] - images["reference"][..., :3]).max(axis=-1)
        assert (diff > 1 / 255).mean() < 0.02, m
        ref = stats["reference"]["fragments"]
        assert abs(stats[m]["fragments"] - ref) <= ref // 100, (m, stats[m]["fragments"], ref)


def test_wrong_methods_are_refused():
    with pytest.raises(ValueError):
        oit.Renderer(method="dfbb")
    with oit.Scene.open(ASSEMBLY) as scene, oit.Renderer(method="stream") as r:
        with pytest.raises(oit.OitError) as e:
            r.render(scene, size=SIZE, view=VIEW)
        assert "draws part files" in str(e.value)
