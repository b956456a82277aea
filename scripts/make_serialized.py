#!/usr/bin/env python3
"""Write Mitsuba `.serialized` mesh files: the test data of caustica's serialized loader.

Mitsuba 3 only reads the format (it writes PLY), so this writes it from the format description in
Mitsuba 3's src/shapes/serialized.cpp: per mesh a little-endian header (uint16 0x041C, uint16
version 3 or 4) and a zlib stream (uint32 flags, version 4: a null-terminated name, uint64 vertex
and triangle counts, positions, normals, uvs, colours, uint32 indices); at the end of the file the
byte offset of every mesh (uint64 in v4, uint32 in v3) and a uint32 mesh count.

Usage: python3 scripts/make_serialized.py   (rewrites every file listed in main())
"""
import math
import os
import struct
import zlib

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
HAS_NORMALS, HAS_UVS, HAS_COLORS, FACE_NORMALS, SINGLE, DOUBLE = 0x1, 0x2, 0x8, 0x10, 0x1000, 0x2000


def mesh_stream(positions, triangles, normals=None, uvs=None, colors=None, name='mesh',
                version=4, double=False, extra_flags=0):
    """The uncompressed payload of one mesh (what follows the 4-byte header)."""
    flags = (DOUBLE if double else SINGLE) | extra_flags
    flags |= HAS_NORMALS if normals else 0
    flags |= HAS_UVS if uvs else 0
    flags |= HAS_COLORS if colors else 0
    real = 'd' if double else 'f'
    out = struct.pack('<I', flags)
    if version == 4:
        out += name.encode('utf-8') + b'\0'
    out += struct.pack('<QQ', len(positions), len(triangles))
    for arr in (positions, normals, uvs, colors):
        if arr:
            flat = [c for v in arr for c in v]
            out += struct.pack('<%d%s' % (len(flat), real), *flat)
    flat = [i for t in triangles for i in t]
    out += struct.pack('<%dI' % len(flat), *flat)
    return out


def serialized_file(payloads, version=4):
    """Concatenates compressed meshes and appends the end-of-file offset dictionary."""
    data, offsets = b'', []
    for p in payloads:
        offsets.append(len(data))
        data += struct.pack('<HH', 0x041C, version) + zlib.compress(p)
    fmt = '<Q' if version == 4 else '<I'
    for o in offsets:
        data += struct.pack(fmt, o)
    return data + struct.pack('<I', len(payloads))


def quad():
    """[-1, 1]^2 in z = 0 as two triangles, normals +z, uvs in [0, 1]^2."""
    p = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    return dict(positions=p, triangles=[(0, 1, 2), (0, 2, 3)], normals=[(0, 0, 1)] * 4,
                uvs=[((x + 1) / 2, (y + 1) / 2) for x, y, _ in p])


def tetrahedron():
    p = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    return dict(positions=p, triangles=[(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)],
                colors=[(1, 0, 0)] * 4)


def uv_sphere(rings=12, segments=24, smooth=True):
    """A unit sphere of rings x segments quads with (optionally) its analytic normals."""
    pos, nrm, uv, tri = [], [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments + 1):
            ph = 2 * math.pi * j / segments
            v = (math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th))
            pos.append(v)
            nrm.append(v)
            uv.append((j / segments, i / rings))
    w = segments + 1
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = i * w + j, i * w + j + 1, (i + 1) * w + j + 1, (i + 1) * w + j
            if i > 0:
                tri.append((a, d, b))
            if i < rings - 1:
                tri.append((b, d, c))
    m = dict(positions=pos, triangles=tri, uvs=uv)
    if smooth:
        m['normals'] = nrm
    return m


def torus(R=1.0, r=0.4, n=24, m=12):
    """A torus around z without normals (the loader computes Mitsuba's vertex normals)."""
    pos, tri = [], []
    for i in range(n):
        u = 2 * math.pi * i / n
        for j in range(m):
            v = 2 * math.pi * j / m
            pos.append(((R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u),
                        r * math.sin(v)))
    for i in range(n):
        for j in range(m):
            a, b = i * m + j, ((i + 1) % n) * m + j
            c, d = ((i + 1) % n) * m + (j + 1) % m, i * m + (j + 1) % m
            tri += [(a, b, c), (a, c, d)]
    return dict(positions=pos, triangles=tri)


def write(rel, data):
    path = os.path.join(ROOT, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'wb') as fp:
        fp.write(data)
    print('%s: %d bytes' % (rel, len(data)))


def main():
    io = 'tests/io/data/serialized/'
    write(io + 'two_meshes_v4.serialized', serialized_file([
        mesh_stream(name='quad', **quad()),
        mesh_stream(name='tetra', double=True, **tetrahedron())]))
    write(io + 'two_meshes_v3.serialized', serialized_file([
        mesh_stream(version=3, **quad()),
        mesh_stream(version=3, double=True, **tetrahedron())], version=3))
    write(io + 'face_normals_flag.serialized', serialized_file([
        mesh_stream(name='quad', extra_flags=FACE_NORMALS, **quad())]))
    write('tests/compat/scenes/meshes/sphere_torus.serialized', serialized_file([
        mesh_stream(name='sphere', **uv_sphere()),
        mesh_stream(name='torus', double=True, **torus())]))

    # Malformed files for tests/io/data/bad (one defect each).
    bad = 'tests/io/data/bad/parts/'
    good = serialized_file([mesh_stream(**quad())])
    write(bad + 'bad_magic.serialized', b'\x1d\x04' + good[2:])
    write(bad + 'bad_version.serialized', good[:2] + b'\x05\x00' + good[4:])
    write(bad + 'truncated.serialized', good[:40])
    write(bad + 'corrupt.serialized', good[:4] + b'\x78\x9c' + bytes(range(7, 90)))
    q = quad()
    q['triangles'] = [(0, 1, 2), (0, 2, 7)]
    write(bad + 'index_out_of_range.serialized', serialized_file([mesh_stream(**q)]))
    q = quad()
    q['positions'] = [(-1, -1, 0), (1, float('nan'), 0), (1, 1, 0), (-1, 1, 0)]
    write(bad + 'nan.serialized', serialized_file([mesh_stream(**q)]))
    two = serialized_file([mesh_stream(**quad()), mesh_stream(**tetrahedron())])
    write(bad + 'bad_offset.serialized', two[:-12] + struct.pack('<QI', 1 << 40, 2))


if __name__ == '__main__':
    main()
