"""Renderer.stats in Python terms (names as str, not bytes) and the
docstrings in Python's names: every value an option takes, from the
package's own tables (checked against C by tests/python/check_layout.py),
and stats["x"], not the tools' flags, for the figures.

Run with the build's library: OIT_LIBRARY=build/lib/liboit.so
"""
import ctypes
import os
import re

import oit
from oit import _lib as L
from test_capture import part_file  # noqa: F401 (a fixture)
from test_clip import FRONT, two_squares

HERE = os.path.dirname(os.path.abspath(__file__))
README = os.path.join(HERE, "..", "..", "README.md")
# oit_draw_stats' strings (const char *): str in Python, None where NULL
NAMES = [n for n, t in L.DrawStats._fields_ if t is ctypes.c_char_p]


def check_strings(stats):
    assert NAMES and set(NAMES) <= set(stats)
    for n in NAMES:
        assert stats[n] is None or isinstance(stats[n], str), (n, stats[n])


def test_stats_names_are_str(part_file):  # noqa: F811
    pos, idx, col = two_squares()
    with oit.Renderer(method="dfb") as r, oit.Scene.from_arrays(pos, idx, col) as s:
        r.render(s, size=(32, 32), view=FRONT)
        check_strings(r.stats)
        assert r.stats["method"] == "dfb" and r.stats["device"]
    with oit.Renderer(capture="array", pack="disjoint") as r, oit.Scene.open(part_file) as s:
        r.render(s, size=(32, 32), view=FRONT)
        check_strings(r.stats)
        assert r.stats["method"] == "stream"
        assert r.stats["capture_asked"] == "array" and r.stats["capture_slots"] == "array"


def quoted(values, doc):
    """The values doc does not name, each in quotes."""
    return [v for v in values if f'"{v}"' not in doc]


def test_docstrings_name_every_value():
    init, render = oit.Renderer.__init__.__doc__, oit.render.__doc__
    assert not quoted(L.CAPTURES, init), "Renderer: capture values"
    assert not quoted(L.CAPTURES, render), "oit.render: capture values"
    assert not quoted(L.PACKS, init), "Renderer: pack values"
    assert not quoted(L.COLOUR_SPACES, init), "Renderer: colour_space values"
    assert not quoted(oit._SHADINGS, init), "Renderer: shading values"
    assert not quoted(L.UP_AXES, oit.Renderer.render.__doc__), "render: up values"


def test_docstrings_say_stats_not_flags():
    docs = [oit.__doc__, oit.Renderer.__doc__, oit.Renderer.__init__.__doc__,
            oit.Renderer.render.__doc__, oit.Renderer.desc.__doc__, oit.render.__doc__,
            oit.render_arrays.__doc__]
    for d in docs:
        assert "--stats" not in d, d
    # the figures a Renderer keeps are described where a user looks
    assert 'stats["method"]' in oit.Renderer.__doc__ and "str" in oit.Renderer.__doc__


def test_readme_python_section_documents_capture():
    text = open(README).read()
    section = re.search(r"^### Python\n(.*?)^### ", text, re.S | re.M).group(1)
    assert "capture=" in section
    assert not quoted(L.CAPTURES, section), "README's Python section: capture values"
    assert "--stats" not in section
