"""The Python package against real pixels of liboit (python/oit).

Run with the build's library: OIT_LIBRARY=build/lib/liboit.so
OIT_PREP=build/bin/oitprep python3 -m pytest python (ctest: python_oit)."""
import os
import struct
import subprocess
import sys
import zlib

import numpy as np
import pytest

import oit

HERE = os.path.dirname(os.path.abspath(__file__))


def square(alpha=128):
    pos = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float32)
    idx = np.array([[0, 1, 2], [0, 2, 3]])
    col = np.array([[255, 0, 0, alpha]] * 2, dtype=np.uint8)
    return pos, idx, col


FRONT = {"eye": (0, 0, 4), "target": (0, 0, 0), "fovy": 30}


def test_red_square_over_white():
    pos, idx, col = square()
    img = oit.render_arrays(pos, idx, col, size=(64, 48), view=FRONT)
    assert img.shape == (48, 64, 4) and img.dtype == np.uint8
    # Facing the camera (light 1) at alpha a = 128/255 over white:
    # r = a + (1 - a) = 1, g = b = 1 - a.
    assert tuple(img[24, 32]) == (255, 127, 127, 255)
    assert tuple(img[0, 0]) == (255, 255, 255, 255)
    assert tuple(img[47, 63]) == (255, 255, 255, 255)
    # The square spans 1 / (4 tan 15deg) of the height, centred.
    rows = np.nonzero(img[:, 32, 1] == 127)[0]
    assert 0 < rows.min() < 8 and 40 < rows.max() < 47
    f = oit.render_arrays(pos, idx, col, size=(64, 48), view=FRONT, dtype=np.float32)
    assert f.dtype == np.float32
    assert f[24, 32, 0] == pytest.approx(1.0, abs=1e-5)
    assert f[24, 32, 1] == pytest.approx(127 / 255, abs=2e-3)


def test_linear_colour_space():
    pos, idx, col = square()
    img = oit.render_arrays(pos, idx, col, size=(64, 48), view=FRONT, colour_space="linear")
    # In linear light: g = 1 - a = 127/255 linear, encoded 187.19.
    assert tuple(img[24, 32]) == (255, 187, 187, 255)
    assert tuple(img[0, 0]) == (255, 255, 255, 255)
    f = oit.render_arrays(pos, idx, col, size=(64, 48), view=FRONT, dtype=np.float32,
                          colour_space="linear")
    assert f[24, 32, 1] == pytest.approx(1.055 * (127 / 255) ** (1 / 2.4) - 0.055, abs=1e-3)
    # Over a grey background (sRGB 0.5, decoded to 0.214 before blending).
    g = oit.render_arrays(pos, idx, col, size=(32, 32), view=FRONT, background=(0.5, 0.5, 0.5),
                          colour_space="linear")
    a = 128 / 255
    lin = 0.5 / 1.055 + 0.055 / 1.055
    want = 1.055 * ((1 - a) * lin ** 2.4) ** (1 / 2.4) - 0.055
    assert abs(int(g[16, 16, 1]) - round(want * 255)) <= 1 and tuple(g[0, 0, :3]) == (128,) * 3
    with pytest.raises(ValueError):
        oit.Renderer(colour_space="gamma")


def test_row_zero_is_the_top():
    pos, idx, col = square()
    pos[:, 1] = np.where(pos[:, 1] > 0, 1.0, 0.3)  # the square's upper part only
    img = oit.render_arrays(pos, idx, col, size=(32, 32), view=FRONT)
    assert img[8, 16, 1] == 127 and img[24, 16, 1] == 255


def test_background_and_alpha():
    pos, idx, col = square()
    img = oit.render_arrays(pos, idx, col, size=(32, 32), view=FRONT,
                            background=(0, 0, 0, 0))
    # Over transparent black: colour a * red, alpha a.
    assert tuple(img[16, 16]) == (128, 0, 0, 128)
    assert tuple(img[0, 0]) == (0, 0, 0, 0)
    img = oit.render_arrays(pos, idx, col, size=(32, 32), view=FRONT, background=(0, 0, 1))
    assert tuple(img[0, 0]) == (0, 0, 255, 255)
    assert tuple(img[16, 16]) == (128, 0, 127, 255)  # a * red + (1 - a) * blue


def layered_scene():
    """Three overlapping tilted quads, one colour each (4 own vertices)."""
    pos, col, idx = [], [], []
    rgba = [(230, 40, 40, 150), (40, 200, 60, 110), (50, 70, 240, 180)]
    for layer, c in enumerate(rgba):
        z, dx = -0.5 + 0.5 * layer, 0.3 * layer - 0.3
        base = len(pos)
        for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append((x * 0.8 + dx, y * 0.8 + 0.1 * layer, z + 0.2 * x))
            col.append(c)
        idx += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    return (np.array(pos, dtype=np.float32), np.array(idx, dtype=np.uint32),
            np.array(col, dtype=np.uint8))


def write_ply(path, pos, idx, col):
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\n")
        f.write(f"element vertex {len(pos)}\nproperty float x\nproperty float y\n"
                "property float z\nproperty uchar red\nproperty uchar green\n"
                "property uchar blue\nproperty uchar alpha\n")
        f.write(f"element face {len(idx)}\nproperty list uchar int vertex_indices\n"
                "end_header\n")
        for p, c in zip(pos, col):
            f.write("%r %r %r %d %d %d %d\n" % (float(p[0]), float(p[1]), float(p[2]), *c))
        for t in idx:
            f.write("3 %d %d %d\n" % tuple(t))


def test_render_model_equals_render_arrays(tmp_path):
    pos, idx, col = layered_scene()
    ply = tmp_path / "layers.ply"
    write_ply(ply, pos, idx, col)
    from_file = oit.render(ply, size=(96, 72))
    covered = np.any(from_file[:, :, :3] != 255, axis=2).mean()
    assert covered > 0.2, f"only {covered:.0%} of the frame covered"
    assert np.array_equal(from_file, oit.render_arrays(pos, idx, col, size=(96, 72)))
    # The same triangles as a soup with float colours per triangle.
    soup = pos[idx.reshape(-1)]
    tri_col = col[idx[:, 0]].astype(np.float32) / 255.0
    assert np.array_equal(from_file, oit.render_arrays(soup, None, tri_col, size=(96, 72)))
    # A changed colour shows: the comparison can fail.
    col2 = col.copy()
    col2[0] = (0, 0, 0, 255)
    assert not np.array_equal(from_file, oit.render_arrays(pos, idx, col2, size=(96, 72)))


def test_prep_then_part_file(tmp_path):
    pos, idx, col = layered_scene()
    ply, part = tmp_path / "layers.ply", tmp_path / "layers.oitp"
    write_ply(ply, pos, idx, col)
    assert oit.prep(ply, part, part_triangles=2) == part
    with oit.Scene.open(part) as s:
        info = s.info
    assert not info["in_core"] and info["parts"] >= 2 and info["triangles"] >= 6
    a = oit.render(ply, size=(96, 72), dtype=np.float32)
    b = oit.render(part, size=(96, 72), dtype=np.float32)
    # stream vs DFB: at most 0.1% of pixels more than 1/255 apart
    over = (np.abs(a - b).max(axis=2) > 1 / 255).mean()
    assert over <= 0.001, f"{over:.2%} of pixels differ"
    with pytest.raises(oit.OitError) as e:
        oit.prep(tmp_path / "missing.ply", tmp_path / "out.oitp")
    assert "missing.ply" in str(e.value)


def test_large_frames(tmp_path):
    """2048x2048: 2^22 pixels (the capture's end pass alone is more work
    groups than GL promises in one dispatch) and, translucent, more state
    than one storage binding holds (drawn in bands). The part file streamed
    against the mesh in core (DFB)."""
    pos, idx, col = layered_scene()
    ply, part = tmp_path / "layers.ply", tmp_path / "layers.oitp"
    write_ply(ply, pos, idx, col)
    oit.prep(ply, part, part_triangles=2)
    for shading in ("transparent", "translucent"):
        a = oit.render(ply, size=(2048, 2048), dtype=np.float32, shading=shading)
        b = oit.render(part, size=(2048, 2048), dtype=np.float32, shading=shading)
        covered = np.any(a[:, :, :3] < 0.99, axis=2).mean()
        assert covered > 0.2, f"{shading}: only {covered:.0%} of the frame covered"
        over = (np.abs(a - b).max(axis=2) > 1 / 255).mean()
        assert over <= 0.0001, f"{shading}: {over:.4%} of pixels differ"


def test_renderer_options(tmp_path):
    pos, idx, col = layered_scene()
    ply, part = tmp_path / "layers.ply", tmp_path / "layers.oitp"
    write_ply(ply, pos, idx, col)
    oit.prep(ply, part, part_triangles=2)
    ref = oit.render(ply, size=(64, 48))
    with oit.Scene.open(part) as s:
        for opts in ({"pack": "first-k"}, {"pack": "counted", "cache_budget": "off"},
                     {"upload_budget": 65536, "cache_budget": 0}):
            with oit.Renderer(**opts) as r:
                img = r.render(s, size=(64, 48))
                assert (np.abs(img.astype(int) - ref).max(axis=2) > 1).mean() <= 0.001, opts
                if opts.get("cache_budget") == "off":
                    r.render(s, size=(64, 48))
                    assert r.stats["cache_hits"] == 0 and r.stats["bytes_uploaded"] > 0
                # the options in use, every default resolved: what the stats say
                d, st = r.desc, r.stats
                cache = st["cache_budget"] if st["cache_budget"] else "off"
                assert (d["upload_budget"], d["cache_budget"], d["gpu_budget"]) == \
                    (st["ring_budget"], cache, st["gpu_budget"]), (opts, d, st)
                assert 2 <= d["K"] <= 16 and d["alpha"] > 0 and d["scene_scale"] > 0, (opts, d)
                assert d["pack"] == opts.get("pack", "auto"), (opts, d)
    with pytest.raises(oit.OitError) as e:
        oit.Renderer(cache_budget=1000)
    assert "cache_budget = 1000" in e.value.message
    with pytest.raises(ValueError):
        oit.Renderer(pack="sideways")


def test_views():
    pos, idx, col = layered_scene()
    default = oit.render_arrays(pos, idx, col, size=(64, 64))
    assert np.array_equal(default, oit.render_arrays(pos, idx, col, size=(64, 64), view={}))
    eye, target, up, fovy = np.array([0.5, 0.7, 4.0]), np.zeros(3), np.array([0, 1, 0]), 40.0
    near, far = 1.0, 10.0
    looked = oit.render_arrays(pos, idx, col, size=(64, 64),
                               view={"eye": eye, "target": target, "fovy": fovy,
                                     "znear": near, "zfar": far})
    assert not np.array_equal(default, looked)
    # The same camera as numpy matrices (gluLookAt / gluPerspective).
    f = target - eye
    f /= np.linalg.norm(f)
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    view = np.eye(4)
    view[0, :3], view[1, :3], view[2, :3] = s, u, -f
    view[:3, 3] = -view[:3, :3] @ eye
    t = 1 / np.tan(np.radians(fovy) / 2)
    proj = np.zeros((4, 4))
    proj[0, 0], proj[1, 1] = t, t
    proj[2, 2], proj[2, 3] = (far + near) / (near - far), 2 * far * near / (near - far)
    proj[3, 2] = -1
    mats = oit.render_arrays(pos, idx, col, size=(64, 64),
                             view={"view": view, "projection": proj})
    assert (np.abs(mats.astype(int) - looked).max(axis=2) > 1).mean() <= 0.001


def test_translucent_differs():
    pos, idx, col = layered_scene()
    a = oit.render_arrays(pos, idx, col, size=(48, 48))
    b = oit.render_arrays(pos, idx, col, size=(48, 48), shading="translucent")
    assert not np.array_equal(a, b)


def test_errors(tmp_path):
    with pytest.raises(oit.OitError) as e:
        oit.render(tmp_path / "nothing.ply")
    assert e.value.status == "i/o error" and "nothing.ply" in e.value.message
    pos, idx, col = square()
    with pytest.raises(oit.OitError) as e:
        oit.render_arrays(pos, [[0, 1, 7]])
    assert "indices[2] = 7" in e.value.message
    with pytest.raises(ValueError):
        oit.render_arrays(pos[:, :2])
    with pytest.raises(oit.OitError) as e:
        oit.render_arrays(pos, idx, col, view={"eye": (1, 1, 1), "target": (1, 1, 1)})
    assert "eye and target" in e.value.message


def test_library_not_found():
    env = dict(os.environ, OIT_LIBRARY="/nonexistent/liboit.so", LD_LIBRARY_PATH="")
    code = ("import oit\n"
            "try:\n    oit.render_arrays([[0,0,0],[1,0,0],[0,1,0]])\n"
            "except oit.LibraryNotFound as e:\n    print(e)\n")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, cwd=os.path.dirname(HERE))
    assert "/nonexistent/liboit.so" in out.stdout and "OIT_LIBRARY" in out.stdout, \
        out.stdout + out.stderr


def test_save_png(tmp_path):
    pos, idx, col = square()
    img = oit.render_arrays(pos, idx, col, size=(20, 10), view=FRONT)
    path = tmp_path / "square.png"
    oit.save_png(path, img)
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    w, h, depth, ctype = struct.unpack(">IIBB", data[16:26])
    assert (w, h, depth, ctype) == (20, 10, 8, 6)
    start = data.index(b"IDAT") + 4
    length = struct.unpack(">I", data[start - 8:start - 4])[0]
    raw = zlib.decompress(data[start:start + length])
    rows = np.frombuffer(raw, dtype=np.uint8).reshape(10, 1 + 20 * 4)
    assert np.all(rows[:, 0] == 0)
    assert np.array_equal(rows[:, 1:].reshape(10, 20, 4), img)


def read_png_rgba(path):
    """An 8-bit RGB or RGBA PNG as (h, w, n) uint8, every row filter undone."""
    data = open(path, "rb").read()
    w, h, depth, ctype = struct.unpack(">IIBB", data[16:26])
    assert depth == 8 and ctype in (2, 6), (depth, ctype)
    n = 3 if ctype == 2 else 4
    idat, pos = b"", 8
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        if kind == b"IDAT":
            idat += data[pos + 8:pos + 8 + length]
        pos += 12 + length
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(h, 1 + w * n)
    out = np.zeros((h, w * n), dtype=np.int32)
    for y in range(h):
        f, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        prev = out[y - 1] if y else np.zeros(w * n, dtype=np.int32)
        row = np.zeros(w * n, dtype=np.int32)
        for i in range(w * n):
            a = row[i - n] if i >= n else 0
            b, c = prev[i], (prev[i - n] if i >= n else 0)
            if f == 0:
                p = 0
            elif f == 1:
                p = a
            elif f == 2:
                p = b
            elif f == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            row[i] = (line[i] + p) & 255
        out[y] = row
    return out.reshape(h, w, n).astype(np.uint8)


def z_up(pos):
    """The scene turned so that its +y is +z (x stays): (x, y, z) -> (x, -z, y),
    exact in float, which maps oitstream's y-up default view onto its z-up one."""
    return np.stack([pos[:, 0], -pos[:, 2], pos[:, 1]], axis=1).astype(np.float32)


def test_up_azimuth_elevation(tmp_path):
    pos, idx, col = layered_scene()
    zpos = z_up(pos)
    size = (64, 48)
    for az, el in ((None, None), (30, 10), (-75, -40)):
        y_up = oit.render_arrays(pos, idx, col, size=size, azimuth=az, elevation=el)
        z_file = oit.render_arrays(zpos, idx, col, size=size, up="z", azimuth=az, elevation=el)
        assert np.array_equal(y_up, z_file), (az, el)
        # Without up="z" the turned scene is seen from elsewhere: the check can fail.
        assert not np.array_equal(y_up, oit.render_arrays(zpos, idx, col, size=size,
                                                          azimuth=az, elevation=el)), (az, el)
    # The defaults are oitstream's: azimuth 0, elevation 20, up y.
    default = oit.render_arrays(pos, idx, col, size=size)
    assert np.array_equal(default, oit.render_arrays(pos, idx, col, size=size, up="y",
                                                     azimuth=0, elevation=20))
    assert not np.array_equal(default, oit.render_arrays(pos, idx, col, size=size, azimuth=40))
    # A view dict's up alone turns the default view too (it used to fail:
    # "eye and target are the same point").
    assert np.array_equal(oit.render_arrays(zpos, idx, col, size=size, up="z"),
                          oit.render_arrays(zpos, idx, col, size=size,
                                            view={"up": (0, 0, 2.5)}))
    with pytest.raises(oit.OitError) as e:
        oit.render_arrays(zpos, idx, col, size=size, view={"up": (0, 1, 1)})
    assert "+x, +y or +z" in e.value.message
    with pytest.raises(oit.OitError) as e:
        oit.render_arrays(pos, idx, col, size=size, elevation=91)
    assert "elevation 91" in e.value.message
    with pytest.raises(ValueError):
        oit.render_arrays(pos, idx, col, size=size, up="w")
    with pytest.raises(ValueError):
        oit.render_arrays(pos, idx, col, size=size, up="z", view=FRONT)


def test_up_as_oitstream(tmp_path):
    """oit.render(path, up="z", ...) is the image oitstream --up z draws."""
    prep = os.environ.get("OIT_PREP", "")
    tool = os.path.join(os.path.dirname(prep), "oitstream")
    if not os.access(tool, os.X_OK):
        pytest.skip(f"no oitstream beside OIT_PREP ({prep!r})")
    pos, idx, col = layered_scene()
    ply = tmp_path / "zup.ply"
    write_ply(ply, z_up(pos), idx, col)
    for args, kw in (([], {}), (["--azimuth", "30", "--elevation", "-15"],
                                {"azimuth": 30, "elevation": -15})):
        png = tmp_path / "zup.png"
        subprocess.run([tool, str(ply), "--method", "dfb", "--up", "z", "--size", "80x60",
                        "--out", str(png)] + args, check=True, capture_output=True)
        ours = oit.render(ply, size=(80, 60), up="z", **kw)
        theirs = read_png_rgba(png)[:, :, :3]
        covered = np.any(theirs != 255, axis=2).mean()
        assert covered > 0.1, f"{args}: only {covered:.0%} of oitstream's frame covered"
        assert (np.abs(ours[:, :, :3].astype(int) - theirs).max(axis=2) > 1).mean() <= 0.001, args
        assert not np.array_equal(ours, oit.render(ply, size=(80, 60), **kw))
