#!/usr/bin/env python3
"""A reference image from caustica's own path tracer, for error-against-time comparisons at sizes
that have no Mitsuba reference: N independent renders (seeds S..S+N-1) of SPP samples per pixel,
their mean as REF.pfm and the per-pixel variance of that mean (the sample variance across the
batches divided by N) as REF.var.pfm, which bench/converge.py finds beside REF.pfm and uses to
remove the reference's own noise from the error.

The path tracer agrees with Mitsuba 3 on the bundled scenes (tests/e2e), and its error against
its own long render is independent noise, so such a reference is fair to every integrator.
Batches already rendered (BATCHDIR/batch-SEED.pfm) are reused, so an interrupted run resumes.

Example (cornell-water at 256x256, 8 x 1024 spp: about 16 minutes on 2 cores):
  bench/make_reference.py scenes/cornell-water/scene.xml --res 256x256 --spp 1024 --batches 8 \\
      --first-seed 2001 -o out/ref256.pfm
"""
import argparse
import array
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..'))


def read_pfm(path):
    with open(path, 'rb') as f:
        if f.readline().strip() != b'PF':
            sys.exit('%s: not an RGB PFM' % path)
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = array.array('f')
        data.frombytes(f.read(width * height * 12))
    if (scale < 0) != (sys.byteorder == 'little'):
        data.byteswap()
    return width, height, data


def write_pfm(path, width, height, values):
    data = array.array('f', values)
    with open(path, 'wb') as f:
        f.write(b'PF\n%d %d\n%s\n' % (width, height, b'-1.0' if sys.byteorder == 'little' else b'1.0'))
        f.write(data.tobytes())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('scene')
    ap.add_argument('-o', '--output', required=True, help='REF.pfm (REF.var.pfm is written beside it)')
    ap.add_argument('--res', required=True, help='WIDTHxHEIGHT')
    ap.add_argument('--spp', type=int, default=1024, help='samples per pixel of each batch')
    ap.add_argument('--batches', type=int, default=8)
    ap.add_argument('--first-seed', type=int, default=1001)
    ap.add_argument('--batch-dir', help='where the batches are kept (default: REF.batches/)')
    ap.add_argument('--caustica', default=os.path.join(ROOT, 'build', 'caustica'))
    a = ap.parse_args()
    if not a.output.endswith('.pfm'):
        sys.exit('the reference is written as PFM: name it REF.pfm')
    if a.batches < 2:
        sys.exit('at least 2 batches are needed for a variance')
    batch_dir = a.batch_dir or a.output[:-4] + '.batches'
    os.makedirs(batch_dir, exist_ok=True)
    images = []
    for b in range(a.batches):
        seed = a.first_seed + b
        path = os.path.join(batch_dir, 'batch-%d.pfm' % seed)
        if not os.path.exists(path):
            tmp = path[:-4] + '.tmp.pfm'
            cmd = [a.caustica, 'render', a.scene, '--res', a.res, '--spp', str(a.spp), '--seed', str(seed),
                   '--integrator', 'path', '-q', '--checkpoint-every', '0', '-o', tmp]
            p = subprocess.run(cmd, capture_output=True, text=True)
            if p.returncode != 0:
                sys.exit('failed (%d): %s\n%s' % (p.returncode, ' '.join(cmd), p.stderr.strip()))
            os.replace(tmp, path)
        print('batch %d/%d (seed %d)' % (b + 1, a.batches, seed), flush=True)
        images.append(read_pfm(path))
    width, height = images[0][0], images[0][1]
    if any((w, h) != (width, height) for w, h, _ in images):
        sys.exit('%s: batches of different sizes' % batch_dir)
    n = len(images)
    values = len(images[0][2])
    mean = [sum(img[2][i] for img in images) / n for i in range(values)]
    var = [sum((img[2][i] - mean[i]) ** 2 for img in images) / (n - 1) / n for i in range(values)]
    write_pfm(a.output, width, height, mean)
    write_pfm(a.output[:-4] + '.var.pfm', width, height, var)
    print('wrote %s and %s (%d x %d spp)' % (a.output, a.output[:-4] + '.var.pfm', n, a.spp))


if __name__ == '__main__':
    main()
