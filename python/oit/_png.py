"""save_png: an RGBA image array to a PNG file with the standard library
alone (zlib), so the package needs nothing beyond numpy."""
import struct
import zlib

import numpy as np


def _chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def save_png(path, image):
    """Writes image, (height, width, 4) or (height, width, 3), uint8 or
    float in 0..1 (rounded as the tools' PNGs are), row 0 at the top, as an
    8-bit RGBA or RGB PNG."""
    img = np.asarray(image)
    if img.ndim != 3 or img.shape[2] not in (3, 4):
        raise ValueError(f"save_png: shape {img.shape}, expected (h, w, 4) or (h, w, 3)")
    if img.dtype != np.uint8:
        img = np.rint(np.nan_to_num(np.clip(img.astype(np.float64), 0.0, 1.0)) * 255.0)
        img = img.astype(np.uint8)
    h, w, c = img.shape
    raw = b"".join(b"\x00" + img[y].tobytes() for y in range(h))
    header = struct.pack(">IIBBBBB", w, h, 8, 6 if c == 4 else 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header) +
                _chunk(b"IDAT", zlib.compress(raw, 6)) + _chunk(b"IEND", b""))
