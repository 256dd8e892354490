"""ctypes declarations of liboit (include/oit/liboit.h, include/oit/offscreen.h).

The structures mirror the C headers field by field; keep them in step.
The library is found, in this order, through:

1. the environment variable OIT_LIBRARY: the path of liboit.so (or of the
   folder holding it), e.g. build/lib/liboit.so of a build tree;
2. the library installed beside this package by `cmake --install`
   (_install_paths.py, written at install time, says where, relative to
   this folder);
3. the system's loader search (ctypes.util.find_library("oit"),
   LD_LIBRARY_PATH, ldconfig).
"""
import ctypes
import ctypes.util
import os

# ---- structures -----------------------------------------------------------


class Error(ctypes.Structure):
    _fields_ = [("status", ctypes.c_int), ("message", ctypes.c_char * 512)]


class SceneDesc(ctypes.Structure):
    _fields_ = [("defer_validation", ctypes.c_int), ("share_count", ctypes.c_uint32),
                ("share_index", ctypes.c_uint32)]


class SceneInfo(ctypes.Structure):
    _fields_ = [("triangles", ctypes.c_uint64), ("parts", ctypes.c_uint64),
                ("bounds_min", ctypes.c_float * 3), ("bounds_max", ctypes.c_float * 3),
                ("K", ctypes.c_uint32), ("attributes", ctypes.c_uint32),
                ("origin", ctypes.c_double * 3), ("in_core", ctypes.c_uint32),
                ("share_count", ctypes.c_uint32), ("share_index", ctypes.c_uint32),
                ("share_parts", ctypes.c_uint64), ("share_triangles", ctypes.c_uint64),
                ("up_axis", ctypes.c_uint32)]


class SceneMeshDesc(ctypes.Structure):
    _fields_ = [("positions", ctypes.c_void_p), ("vertex_count", ctypes.c_uint64),
                ("indices", ctypes.c_void_p), ("index_count", ctypes.c_uint64),
                ("colours", ctypes.c_void_p), ("colour_type", ctypes.c_int),
                ("colour_rate", ctypes.c_int), ("name", ctypes.c_char_p)]


class RenderShading(ctypes.Structure):
    _fields_ = [("mode", ctypes.c_int), ("alpha", ctypes.c_float),
                ("default_rgb", ctypes.c_float * 3), ("absorption", ctypes.c_float),
                ("scene_scale", ctypes.c_float), ("colour_space", ctypes.c_int)]


class RendererDesc(ctypes.Structure):
    _fields_ = [("method", ctypes.c_char_p), ("ambiguity_px", ctypes.c_float),
                ("shading", RenderShading), ("see_through", ctypes.c_int),
                ("epsilon", ctypes.c_float),
                ("K", ctypes.c_uint32), ("pack", ctypes.c_int), ("schedule", ctypes.c_int),
                ("capture", ctypes.c_int), ("frames", ctypes.c_uint32),
                ("gpu_budget", ctypes.c_uint64), ("upload_budget", ctypes.c_uint64),
                ("cache_budget", ctypes.c_uint64), ("slot_budget", ctypes.c_uint64),
                ("store_budget", ctypes.c_uint64), ("binding_limit", ctypes.c_uint64),
                ("reader_threads", ctypes.c_uint32), ("read_on_draw_thread", ctypes.c_int),
                ("program_cache", ctypes.c_char_p)]


class RenderMethodInfo(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("flags", ctypes.c_uint32)]


class OffscreenDesc(ctypes.Structure):
    _fields_ = [("renderer", RendererDesc)]


class OffscreenView(ctypes.Structure):
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int),
                ("format", ctypes.c_int), ("use_matrices", ctypes.c_int),
                ("view", ctypes.c_float * 16), ("projection", ctypes.c_float * 16),
                ("eye", ctypes.c_float * 3), ("target", ctypes.c_float * 3),
                ("up", ctypes.c_float * 3), ("fovy_deg", ctypes.c_float),
                ("znear", ctypes.c_float), ("zfar", ctypes.c_float),
                ("background", ctypes.c_float * 4),
                ("clip_count", ctypes.c_uint32), ("clip", (ctypes.c_float * 4) * 6)]


class PickLayer(ctypes.Structure):
    _fields_ = [("depth", ctypes.c_double), ("point", ctypes.c_double * 3),
                ("colour", ctypes.c_float * 3),
                ("alpha", ctypes.c_float), ("transmittance", ctypes.c_float * 3),
                ("front", ctypes.c_int), ("part", ctypes.c_uint32),
                ("source_triangle", ctypes.c_uint64), ("group", ctypes.c_char_p),
                ("material", ctypes.c_char_p)]


PICK_NO_PART = 0xFFFFFFFF


class DrawStats(ctypes.Structure):
    _fields_ = [("draw", ctypes.c_uint64), ("ms", ctypes.c_double),
                ("method", ctypes.c_char_p), ("device", ctypes.c_char_p),
                ("gpu_frame", ctypes.c_uint64), ("gpu_ms", ctypes.c_double),
                ("gpu_phase_ms", ctypes.c_double * 8), ("host_waits", ctypes.c_uint32),
                ("redraws", ctypes.c_uint32), ("fragments", ctypes.c_uint64),
                ("max_layers", ctypes.c_uint32), ("fragments_saturated", ctypes.c_uint64),
                ("overflow_pixels", ctypes.c_uint64),
                ("deep_pixels", ctypes.c_uint64), ("second_pass_pixels", ctypes.c_uint64),
                ("second_pass_packs", ctypes.c_uint32), ("parts_drawn", ctypes.c_uint64),
                ("parts_culled", ctypes.c_uint64), ("parts_skipped", ctypes.c_uint64),
                ("parts_clipped", ctypes.c_uint64), ("bytes_clipped", ctypes.c_uint64),
                ("bytes_uploaded", ctypes.c_uint64), ("cache_hits", ctypes.c_uint64),
                ("cache_bytes", ctypes.c_uint64), ("draw_calls", ctypes.c_uint64),
                ("reader_threads", ctypes.c_uint32), ("resident", ctypes.c_uint32),
                ("packs", ctypes.c_uint32), ("batches", ctypes.c_uint32),
                ("predicted_batches", ctypes.c_uint32), ("capture", ctypes.c_char_p),
                ("capture_k", ctypes.c_uint32), ("capture_asked", ctypes.c_char_p),
                ("capture_slots", ctypes.c_char_p), ("capture_slots_k", ctypes.c_uint32),
                ("capture_fallback", ctypes.c_char_p), ("order_ms", ctypes.c_double),
                ("pack_ms", ctypes.c_double), ("auto_first_k", ctypes.c_uint32),
                ("front_first", ctypes.c_uint32), ("choice", ctypes.c_char_p),
                ("choice_why", ctypes.c_char_p), ("choice_first_k_ms", ctypes.c_double),
                ("choice_counted_ms", ctypes.c_double), ("gpu_bytes_peak", ctypes.c_uint64),
                ("gpu_mesh_bytes", ctypes.c_uint64),
                ("gpu_budget", ctypes.c_uint64), ("ring_budget", ctypes.c_uint64),
                ("cache_budget", ctypes.c_uint64), ("capture_budget", ctypes.c_uint64),
                ("store_budget", ctypes.c_uint64), ("gpu_free_bytes", ctypes.c_uint64),
                ("budget_source", ctypes.c_char_p), ("see_through", ctypes.c_uint32),
                ("opaque", ctypes.c_uint32)]


# enum values of the headers
OIT_OK = 0
COLOUR_UINT8, COLOUR_FLOAT = 0, 1
COLOUR_PER_VERTEX, COLOUR_PER_TRIANGLE = 0, 1
PIXELS_RGBA8, PIXELS_RGBA32F = 0, 1
RENDER_TRANSPARENT, RENDER_TRANSLUCENT = 0, 1
RENDER_CACHE_OFF = 2**64 - 1
ATTR_COLOUR, ATTR_ALPHA = 1, 2
# The modes by the tools' spelling of their values; ENUMS gives each one's
# C prefix (the C name: prefix + the key upper-cased, "-" dropped), which
# tests/python/check_layout.py holds to the C compiler's values.
PACKS = {"auto": 0, "counted": 1, "budget": 2, "disjoint": 3, "first-k": 4}
CAPTURES = {"auto": 0, "array": 1, "stencil": 2, "compute": 5}
COLOUR_SPACES = {"srgb": 0, "linear": 1}
UP_AXES = {"y": 0, "z": 1, "x": 2}
ENUMS = {"PACKS": "OIT_RENDER_PACK_", "CAPTURES": "OIT_RENDER_CAPTURE_",
         "COLOUR_SPACES": "OIT_RENDER_COLOUR_", "UP_AXES": "OIT_UP_"}


class LibraryNotFound(OSError):
    """liboit.so could not be loaded from any of the places tried."""


def _candidates():
    """(how, path) pairs in the order they are tried."""
    out = []
    env = os.environ.get("OIT_LIBRARY")
    if env:
        path = os.path.join(env, "liboit.so") if os.path.isdir(env) else env
        out.append(("OIT_LIBRARY", path))
    try:
        from . import _install_paths  # written by cmake --install
        here = os.path.dirname(os.path.abspath(__file__))
        out.append(("installed", os.path.normpath(
            os.path.join(here, _install_paths.LIBDIR, "liboit.so"))))
    except ImportError:
        pass
    found = ctypes.util.find_library("oit")
    out.append(("system", found or "liboit.so"))
    return out


def _declare(lib):
    P = ctypes.POINTER
    vp, err = ctypes.c_void_p, P(Error)
    sigs = {
        "oit_scene_open": (ctypes.c_int, [ctypes.c_char_p, P(SceneDesc), P(vp), err]),
        "oit_scene_create_mesh": (ctypes.c_int, [P(SceneMeshDesc), P(vp), err]),
        "oit_scene_get_info": (ctypes.c_int, [vp, P(SceneInfo), err]),
        "oit_scene_close": (None, [vp]),
        "oit_offscreen_create": (ctypes.c_int, [P(OffscreenDesc), P(vp), err]),
        "oit_offscreen_destroy": (None, [vp]),
        "oit_offscreen_release_scene": (None, [vp, vp]),
        "oit_offscreen_gl_renderer": (ctypes.c_char_p, [vp]),
        "oit_offscreen_get_desc": (None, [vp, P(OffscreenDesc)]),
        "oit_offscreen_render": (ctypes.c_int, [vp, vp, P(OffscreenView), vp, ctypes.c_size_t,
                                                P(DrawStats), err]),
        "oit_offscreen_pick": (ctypes.c_int, [vp, vp, P(OffscreenView), ctypes.c_int,
                                              ctypes.c_int, P(PickLayer), ctypes.c_size_t,
                                              P(ctypes.c_size_t), err]),
        "oit_offscreen_default_view": (ctypes.c_int, [vp, ctypes.c_int, ctypes.c_float,
                                                      ctypes.c_float, P(OffscreenView), err]),
        "oit_status_name": (ctypes.c_char_p, [ctypes.c_int]),
        "oit_render_methods": (P(RenderMethodInfo), [P(ctypes.c_uint32)]),
    }
    for name, (res, args) in sigs.items():
        fn = getattr(lib, name)
        fn.restype = res
        fn.argtypes = args
    return lib


_lib = None
_lib_path = None


def lib():
    """The loaded liboit (ctypes.CDLL); raises LibraryNotFound naming every
    place tried."""
    global _lib, _lib_path
    if _lib is not None:
        return _lib
    tried = []
    for how, path in _candidates():
        try:
            loaded = ctypes.CDLL(path)
        except OSError as e:
            tried.append(f"  {how}: {path}: {e}")
            continue
        _lib, _lib_path = _declare(loaded), path
        return _lib
    raise LibraryNotFound(
        "oit: cannot load liboit.so; tried:\n" + "\n".join(tried) +
        "\nset OIT_LIBRARY to the library (e.g. build/lib/liboit.so) or install liboit "
        "(cmake --install BUILD --prefix PREFIX)")


def lib_path():
    """The path liboit was loaded from (loads it if needed)."""
    lib()
    return _lib_path
