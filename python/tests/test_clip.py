"""oit.render(..., clip=...): section planes (liboit oit_frame.clip).

Run with the build's library: OIT_LIBRARY=build/lib/liboit.so
"""
import numpy as np
import pytest

import oit
from test_oit import write_ply

FRONT = {"eye": (0, 0, 4), "target": (0, 0, 0), "fovy": 30}


def two_squares():
    """A red square at z = 0.5 in front of a blue one at z = -0.5, both
    alpha 128, as separate triangles."""
    pos, idx, col = [], [], []
    for z, c in ((0.5, (255, 0, 0, 128)), (-0.5, (0, 0, 255, 128))):
        base = len(pos)
        for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append((x, y, z))
            col.append(c)
        idx += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    return (np.array(pos, dtype=np.float32), np.array(idx, dtype=np.uint32),
            np.array(col, dtype=np.uint8))


def test_clip_keeps_one_side():
    pos, idx, col = two_squares()
    both = oit.render_arrays(pos, idx, col, size=(64, 64), view=FRONT)
    # Keeps z <= 0: the blue square alone, as if the red one were not there.
    back = oit.render_arrays(pos, idx, col, size=(64, 64), view=FRONT, clip=[(0, 0, -1, 0)])
    alone = oit.render_arrays(pos[4:], idx[2:] - 4, col[4:], size=(64, 64), view=FRONT)
    assert np.array_equal(back, alone)
    assert not np.array_equal(back, both)
    # Keeps x >= 0.25 (file units): the left part shows the background only.
    right = oit.render_arrays(pos, idx, col, size=(64, 64), view=FRONT, clip=[(1, 0, 0, -0.25)])
    assert tuple(right[32, 20]) == (255, 255, 255, 255)
    assert tuple(right[32, 50]) == tuple(both[32, 50]) != (255, 255, 255, 255)
    # A plane that removes everything: the background everywhere.
    none = oit.render_arrays(pos, idx, col, size=(32, 32), view=FRONT, clip=[(0, 0, 1, -5)])
    assert (none == 255).all()


def test_clip_part_file_culls_parts(tmp_path):
    pos, idx, col = two_squares()
    ply, part = tmp_path / "two.ply", tmp_path / "two.oitp"
    write_ply(ply, pos, idx, col)
    oit.prep(ply, part, part_triangles=2)
    r = oit.Renderer()
    with oit.Scene.open(part) as s, oit.Scene.open(ply) as m:
        img = r.render(s, size=(64, 64), view=FRONT, clip=[(0, 0, -1, 0)])
        stats = dict(r.stats)
        ref = r.render(m, size=(64, 64), view=FRONT, clip=[(0, 0, -1, 0)])
        r.render(s, size=(64, 64), view=FRONT)
        plain = dict(r.stats)
    r.close()
    over = (np.abs(img.astype(int) - ref.astype(int)).max(axis=2) > 1).mean()
    assert over <= 0.001, f"stream vs DFB: {over:.2%} of pixels differ"
    # The red square's part lies wholly in front of the plane: not uploaded.
    assert stats["parts_clipped"] >= 1 and stats["bytes_clipped"] > 0
    assert stats["parts_drawn"] + stats["parts_clipped"] == plain["parts_drawn"]
    assert stats["bytes_uploaded"] < plain["bytes_uploaded"]
    assert plain["parts_clipped"] == 0 and plain["bytes_clipped"] == 0


def test_clip_errors():
    pos, idx, col = two_squares()
    with pytest.raises(oit.OitError) as e:
        oit.render_arrays(pos, idx, col, size=(8, 8), view=FRONT, clip=[(0, 0, 0, 1)])
    assert e.value.status == "invalid argument" and "normal" in e.value.message
    with pytest.raises(oit.OitError) as e:
        oit.render_arrays(pos, idx, col, size=(8, 8), view=FRONT, clip=[(1, 0, 0, 0)] * 7)
    assert "at most 6" in e.value.message
    with pytest.raises(oit.OitError) as e:
        oit.render_arrays(pos, idx, col, size=(8, 8), view=FRONT,
                          clip=[(1, 0, 0, float("nan"))])
    assert "finite" in e.value.message
    with pytest.raises(ValueError):
        oit.render_arrays(pos, idx, col, size=(8, 8), view=FRONT, clip=[(1, 0, 0)])
