#!/usr/bin/env python3
"""Rewrites an oitgen PLY (float x y z, uchar r g b a; triangles) without its
alpha property, so that oitstream/oitbench --alpha sets one alpha for the
whole scene. Usage: strip_alpha.py IN.ply OUT.ply"""
import struct
import sys

src, dst = sys.argv[1], sys.argv[2]
data = open(src, 'rb').read()
end = data.index(b'end_header\n') + len(b'end_header\n')
header = data[:end].decode('ascii').splitlines()
nv = int(next(l for l in header if l.startswith('element vertex')).split()[2])
nf = int(next(l for l in header if l.startswith('element face')).split()[2])
body = data[end:]
verts = [struct.unpack_from('<fffBBBB', body, 16 * i)[:6] for i in range(nv)]
faces = body[16 * nv:]
out = ['ply', 'format binary_little_endian 1.0', 'element vertex %d' % nv,
       'property float x', 'property float y', 'property float z',
       'property uchar red', 'property uchar green', 'property uchar blue',
       'element face %d' % nf, 'property list uchar int vertex_indices', 'end_header']
with open(dst, 'wb') as f:
    f.write(('\n'.join(out) + '\n').encode('ascii'))
    for v in verts:
        f.write(struct.pack('<fffBBB', *v))
    f.write(faces)
