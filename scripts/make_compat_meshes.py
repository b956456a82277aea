#!/usr/bin/env python3
"""Write the meshes of caustica's shape compatibility scenes (tests/compat/scenes/meshes):
a coarse sphere as OBJ (no normals: Mitsuba and caustica compute vertex normals) and as binary PLY
with analytic normals, so that face_normals and flip_normals change the image visibly.
The .serialized mesh of the same scenes is written by scripts/make_serialized.py.
Usage: python3 scripts/make_compat_meshes.py
"""
import os
import struct

from make_serialized import ROOT, uv_sphere

OUT = os.path.join(ROOT, 'tests', 'compat', 'scenes', 'meshes')


def write_obj(path, m):
    with open(path, 'w') as fp:
        fp.write('# coarse sphere, no normals (scripts/make_compat_meshes.py)\n')
        for p in m['positions']:
            fp.write('v %.7g %.7g %.7g\n' % p)
        for t in m['triangles']:
            fp.write('f %d %d %d\n' % (t[0] + 1, t[1] + 1, t[2] + 1))


def write_ply(path, m):
    n, f = len(m['positions']), len(m['triangles'])
    head = ('ply\nformat binary_little_endian 1.0\ncomment scripts/make_compat_meshes.py\n'
            'element vertex %d\nproperty float x\nproperty float y\nproperty float z\n'
            'property float nx\nproperty float ny\nproperty float nz\n'
            'element face %d\nproperty list uchar int vertex_indices\nend_header\n' % (n, f))
    with open(path, 'wb') as fp:
        fp.write(head.encode('ascii'))
        for p, nn in zip(m['positions'], m['normals']):
            fp.write(struct.pack('<6f', *p, *nn))
        for t in m['triangles']:
            fp.write(struct.pack('<B3i', 3, *t))


def main():
    os.makedirs(OUT, exist_ok=True)
    m = uv_sphere(rings=8, segments=12)
    write_obj(os.path.join(OUT, 'coarse_sphere.obj'), m)
    write_ply(os.path.join(OUT, 'coarse_sphere.ply'), m)
    print('wrote', OUT)


if __name__ == '__main__':
    main()
