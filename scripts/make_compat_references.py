#!/usr/bin/env python3
"""Render the Mitsuba 3 references of caustica's compatibility tests (tests/compat).

Each scene tests/compat/scenes/<name>.xml is loaded by Mitsuba 3 (scalar_rgb) with its own
<default>s (32x32, box filter) and rendered as N independent batches (batch b with seed b). It
writes tests/compat/reference/<name>.exr (float32 mean of the batches), <name>.var.exr (per pixel
and channel: unbiased sample variance across the batches divided by N, the variance of the stored
mean) and <name>.json (Mitsuba version, spp, batches, render time). tests/compat/compat_test.cpp
compares caustica's renders with them (tests/common/image_stats.h).

Usage:
  python3 scripts/make_compat_references.py                 # all scenes
  python3 scripts/make_compat_references.py plastic --spp 8192 --batches 16 --threads 2
"""
import argparse
import glob
import json
import math
import os
import platform
import sys
import time

from make_references import batch_mean_variance

HERE = os.path.dirname(os.path.abspath(__file__))
COMPAT = os.path.normpath(os.path.join(HERE, '..', 'tests', 'compat'))


def render(mi, dr, name, spp, batches):
    path = os.path.join(COMPAT, 'scenes', name + '.xml')
    scene = mi.load_file(path)
    if spp % batches:
        sys.exit('--spp must be a multiple of --batches')
    per = spp // batches
    imgs, times = [], []
    for b in range(batches):
        t = time.time()
        img = mi.render(scene, spp=per, seed=b)
        times.append(time.time() - t)
        imgs.append(list(img.array))
        shape = tuple(img.shape)
    h, w, ch = shape
    mean, var = batch_mean_variance(imgs)
    out = os.path.join(COMPAT, 'reference')
    os.makedirs(out, exist_ok=True)
    stem = os.path.join(out, name)
    for values, f in ((mean, stem + '.exr'), (var, stem + '.var.exr')):
        mi.Bitmap(mi.TensorXf(dr.scalar.ArrayXf(values), shape=shape)).write(f)
    wall = math.fsum(times)
    info = {
        'scene': 'tests/compat/scenes/%s.xml' % name,
        'mitsuba_version': mi.MI_VERSION,
        'variant': mi.variant(),
        'width': w, 'height': h,
        'spp': spp, 'batches': batches, 'spp_per_batch': per,
        'seeds': list(range(batches)),
        'variance_definition': 'unbiased sample variance across the batch means divided by the number of batches',
        'render_time_s': round(wall, 2),
        'threads': dr.thread_count(),
        'host': platform.node(),
        'mean_rgb': [round(math.fsum(mean[c::3]) / (w * h), 6) for c in range(3)],
        'command': 'python3 scripts/make_compat_references.py %s --spp %d --batches %d' % (name, spp, batches),
    }
    with open(stem + '.json', 'w') as fp:
        json.dump(info, fp, indent=2)
        fp.write('\n')
    print('%s: %d spp (%d x %d) in %.1f s, mean RGB %s' % (name, spp, batches, per, wall, info['mean_rgb']),
          flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('scenes', nargs='*')
    ap.add_argument('--spp', type=int, default=8192, help='total spp (default 8192)')
    ap.add_argument('--batches', type=int, default=16, help='independent batches (default 16)')
    ap.add_argument('--threads', type=int, default=2)
    args = ap.parse_args()
    import drjit as dr
    import mitsuba as mi
    mi.set_variant('scalar_rgb')
    dr.set_thread_count(args.threads)
    names = args.scenes or sorted(os.path.basename(p)[:-4] for p in glob.glob(os.path.join(COMPAT, 'scenes', '*.xml')))
    for name in names:
        render(mi, dr, name, args.spp, args.batches)


if __name__ == '__main__':
    main()
