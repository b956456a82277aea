#!/usr/bin/env python3
"""Generate the closed water volume of scenes/cornell-water as a binary PLY.

The water is ONE closed, watertight triangle mesh that fills the lower part of the
Mitsuba-style Cornell box ([-1, 1]^3, floor at y = -1, open at z = +1):

  * a wavy top surface: a height field y = level + sum of a few directional sine waves
    (phases drawn from a seeded Mersenne Twister, so the output is deterministic),
    sampled on an N x N grid, with smooth analytic vertex normals;
  * four vertical side walls, each a strip between the wavy top edge and the flat bottom edge;
  * a flat bottom (a triangle fan around its centre).

No face of the water is coplanar with a wall of the box: its faces are offset by `--gap`
(default 2e-3, i.e. 1e-3 of the box size 2). By default (`--placement submerged`) the water's
left, right, back and bottom faces lie `gap` OUTSIDE the red, green, back walls and the floor, so
those walls are submerged in the water (water touching them, as in a real tank); only the front
face (z = 1 - gap, the open side of the box, facing the camera) is inside. This matters: with an
air film between the water and the floor or walls (`--placement inset`, every face `gap` inside
the box), light in the water hitting the film beyond the critical angle (48.75 deg) is totally
internally reflected, so the floor is invisible from the Cornell-box camera (its rays run nearly
horizontally in the water) and the walls below the surface receive almost no light.

Vertices along the rim between the top and the side walls (and between the side walls and the
bottom) are duplicated so that each part carries its own normals (smooth on the top, flat on
walls and bottom); the copies are bitwise identical float32 positions, so the mesh is closed
and watertight once vertices are welded by position: every edge is shared by exactly two
triangles with opposite orientation, and there are no T-junctions. All faces wind
counter-clockwise seen from outside (outward geometric normals, matching the vertex normals),
as Mitsuba's dielectric expects (int_ior inside).

Output: binary little-endian PLY, vertex x y z nx ny nz (float32), face list uchar int
vertex_indices. At the default resolution (160) the file is about 1.3 MB.

Usage:  python3 scripts/make_water_surface.py [--res 160] [--seed 7] [--out PATH]
"""
import argparse
import math
import os
import random
import struct
import sys

BOX = 1.0  # half size of the Cornell box


def make_waves(seed, amp_scale, freq_scale):
    """A fixed table of waves (wavelength, amplitude, direction in degrees); the seed only
    perturbs the directions slightly and picks the phases."""
    rng = random.Random(seed)
    # (wavelength, amplitude, direction degrees). Curvature A*k^2 of the strongest waves is 2-4 /
    # unit and their sum reaches ~18, so crests act as lenses (focal length ~ 4 / curvature for
    # water) focusing between the surface and the floor 0.8 below it: a network of caustic lines
    # with cells about 0.4-0.6 wide on the floor.
    table = [
        (0.62, 0.0240, 20.0),
        (0.47, 0.0170, 115.0),
        (0.35, 0.0100, 60.0),
        (0.29, 0.0068, 165.0),
        (0.23, 0.0042, 250.0),
        (0.19, 0.0026, 300.0),
    ]
    waves = []
    for lam, amp, deg in table:
        deg += rng.uniform(-10.0, 10.0)
        phase = rng.uniform(0.0, 2.0 * math.pi)
        k = 2.0 * math.pi / (lam / freq_scale)
        th = math.radians(deg)
        waves.append((amp * amp_scale, k * math.cos(th), k * math.sin(th), phase))
    return waves


def height(waves, level, x, z):
    """Height and its gradient (dh/dx, dh/dz) at (x, z)."""
    h, hx, hz = level, 0.0, 0.0
    for a, kx, kz, ph in waves:
        arg = kx * x + kz * z + ph
        s, c = math.sin(arg), math.cos(arg)
        h += a * s
        hx += a * kx * c
        hz += a * kz * c
    return h, hx, hz


def f32(v):
    return struct.unpack('<f', struct.pack('<f', v))[0]


def build(res, seed, level, gap, amp_scale, freq_scale, placement):
    waves = make_waves(seed, amp_scale, freq_scale)
    if placement == 'submerged':   # walls and floor inside the water, front face inside the box
        x0, x1, z0, z1, y_bot = -BOX - gap, BOX + gap, -BOX - gap, BOX - gap, -BOX - gap
    else:                          # 'inset': the whole volume inside the box, air film all around
        x0, x1, z0, z1, y_bot = -BOX + gap, BOX - gap, -BOX + gap, BOX - gap, -BOX + gap
    y_bot = f32(y_bot)
    xs = [f32(x0 + (x1 - x0) * i / (res - 1)) for i in range(res)]
    zs = [f32(z0 + (z1 - z0) * j / (res - 1)) for j in range(res)]
    xs[0], xs[-1], zs[0], zs[-1] = f32(x0), f32(x1), f32(z0), f32(z1)

    verts = []  # (x, y, z, nx, ny, nz)
    faces = []

    # ---- top: grid vertex (i, j) at x = xs[i], z = zs[j]
    top_h = [[0.0] * res for _ in range(res)]
    for i in range(res):
        x = xs[i]
        for j in range(res):
            z = zs[j]
            h, hx, hz = height(waves, level, x, z)
            h = f32(h)
            top_h[i][j] = h
            nx, ny, nz = -hx, 1.0, -hz
            inv = 1.0 / math.sqrt(nx * nx + ny * ny + nz * nz)
            verts.append((x, h, z, nx * inv, ny * inv, nz * inv))

    def tid(i, j):
        return i * res + j

    for i in range(res - 1):
        for j in range(res - 1):
            a, b, c, d = tid(i, j), tid(i, j + 1), tid(i + 1, j), tid(i + 1, j + 1)
            # (a, b, c): cross((0,*,dz), (dx,*,0)) has +y -> outward (up). Alternate the diagonal
            # so the triangulation has no directional bias.
            if (i + j) % 2 == 0:
                faces.append((a, b, c))
                faces.append((b, d, c))
            else:
                faces.append((a, b, d))
                faces.append((a, d, c))

    # ---- side walls: strips between the top rim and the bottom rim (flat normals)
    # Each wall is described by the list of rim (x, z) points in order and its outward normal.
    walls = [
        ([(xs[0], zs[j]) for j in range(res)], [(0, j) for j in range(res)], (-1.0, 0.0, 0.0)),
        ([(xs[-1], zs[j]) for j in range(res)], [(res - 1, j) for j in range(res)], (1.0, 0.0, 0.0)),
        ([(xs[i], zs[0]) for i in range(res)], [(i, 0) for i in range(res)], (0.0, 0.0, -1.0)),
        ([(xs[i], zs[-1]) for i in range(res)], [(i, res - 1) for i in range(res)], (0.0, 0.0, 1.0)),
    ]
    for pts, ij, n in walls:
        base = len(verts)
        for (x, z), (i, j) in zip(pts, ij):
            verts.append((x, top_h[i][j], z) + n)
        for (x, z) in pts:
            verts.append((x, y_bot, z) + n)
        tops = list(range(base, base + res))
        bots = list(range(base + res, base + 2 * res))
        for k in range(res - 1):
            quad = (tops[k], tops[k + 1], bots[k + 1], bots[k])
            faces.append((quad[0], quad[1], quad[2]))
            faces.append((quad[0], quad[2], quad[3]))
        # fix the winding afterwards (see orient below)

    # ---- bottom: fan around the centre over the rim (flat normal -y), no T-junctions
    base = len(verts)
    ring = []
    for j in range(res):            # x = lo edge, z increasing
        ring.append((xs[0], zs[j]))
    for i in range(1, res):         # z = hi edge, x increasing
        ring.append((xs[i], zs[-1]))
    for j in range(res - 2, -1, -1):  # x = hi edge, z decreasing
        ring.append((xs[-1], zs[j]))
    for i in range(res - 2, 0, -1):   # z = lo edge, x decreasing
        ring.append((xs[i], zs[0]))
    for (x, z) in ring:
        verts.append((x, y_bot, z, 0.0, -1.0, 0.0))
    centre = len(verts)
    verts.append((f32(0.5 * (x0 + x1)), y_bot, f32(0.5 * (z0 + z1)), 0.0, -1.0, 0.0))
    m = len(ring)
    for k in range(m):
        faces.append((centre, base + k, base + (k + 1) % m))

    # Orient every face so its geometric normal agrees with its vertex normals (all outward).
    out = []
    for f in faces:
        p = [verts[v] for v in f]
        e1 = [p[1][t] - p[0][t] for t in range(3)]
        e2 = [p[2][t] - p[0][t] for t in range(3)]
        cr = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
        nsum = [sum(q[3 + t] for q in p) for t in range(3)]
        if cr[0] * nsum[0] + cr[1] * nsum[1] + cr[2] * nsum[2] < 0.0:
            f = (f[0], f[2], f[1])
        out.append(f)
    return verts, out, waves


def check_closed(verts, faces):
    """Weld by position; every directed edge must appear once and its reverse once."""
    key = {}
    remap = []
    for v in verts:
        k = (v[0], v[1], v[2])
        remap.append(key.setdefault(k, len(key)))
    directed = {}
    for f in faces:
        w = [remap[v] for v in f]
        if len(set(w)) < 3:
            return 'degenerate face %r' % (f,)
        for a, b in ((w[0], w[1]), (w[1], w[2]), (w[2], w[0])):
            directed[(a, b)] = directed.get((a, b), 0) + 1
    for (a, b), n in directed.items():
        if n != 1 or directed.get((b, a), 0) != 1:
            return 'edge (%d, %d) used %d times, reverse %d times' % (a, b, n, directed.get((b, a), 0))
    # signed volume (positive for outward winding)
    vol = 0.0
    for f in faces:
        p0, p1, p2 = (verts[v] for v in f)
        vol += (p0[0] * (p1[1] * p2[2] - p1[2] * p2[1]) - p0[1] * (p1[0] * p2[2] - p1[2] * p2[0])
                + p0[2] * (p1[0] * p2[1] - p1[1] * p2[0])) / 6.0
    if vol <= 0.0:
        return 'negative volume %g' % vol
    return None, len(key), vol


def write_ply(path, verts, faces):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    header = (
        'ply\n'
        'format binary_little_endian 1.0\n'
        'comment caustica cornell-water surface, generated by scripts/make_water_surface.py\n'
        'element vertex %d\n'
        'property float x\nproperty float y\nproperty float z\n'
        'property float nx\nproperty float ny\nproperty float nz\n'
        'element face %d\n'
        'property list uchar int vertex_indices\n'
        'end_header\n' % (len(verts), len(faces)))
    vfmt = struct.Struct('<6f')
    ffmt = struct.Struct('<B3i')
    with open(path, 'wb') as fp:
        fp.write(header.encode('ascii'))
        fp.write(b''.join(vfmt.pack(*v) for v in verts))
        fp.write(b''.join(ffmt.pack(3, *f) for f in faces))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--res', type=int, default=160, help='grid vertices per side of the wavy top (default 160)')
    ap.add_argument('--seed', type=int, default=7, help='seed for wave phases/directions (default 7)')
    ap.add_argument('--level', type=float, default=-0.2,
                    help='mean water height; the box spans y in [-1, 1] (default -0.2: bottom 40%%)')
    ap.add_argument('--gap', type=float, default=2e-3,
                    help='offset of the water faces from the box walls and floor (default 2e-3)')
    ap.add_argument('--placement', choices=('submerged', 'inset'), default='submerged',
                    help='submerged (default): walls and floor inside the water; inset: air film all around')
    ap.add_argument('--amp', type=float, default=1.0, help='scale of all wave amplitudes (default 1)')
    ap.add_argument('--freq', type=float, default=1.0, help='scale of all wave frequencies (default 1)')
    ap.add_argument('--out', default=os.path.join(here, '..', 'scenes', 'cornell-water', 'meshes', 'water.ply'))
    ap.add_argument('--no-check', action='store_true', help='skip the closedness check')
    args = ap.parse_args()
    if args.res < 2:
        sys.exit('--res must be at least 2')

    verts, faces, waves = build(args.res, args.seed, args.level, args.gap, args.amp, args.freq, args.placement)
    if not args.no_check:
        r = check_closed(verts, faces)
        if isinstance(r, str):
            sys.exit('water mesh is not closed: ' + r)
        _, nwelded, vol = r
    write_ply(args.out, verts, faces)
    size = os.path.getsize(args.out)
    curv = sum(a * (kx * kx + kz * kz) for a, kx, kz, _ in waves)
    slope = sum(a * math.hypot(kx, kz) for a, kx, kz, _ in waves)
    print('wrote %s (%s): %d vertices, %d triangles, %.2f MB; max slope <= %.3f, max curvature <= %.2f%s'
          % (os.path.relpath(args.out), args.placement, len(verts), len(faces), size / 1e6, slope, curv,
             '' if args.no_check else '; closed (welded %d vertices), volume %.4f' % (nwelded, vol)))


if __name__ == '__main__':
    main()
