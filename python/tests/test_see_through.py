"""see_through (oitstream --see-through; liboit oit_renderer_desc.see_through):
opaque materials hide what is behind them unless it is set.

Run with the build's library: OIT_LIBRARY=build/lib/liboit.so
"""
import os

import numpy as np
import pytest

import oit

HERE = os.path.dirname(os.path.abspath(__file__))
# Two opaque boxes (MTL d 1 and no d) and a red cover of d 0.3 in front of
# half the blue one (tests/tools/oitstream/test_materials.sh).
ASSEMBLY = os.path.join(HERE, "..", "..", "tests", "corpus", "obj", "assembly.obj")
VIEW = {"eye": (0, 0, 6), "target": (0, 0, 0), "fovy": 45}
SIZE = (160, 120)


def draw(renderer, scene):
    """The scene over white and over black, and the stats of the first."""
    white = renderer.render(scene, size=SIZE, view=VIEW, background=(1, 1, 1))
    stats = renderer.stats
    black = renderer.render(scene, size=SIZE, view=VIEW, background=(0, 0, 0))
    return white, black, stats


def opaque_pixels(white, black):
    """Pixels the same over both backgrounds: nothing shows through them."""
    return np.all(white[..., :3] == black[..., :3], axis=-1)


def test_see_through_shows_what_opaque_materials_hide():
    with oit.Scene.open(ASSEMBLY) as scene, oit.Renderer() as solid, \
            oit.Renderer(see_through=True) as see:
        w0, b0, s0 = draw(solid, scene)
        w1, b1, s1 = draw(see, scene)
    hidden = opaque_pixels(w0, b0)
    assert hidden.sum() > SIZE[0] * SIZE[1] // 20, "the opaque boxes hide nothing"
    assert not opaque_pixels(w1, b1).any(), "see_through leaves opaque pixels"
    changed = np.any(w0[..., :3] != w1[..., :3], axis=-1)
    assert changed[hidden].all(), "see_through leaves opaque pixels as they were"
    assert (s0["opaque"], s0["see_through"]) == (1, 0)
    assert (s1["opaque"], s1["see_through"]) == (0, 1)
    # A ray through a box meets a face going in and one going out; the second
    # is stored only when the box is seen through (edge pixels aside).
    assert s1["fragments"] >= s0["fragments"] + hidden.sum() * 9 // 10, (s0, s1)


def test_render_see_through_matches_the_renderer():
    plain = oit.render(ASSEMBLY, size=SIZE, view=VIEW)
    see = oit.render(ASSEMBLY, size=SIZE, view=VIEW, see_through=True)
    with oit.Scene.open(ASSEMBLY) as scene, oit.Renderer(see_through=True) as r:
        assert np.array_equal(see, r.render(scene, size=SIZE, view=VIEW))
    assert np.any(plain != see, axis=-1).sum() > SIZE[0] * SIZE[1] // 20


def test_render_arrays_see_through():
    """An opaque red square in front of a blue one of alpha 128: the blue
    shows through the red only with see_through (then alpha 0.35 on both)."""
    pos, idx, col = [], [], []
    for z, c in ((0.5, (255, 0, 0, 255)), (-0.5, (0, 0, 255, 128))):
        base = len(pos)
        pos += [(-1, -1, z), (1, -1, z), (1, 1, z), (-1, 1, z)]
        col += [c] * 4
        idx += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    args = (np.array(pos, np.float32), np.array(idx, np.uint32), np.array(col, np.uint8))
    front = {"eye": (0, 0, 4), "target": (0, 0, 0), "fovy": 30}
    solid = oit.render_arrays(*args, size=(32, 32), view=front)
    see = oit.render_arrays(*args, size=(32, 32), view=front, see_through=True)
    assert tuple(solid[16, 16]) == (255, 0, 0, 255)
    # red at 0.35 over blue at 0.35 over white: r = .35 + .65^2, g = .65^2,
    # b = .65 * .35 + .65^2
    want = (0.35 + 0.4225, 0.4225, 0.2275 + 0.4225)
    assert all(abs(int(see[16, 16, c]) - want[c] * 255) <= 1 for c in range(3)), see[16, 16]


def test_see_through_is_checked_by_liboit():
    with pytest.raises(oit.OitError, match="see_through = 2"):
        oit.Renderer(see_through=2)
