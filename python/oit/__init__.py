"""oit: exact order-independent transparency of meshes, from Python.

A thin ctypes layer over liboit (include/oit/liboit.h, oit/offscreen.h):
scenes are mesh files (.ply .obj .off .stl .gltf .glb .vtk .vtp, held in core and
drawn with DFB), part files (.oitp, streamed) or numpy arrays; images come
back as numpy arrays (height, width, 4), row 0 at the top.

    import oit
    img = oit.render("bunny.ply", size=(800, 600))      # uint8 RGBA
    oit.save_png("bunny.png", img)

liboit.so is found through OIT_LIBRARY, the installed package's own
location, or the system loader (see oit._lib). Rendering needs EGL with
OpenGL 4.5 core (an NVIDIA driver or Mesa's llvmpipe).
"""
import os
import shutil
import subprocess
import weakref

import ctypes

import numpy as np

from . import _lib as L
from ._lib import LibraryNotFound, lib_path
from ._png import save_png

__all__ = ["render", "render_arrays", "prep", "save_png", "Scene", "Renderer", "OitError",
           "LibraryNotFound", "lib_path", "prep_tool"]


class OitError(RuntimeError):
    """A liboit call failed: .status is its oit_status name, .message the
    library's one line naming the input."""

    def __init__(self, status, message):
        self.status = status
        self.message = message
        super().__init__(f"{status}: {message}")


def _check(status, err):
    if status != L.OIT_OK:
        name = L.lib().oit_status_name(status).decode()
        raise OitError(name, err.message.decode(errors="replace"))


class _Closable:
    """close() on leaving a with-block and when collected (errors then are
    dropped: the interpreter may be shutting down)."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass


class Scene(_Closable):
    """A scene liboit draws: Scene.open(path) or Scene.from_arrays(...).
    Close it (or use `with`) to free it; renderers that drew it let go of
    it first."""

    def __init__(self, handle, name):
        self._h = handle
        self.name = name
        self._renderers = weakref.WeakSet()

    @classmethod
    def open(cls, path):
        """A part file (streamed) or any mesh file the readers take (in core)."""
        h, err = ctypes.c_void_p(), L.Error()
        path = os.fspath(path)
        _check(L.lib().oit_scene_open(path.encode(), None, ctypes.byref(h), ctypes.byref(err)),
               err)
        return cls(h, path)

    @classmethod
    def from_arrays(cls, positions, indices=None, colours=None, colour_rate="auto",
                    name="arrays"):
        """positions: (n, 3) floats. indices: (m, 3) or (3m,) non-negative ints
        below n, or None for a soup (n a multiple of 3). colours: None, or RGBA
        (k, 4) uint8 (0..255) or floats (0..1), per vertex (k = n) or per
        triangle (k = triangles); colour_rate "vertex" or "triangle" says
        which when both counts are equal ("auto" refuses to guess then).
        The arrays are copied."""
        pos = np.ascontiguousarray(positions, dtype=np.float32)
        if pos.ndim != 2 or pos.shape[1] != 3:
            raise ValueError(f"positions: shape {pos.shape}, expected (n, 3)")
        d = L.SceneMeshDesc()
        d.positions = pos.ctypes.data
        d.vertex_count = pos.shape[0]
        keep = [pos]
        if indices is not None:
            idx = np.asarray(indices)
            if idx.size and (idx.min() < 0 or idx.max() > 0xFFFFFFFF):
                raise ValueError("indices: values must lie in 0..2^32-1")
            idx = np.ascontiguousarray(idx, dtype=np.uint32).reshape(-1)
            if idx.size % 3:
                raise ValueError(f"indices: {idx.size} values, not a multiple of 3")
            d.indices = idx.ctypes.data
            d.index_count = idx.size
            keep.append(idx)
            triangles = idx.size // 3
        else:
            triangles = pos.shape[0] // 3
        if colours is not None:
            col = np.asarray(colours)
            if col.ndim != 2 or col.shape[1] != 4:
                raise ValueError(f"colours: shape {col.shape}, expected (k, 4) RGBA")
            if col.dtype == np.uint8:
                d.colour_type = L.COLOUR_UINT8
            else:
                col = col.astype(np.float32)
                d.colour_type = L.COLOUR_FLOAT
            col = np.ascontiguousarray(col)
            rate = colour_rate
            if rate == "auto":
                if col.shape[0] == pos.shape[0] and col.shape[0] == triangles:
                    raise ValueError("colours: as many vertices as triangles; say "
                                     "colour_rate='vertex' or 'triangle'")
                rate = "vertex" if col.shape[0] == pos.shape[0] else "triangle"
            if rate not in ("vertex", "triangle"):
                raise ValueError(f"colour_rate: {colour_rate!r}, expected auto, vertex or "
                                 "triangle")
            want = pos.shape[0] if rate == "vertex" else triangles
            if col.shape[0] != want:
                raise ValueError(f"colours: {col.shape[0]} rows; {pos.shape[0]} vertices, "
                                 f"{triangles} triangles")
            d.colour_rate = L.COLOUR_PER_VERTEX if rate == "vertex" else L.COLOUR_PER_TRIANGLE
            d.colours = col.ctypes.data
            keep.append(col)
        d.name = name.encode()
        h, err = ctypes.c_void_p(), L.Error()
        _check(L.lib().oit_scene_create_mesh(ctypes.byref(d), ctypes.byref(h),
                                             ctypes.byref(err)), err)
        return cls(h, name)

    @property
    def info(self):
        """oit_scene_info as a dict; "up": the up axis ("x", "y" or "z") the
        file's format says or its bounds suggest (z for STEP and IGES and
        for a model flat in z, y for glTF), which the default view turns
        about."""
        info, err = L.SceneInfo(), L.Error()
        _check(L.lib().oit_scene_get_info(self._handle(), ctypes.byref(info),
                                          ctypes.byref(err)), err)
        return {"triangles": info.triangles, "parts": info.parts,
                "bounds_min": tuple(info.bounds_min), "bounds_max": tuple(info.bounds_max),
                "K": info.K, "attributes": info.attributes, "origin": tuple(info.origin),
                "in_core": bool(info.in_core),
                "up": next(k for k, x in _UP_AXES.items() if x == info.up_axis)}

    def _handle(self):
        if not self._h:
            raise ValueError(f"{self.name}: the scene is closed")
        return self._h

    def close(self):
        if self._h:
            for r in list(self._renderers):
                r._release(self)
            L.lib().oit_scene_close(self._h)
            self._h = None


_SHADINGS = {"transparent": L.RENDER_TRANSPARENT, "translucent": L.RENDER_TRANSLUCENT}
# oit_render_colour_space (liboit.h), oit_up_axis (offscreen.h),
# oit_render_pack and oit_render_capture (render_modes.h), spelt as the
# tools spell them (_lib.py holds the values, checked against C)
_COLOUR_SPACES = L.COLOUR_SPACES
_UP_AXES = L.UP_AXES
_PACKS = L.PACKS
_CAPTURES = L.CAPTURES


def methods():
    """The methods a Renderer runs (oit_render_methods), in oitstream's order."""
    n = ctypes.c_uint32()
    m = L.lib().oit_render_methods(ctypes.byref(n))
    return [m[i].name.decode() for i in range(n.value)]


class Renderer(_Closable):
    """An offscreen renderer: its own headless GL context and an oit_renderer
    (oit_offscreen_create). Options as in oit_renderer_desc; 0/None means the
    library's default. Use it from one thread.

    stats: None before the first render, then a dict of the last render's
    figures (liboit's oit_draw_stats, include/oit/draw_stats.h, field for
    field): numbers as int or
    float, gpu_phase_ms a list, and names as str, None where the library
    has none: stats["method"] and stats["device"] what drew ("dfb",
    "llvmpipe (...)"), stats["capture"] the capture that ran,
    stats["capture_asked"] the capture= given, stats["capture_slots"]
    "stencil" or "array" (None: no K-slot fill ran), stats["capture_fallback"]
    why auto did not take stencil ("" when it did), stats["choice"] and
    stats["choice_why"] pack="auto"'s choice, stats["budget_source"] where
    the GPU budget came from."""

    def __init__(self, shading="transparent", alpha=None, default_rgb=None, absorption=None,
                 K=0, epsilon=0.0, pack="auto", upload_budget=0, cache_budget=0,
                 colour_space="srgb", gpu_budget=0, capture="auto", see_through=False,
                 method=None):
        """method: what draws (oit_renderer_desc.method): None (default)
        streams a part file and draws a mesh with DFB; else a name of
        methods(): "reference" (Embree, on the CPU), "dfb", "wboit", ... for
        meshes, "stream" for part files. stats["method"] and stats["device"]
        say what drew.
        shading: "transparent" (default) or "translucent" (Beer-Lambert
        absorption and Fresnel); alpha, default_rgb (r, g, b) and absorption
        its constants, None for the library's (desc has them after a render).
        colour_space: "srgb" (default) composites the sRGB-encoded colours as
        given; "linear" decodes them (exact sRGB EOTF), composites in linear
        light and returns the result sRGB-encoded.
        K: fragments a pixel per batch of the K-slot captures, 2..16 (0, the
        default: the part file's K, else 16).
        epsilon: in [0, 1); the stream drops fragments behind pixels whose
        transmittance fell below it and skips parts whose whole footprint
        did (error <= epsilon a channel); 0 (default): exact. For method
        "f2b" and "guarded", their thresholds (0: theirs, 0.02 and 0.0025).
        pack: how a part file's parts are cut into packs, each captured as
        one batch: "auto" (default: "first-k" or "counted", whichever
        measures faster on the view), "counted" (cut by upload bytes, each
        counted, stored and sorted per pixel: no layer limit), "first-k"
        (as counted, drawn once into K slots a pixel, a second pass only for
        pixels that got more), "disjoint" (K slots a pixel: parts whose
        screen rectangles miss each other) or "budget" (K slots a pixel: the
        layer bounds per tile stay <= K); stats["choice"] says what auto took.
        upload_budget, cache_budget, gpu_budget: bytes of the upload ring
        (>= 64K), of the cache that keeps uploaded parts for later renders
        (>= 64K; "off": no cache) and of the GPU memory of both and the
        capture together (>= 1M); 0 (default): the library's choice
        (stats["ring_budget"], stats["cache_budget"], stats["gpu_budget"]).
        capture: how a part file's K-slot fills are made, for "disjoint" and
        "budget" packs and the first pass of "first-k" (a "counted" pack has
        none): "auto" (default): "stencil" where its self-test passes on
        this driver at K, else "array"; "stencil": the stencil-routed
        A-buffer (MSAA samples filled in order by the stencil), or an
        OitError at the first render with the self-test's reason (llvmpipe
        does not route per sample); "array": slots through an atomic
        counter; "compute": no K-slot fill and no layer limit, every pack
        binned into tiles, rasterized, ordered and composited in compute
        shaders (pack="auto" then cuts counted packs). The image is the same
        whichever runs; stats["capture_slots"] says which fill ran and
        stats["capture_fallback"] why auto did not take stencil.
        see_through: False (default): a model's own alpha, and its opaque
        triangles (glTF OPAQUE and MASK materials, MTL d 1) hide what is
        behind them; True: every triangle takes alpha (its colours kept),
        so what they hid is drawn too. stats["see_through"] and
        stats["opaque"] (1 when opaque triangles hid what is behind them)
        say what the last render did.
        Each option is oitstream's of the same name (K: --max-layers), so a
        command line carries over."""
        if colour_space not in _COLOUR_SPACES:
            raise ValueError(f"colour_space: {colour_space!r}, expected srgb or linear")
        if shading not in _SHADINGS:
            raise ValueError(f"shading: {shading!r}, expected transparent or translucent")
        if pack not in _PACKS:
            raise ValueError(f"pack: {pack!r}, expected one of {', '.join(_PACKS)}")
        if capture not in _CAPTURES:
            raise ValueError(f"capture: {capture!r}, expected one of {', '.join(_CAPTURES)}")
        d = L.OffscreenDesc()
        if method is not None and method not in methods():
            raise ValueError(f"method: {method!r}, expected one of {', '.join(methods())}")
        d.renderer.method = method.encode() if method else None
        d.renderer.capture = _CAPTURES[capture]
        d.renderer.K = K
        d.renderer.epsilon = epsilon
        d.renderer.pack = _PACKS[pack]
        d.renderer.upload_budget = int(upload_budget)
        d.renderer.gpu_budget = int(gpu_budget)
        d.renderer.see_through = int(see_through)  # liboit checks it is 0 or 1
        d.renderer.cache_budget = L.RENDER_CACHE_OFF if cache_budget == "off" else int(cache_budget)
        d.renderer.shading.mode = _SHADINGS[shading]
        d.renderer.shading.colour_space = _COLOUR_SPACES[colour_space]
        if alpha is not None:
            d.renderer.shading.alpha = alpha
        if default_rgb is not None:
            d.renderer.shading.default_rgb[:] = [float(c) for c in default_rgb]
        if absorption is not None:
            d.renderer.shading.absorption = absorption
        h, err = ctypes.c_void_p(), L.Error()
        _check(L.lib().oit_offscreen_create(ctypes.byref(d), ctypes.byref(h),
                                            ctypes.byref(err)), err)
        self._h = h
        self.stats = None

    @property
    def gl_renderer(self):
        return L.lib().oit_offscreen_gl_renderer(self._h).decode()

    @property
    def desc(self):
        """The options in use, every default resolved (oit_renderer_get_desc):
        after a render of a part file, K, upload_budget, cache_budget ("off":
        none, a resident scene included), gpu_budget (0: no total), capture
        (what the K-slot fills use) and read_on_draw_thread as they run
        (stats["ring_budget"] and its siblings say the same); after any
        render, the shading's defaults (alpha, default_rgb, absorption,
        scene_scale). Before a render: the options as given."""
        d = L.OffscreenDesc()
        L.lib().oit_offscreen_get_desc(self._h, ctypes.byref(d))
        r, sh = d.renderer, d.renderer.shading
        name = lambda table, v: next(k for k, x in table.items() if x == v)
        return {"K": r.K, "upload_budget": r.upload_budget,
                "cache_budget": "off" if r.cache_budget == L.RENDER_CACHE_OFF else r.cache_budget,
                "gpu_budget": r.gpu_budget, "pack": name(_PACKS, r.pack),
                "capture": name(_CAPTURES, r.capture), "epsilon": r.epsilon,
                "read_on_draw_thread": bool(r.read_on_draw_thread),
                "see_through": bool(r.see_through), "shading": name(_SHADINGS, sh.mode),
                "alpha": sh.alpha, "default_rgb": list(sh.default_rgb),
                "absorption": sh.absorption, "scene_scale": sh.scene_scale,
                "colour_space": name(_COLOUR_SPACES, sh.colour_space)}

    def render(self, scene, size=(512, 512), view=None, dtype=np.uint8, background=None,
               clip=None, up=None, azimuth=None, elevation=None):
        """The image of scene (a Scene) as a (height, width, 4) array, uint8
        or float32 (dtype); size is (width, height). Afterwards, self.stats
        holds the render's figures (the class's docstring says which).
        view: None (the tools' default view of the scene's bounds), a dict
        with eye, target and optional up, fovy, znear, zfar (the scene's
        coordinates; without eye and target the default view about up,
        which must then be +x, +y or +z), or a dict with view and
        projection 4x4 matrices as numpy writes them (v' = M @ v).
        up ("x", "y" or "z": the model's up axis), azimuth and elevation
        (degrees) turn the default view (up: scene.info["up"], z for STEP
        and IGES and for a model flat in z, else y; azimuth 0, elevation
        20),
        computed by liboit (oit_offscreen_default_view), as oitstream's
        options of those names do; they take view=None.
        background: RGBA, default opaque white. clip: section planes, a
        list of up to 6 (nx, ny, nz, d) in the scene's coordinates, each
        keeping what lies where nx*x + ny*y + nz*z + d >= 0 (liboit checks
        them: oit_frame.clip)."""
        v = _camera_view(scene, size, view, clip, up, azimuth, elevation)
        w, h = v.width, v.height
        dtype = np.dtype(dtype)
        if dtype == np.uint8:
            v.format = L.PIXELS_RGBA8
        elif dtype == np.float32:
            v.format = L.PIXELS_RGBA32F
        else:
            raise ValueError(f"dtype: {dtype}, expected uint8 or float32")
        if background is not None:
            bg = [float(c) for c in background]
            if len(bg) == 3:
                bg.append(1.0)
            if len(bg) != 4:
                raise ValueError("background: 3 or 4 numbers")
            # 0 means 0 here, not the library's "default": negative stands for 0.
            v.background[:] = [c if c != 0.0 else -1.0 for c in bg]
        out = np.empty((h, w, 4), dtype=dtype)
        stats, err = L.DrawStats(), L.Error()
        scene._renderers.add(self)
        _check(L.lib().oit_offscreen_render(self._h, scene._handle(), ctypes.byref(v),
                                            out.ctypes.data, out.nbytes, ctypes.byref(stats),
                                            ctypes.byref(err)), err)
        self.stats = _stats_dict(stats)
        return out

    def pick(self, scene, x, y, size=(512, 512), view=None, clip=None, up=None, azimuth=None,
             elevation=None):
        """Every layer of pixel (x, y) (0, 0 the top left, as render's
        rows) of the view render would draw with the same size, view, clip,
        up, azimuth and elevation, front to back: a list of dicts with
        depth (the tie rule's key along the pixel's ray, scene units),
        point (where the ray meets the layer, in the file's coordinates),
        alpha, colour (rgb as composited), transmittance (rgb, of the light
        in front of the layer), front (the face turns towards the viewer),
        part (None in core), source_triangle, group and material (None: no
        reader keeps names yet). They are the layers of the exact image:
        the reference's ray and the tie rule (oit_renderer_pick; through
        Embree for method="reference" on a mesh); a rasterizing method
        may differ by a triangle on edge pixels only. Needs no GL and
        draws nothing (as oitstream --pick)."""
        v = _camera_view(scene, size, view, clip, up, azimuth, elevation)
        count, err = ctypes.c_size_t(), L.Error()
        scene._renderers.add(self)
        args = (self._h, scene._handle(), ctypes.byref(v), int(x), int(y))
        _check(L.lib().oit_offscreen_pick(*args, None, 0, ctypes.byref(count),
                                          ctypes.byref(err)), err)
        layers = (L.PickLayer * max(count.value, 1))()
        _check(L.lib().oit_offscreen_pick(*args, layers, count.value, ctypes.byref(count),
                                          ctypes.byref(err)), err)
        name = lambda b: b.decode() if b is not None else None
        origin = scene.info["origin"]
        return [{"depth": l.depth, "point": [p + o for p, o in zip(l.point, origin)],
                 "alpha": l.alpha, "colour": list(l.colour),
                 "transmittance": list(l.transmittance), "front": bool(l.front),
                 "part": None if l.part == L.PICK_NO_PART else l.part,
                 "source_triangle": l.source_triangle, "group": name(l.group),
                 "material": name(l.material)} for l in layers[:count.value]]

    def _release(self, scene):
        if self._h and scene._h:
            L.lib().oit_offscreen_release_scene(self._h, scene._h)

    def close(self):
        if self._h:
            L.lib().oit_offscreen_destroy(self._h)
            self._h = None


def _stats_dict(stats):
    """oit_draw_stats as a dict: its strings (bytes through ctypes) as str,
    NULL as None, gpu_phase_ms a list."""
    out = {}
    for name, _ in L.DrawStats._fields_:
        v = getattr(stats, name)
        out[name] = v.decode(errors="replace") if isinstance(v, bytes) else v
    out["gpu_phase_ms"] = list(stats.gpu_phase_ms)
    return out


def _camera_view(scene, size, view, clip, up, azimuth, elevation):
    """The OffscreenView of render's and pick's size, camera and planes."""
    v = L.OffscreenView()
    v.width, v.height = (int(size[0]), int(size[1]))
    _set_view(v, view)
    if up is not None or azimuth is not None or elevation is not None:
        _set_default_view(v, scene, view, up, azimuth, elevation)
    _set_clip(v, clip)
    return v


def _set_view(v, view):
    if view is None:
        return
    if not isinstance(view, dict):
        raise ValueError("view: None or a dict (eye/target/up/fovy/znear/zfar, or "
                         "view/projection matrices)")
    if "view" in view or "projection" in view:
        for key in ("view", "projection"):
            m = np.asarray(view[key], dtype=np.float32)
            if m.shape != (4, 4):
                raise ValueError(f"view[{key!r}]: shape {m.shape}, expected (4, 4)")
            getattr(v, key)[:] = m.T.reshape(-1).tolist()  # column-major for GL
        v.use_matrices = 1
        return
    unknown = set(view) - {"eye", "target", "up", "fovy", "znear", "zfar"}
    if unknown:
        raise ValueError(f"view: unknown keys {sorted(unknown)}")
    for key in ("eye", "target", "up"):
        if key in view:
            vec = [float(c) for c in view[key]]
            if len(vec) != 3:
                raise ValueError(f"view[{key!r}]: 3 numbers")
            getattr(v, key)[:] = vec
    v.fovy_deg = float(view.get("fovy", 0.0))
    v.znear = float(view.get("znear", 0.0))
    v.zfar = float(view.get("zfar", 0.0))


def _set_clip(v, clip):
    if clip is None:
        return
    planes = [[float(c) for c in plane] for plane in clip]
    for i, plane in enumerate(planes):
        if len(plane) != 4:
            raise ValueError(f"clip[{i}]: {len(plane)} numbers, expected 4 (nx, ny, nz, d)")
    # The count goes as given, so that liboit, which owns the check, says
    # when there are too many.
    v.clip_count = len(planes)
    for i, plane in enumerate(planes[:len(v.clip)]):
        v.clip[i][:] = plane


def _set_default_view(v, scene, view, up, azimuth, elevation):
    """v's camera: the default view turned by up, azimuth and elevation."""
    if view is not None:
        raise ValueError("up/azimuth/elevation turn the default view: give them with "
                         "view=None (a view dict's own up turns it too)")
    if up is None:
        up = scene.info["up"]
    if up not in _UP_AXES:
        raise ValueError(f"up: {up!r}, expected x, y or z")
    err = L.Error()
    _check(L.lib().oit_offscreen_default_view(
        scene._handle(), _UP_AXES[up], float(0.0 if azimuth is None else azimuth),
        float(20.0 if elevation is None else elevation), ctypes.byref(v), ctypes.byref(err)), err)


_renderers = {}


def _default_renderer(shading, colour_space="srgb", capture="auto", see_through=False):
    """One Renderer a shading, colour space, capture and see_through for the
    module-level functions, made at first use."""
    key = (shading, colour_space, capture, int(see_through))
    r = _renderers.get(key)
    if r is None or not r._h:
        r = _renderers[key] = Renderer(shading=shading, colour_space=colour_space,
                                       capture=capture, see_through=see_through)
    return r


def render(model_path, size=(512, 512), view=None, dtype=np.uint8, background=None,
           shading="transparent", colour_space="srgb", clip=None, up=None, azimuth=None,
           elevation=None, capture="auto", see_through=False):
    """Renders a mesh file (in core) or part file (streamed) into a
    (height, width, 4) array; see Renderer.render for view, background, up,
    azimuth, elevation and clip (section planes), and Renderer for shading,
    colour_space and see_through (True: opaque materials drawn with the
    default alpha too). capture: how a part file's K-slot fills are made,
    "auto" (default: "stencil" where its self-test passes on this driver,
    else "array"), "stencil", "array" or "compute" (Renderer says what each
    does); the same image whichever."""
    r = _default_renderer(shading, colour_space, capture, see_through)
    with Scene.open(model_path) as s:
        return r.render(s, size=size, view=view, dtype=dtype, background=background, up=up,
                        azimuth=azimuth, elevation=elevation, clip=clip)


def render_arrays(positions, indices=None, colours=None, size=(512, 512), view=None,
                  dtype=np.uint8, background=None, shading="transparent", colour_rate="auto",
                  colour_space="srgb", clip=None, up=None, azimuth=None, elevation=None,
                  see_through=False):
    """Renders triangles from arrays (see Scene.from_arrays) into a
    (height, width, 4) array; see Renderer.render for view, background, up,
    azimuth and elevation, Renderer for colour_space and see_through; clip:
    section planes."""
    r = _default_renderer(shading, colour_space, see_through=see_through)
    with Scene.from_arrays(positions, indices, colours, colour_rate=colour_rate) as s:
        return r.render(s, size=size, view=view, dtype=dtype, background=background, up=up,
                        azimuth=azimuth, elevation=elevation, clip=clip)


def prep_tool():
    """The oitprep executable prep() runs: OIT_PREP, else the one installed
    beside liboit (PREFIX/bin), else oitprep on PATH."""
    env = os.environ.get("OIT_PREP")
    if env:
        return env
    try:
        from . import _install_paths
        here = os.path.dirname(os.path.abspath(__file__))
        cand = os.path.normpath(os.path.join(here, _install_paths.BINDIR, "oitprep"))
        if os.access(cand, os.X_OK):
            return cand
    except ImportError:
        pass
    found = shutil.which("oitprep")
    if found:
        return found
    raise FileNotFoundError("oit.prep: no oitprep found: set OIT_PREP to the tool (e.g. "
                            "build/bin/oitprep), install liboit with its tools, or put "
                            "oitprep on PATH")


def prep(src, dst, **options):
    """Converts a mesh file into a part file by running oitprep (liboit has
    no conversion entry: the converter is the tool's, with its thread pool
    and CGAL predicates). Options become oitprep's flags: K=8 or
    max_layers=8 -> --max-layers 8, part_triangles=24 -> --part-triangles
    24, threads=2 -> --threads 2; True alone for a flag without a value.
    Raises OitError with the tool's message when it fails; returns dst."""
    cmd = [prep_tool(), os.fspath(src), "-o", os.fspath(dst)]
    for key, value in options.items():
        flag = "--max-layers" if key == "K" else "--" + key.replace("_", "-")
        if value is True:
            cmd.append(flag)
        elif value is not False and value is not None:
            cmd += [flag, str(value)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        msg = (p.stderr.strip() or p.stdout.strip()).splitlines()
        raise OitError(f"oitprep exit {p.returncode}", msg[-1] if msg else "failed")
    return dst
