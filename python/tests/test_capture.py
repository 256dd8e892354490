"""oit.Renderer(capture=...) and oit.render(..., capture=...): how a part
file's K-slot fills are made (liboit oit_renderer_desc.capture, oitstream
--capture).

Run with the build's library: OIT_LIBRARY=build/lib/liboit.so
"""
import numpy as np
import pytest

import oit
from test_clip import FRONT, two_squares
from test_oit import write_ply


@pytest.fixture
def part_file(tmp_path):
    pos, idx, col = two_squares()
    ply, part = tmp_path / "two.ply", tmp_path / "two.oitp"
    write_ply(ply, pos, idx, col)
    oit.prep(ply, part, part_triangles=2)
    return part


def render_with(part, capture, pack="disjoint"):
    """The image and the stats of one render with a renderer of its own."""
    r = oit.Renderer(capture=capture, pack=pack)
    try:
        with oit.Scene.open(part) as s:
            img = r.render(s, size=(64, 64), view=FRONT)
        return img, dict(r.stats)
    finally:
        r.close()


def test_capture_array_auto_stencil(part_file):
    arr, arr_stats = render_with(part_file, "array")
    assert arr_stats["capture_slots"] == "array"
    assert not arr_stats["capture_fallback"]
    # Both squares drawn: the middle is neither background nor one square.
    assert tuple(arr[32, 32]) != (255, 255, 255, 255)
    auto, auto_stats = render_with(part_file, "auto")
    assert np.array_equal(auto, arr)
    if auto_stats["capture_slots"] == "array":
        # The self-test failed here (llvmpipe): auto says why, and a
        # stencil capture asked for outright is refused with that reason.
        assert auto_stats["capture_fallback"]
        with pytest.raises(oit.OitError):
            render_with(part_file, "stencil")
    else:
        assert auto_stats["capture_slots"] == "stencil"
        st, st_stats = render_with(part_file, "stencil")
        assert st_stats["capture_slots"] == "stencil"
        assert np.array_equal(st, arr)


def test_capture_module_render(part_file):
    img = oit.render(part_file, size=(64, 64), view=FRONT, capture="array")
    # the module's renderer for that capture is its own, and ran array slots
    stats = oit._default_renderer("transparent", "srgb", "array").stats
    assert stats["capture_slots"] == "array"
    assert np.array_equal(img, oit.render(part_file, size=(64, 64), view=FRONT))


def test_capture_bad_name():
    with pytest.raises(ValueError, match="capture"):
        oit.Renderer(capture="routed")


def test_auto_choice_stats(part_file):
    """pack="auto" reports its measured choice (liboit oit_draw_stats.choice,
    view/stream/choice.h): the first draw the seed with no costs, the same view
    again first-k held (two squares: no second pass, nothing to probe) with
    first-k's measured cost; a fixed pack reports none."""
    r = oit.Renderer(pack="auto")
    try:
        with oit.Scene.open(part_file) as s:
            r.render(s, size=(64, 64), view=FRONT)
            first = dict(r.stats)
            r.render(s, size=(64, 64), view=FRONT)
            second = dict(r.stats)
    finally:
        r.close()
    assert first["choice"] == "first-k" and first["choice_why"] == "seed"
    assert first["choice_first_k_ms"] == -1.0 and first["choice_counted_ms"] == -1.0
    assert second["choice"] == "first-k" and second["choice_why"] == "held"
    assert second["choice_first_k_ms"] > 0.0 and second["choice_counted_ms"] == -1.0
    _, fixed = render_with(part_file, "array", pack="counted")
    assert fixed["choice"] is None and fixed["choice_first_k_ms"] == -1.0
