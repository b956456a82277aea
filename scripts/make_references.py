#!/usr/bin/env python3
"""Render the Mitsuba 3 reference images of the bundled scenes for caustica's end-to-end tests.

For each scene, the scene file itself (scenes/<name>/scene.xml) is loaded by Mitsuba 3 with only
its <default> parameters overridden (width, height; the sample count is given to mi.render), and
rendered as N independent batches (batch b uses sampler seed `seed0 + b`). It writes, next to the
scene, in scenes/<name>/reference/:

  <name>-<res>.exr       mean of the batches (float32 RGB, linear, box-filtered pixels)
  <name>-<res>.var.exr   per-pixel variance of that mean: the unbiased sample variance across the
                         batches divided by N (so sqrt of it is the standard error of each pixel)
  <name>-<res>.json      Mitsuba version and variant, parameters, spp, batches, seeds, render time,
                         mean pixel values and noise statistics

Each batch image is also cached (keyed by a hash of the scene directory's files and the
parameters) under --cache (default /tmp/caustica-refcache), so an interrupted run resumes, and a
later run with more batches (same spp per batch) only renders the new ones.

Only the Python standard library and Mitsuba 3 (scalar_rgb) are needed.

Usage:
  python3 scripts/make_references.py                      # all scenes, default spp
  python3 scripts/make_references.py cornell-box --spp 16384 --batches 16 --threads 2
  python3 scripts/make_references.py --preview            # also write larger PNGs to /tmp only
"""
import argparse
import hashlib
import json
import math
import os
import platform
import re
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.normpath(os.path.join(HERE, '..', 'scenes'))

# Per-scene defaults: total spp of the reference, batches, image size, preview (size, spp).
CONFIG = {
    'cornell-box': dict(spp=16384, batches=16, res=64, preview=(256, 256)),
    'cornell-water': dict(spp=16384, batches=16, res=64, preview=(240, 512)),
    'door-gap': dict(spp=32768, batches=32, res=64, preview=(256, 1024)),
    'glass-caustic': dict(spp=262144, batches=256, res=64, preview=(256, 1024)),
}


def luminance(r, g, b):
    return 0.212671 * r + 0.715160 * g + 0.072169 * b


def scene_defaults(path):
    """The <default name=... value=...> parameters of a Mitsuba XML scene, as strings."""
    import xml.etree.ElementTree as ET
    return {e.get('name'): e.get('value') for e in ET.parse(path).getroot().iter('default')}


def scene_hash(name, params, per, variant='scalar_rgb'):
    """Hash of every file of the scene directory (except references; XML comments ignored) and
    the parameters."""
    h = hashlib.sha1()
    root = os.path.join(SCENES, name)
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d != 'reference')
        for f in sorted(filenames):
            fp = os.path.join(dirpath, f)
            h.update(os.path.relpath(fp, root).encode())
            with open(fp, 'rb') as fh:
                data = fh.read()
            if f.endswith('.xml'):  # comments do not change the image
                data = re.sub(rb'<!--.*?-->', b'', data, flags=re.S)
            h.update(hashlib.sha1(data).digest())
    h.update(json.dumps(sorted((k, str(v)) for k, v in params.items())).encode())
    h.update(str(per).encode())
    if variant != 'scalar_rgb':  # (keeps the keys of existing scalar_rgb caches)
        h.update(variant.encode())
    return h.hexdigest()[:16]


def batch_mean_variance(imgs):
    """Per value of the batch images `imgs` (flat lists of one length): the mean over the batches
    and its variance, the unbiased sample variance across the batches divided by their number
    (0 for a single batch). Also used by make_compat_references.py."""
    batches = len(imgs)
    mean = [0.0] * len(imgs[0])
    var = [0.0] * len(imgs[0])
    for i in range(len(mean)):
        xs = [im[i] for im in imgs]
        m = math.fsum(xs) / batches
        mean[i] = m
        var[i] = math.fsum((x - m) ** 2 for x in xs) / (batches - 1) / batches if batches > 1 else 0.0
    return mean, var


def render_reference(mi, dr, name, spp, batches, res, seed0, extra, cache):
    path = os.path.join(SCENES, name, 'scene.xml')
    params = dict(width=res, height=res)
    params.update(extra)
    scene = mi.load_file(path, **{k: v for k, v in params.items()})
    if spp % batches:
        sys.exit('%s: --spp (%d) must be a multiple of --batches (%d)' % (name, spp, batches))
    per = spp // batches
    key = scene_hash(name, params, per, mi.variant())
    if cache:
        os.makedirs(cache, exist_ok=True)
    imgs = []
    times = []
    t0 = time.time()
    for b in range(batches):
        cached = os.path.join(cache, '%s-%s-seed%d.exr' % (name, key, seed0 + b)) if cache else None
        if cached and os.path.exists(cached):
            img = mi.TensorXf(mi.Bitmap(cached))
            tjson = cached[:-4] + '.time'
            times.append(float(open(tjson).read()) if os.path.exists(tjson) else float('nan'))
            print('  %s batch %d/%d: cached %s' % (name, b + 1, batches, cached), flush=True)
        else:
            tb = time.time()
            img = mi.render(scene, spp=per, seed=seed0 + b)
            dr.eval(img)  # JIT variants (llvm_*) trace lazily: time the evaluated image
            dr.sync_thread()
            times.append(time.time() - tb)
            if cached:
                mi.Bitmap(img).write(cached)
                with open(cached[:-4] + '.time', 'w') as fh:
                    fh.write('%.3f\n' % times[-1])
            print('  %s batch %d/%d: %d spp, %.1f s' % (name, b + 1, batches, per, times[-1]), flush=True)
        shape = tuple(img.shape)
        if shape != (res, res, 3):
            sys.exit('%s: unexpected image shape %r' % (name, shape))
        imgs.append(list(img.array))
    wall = math.fsum(times)

    mean, var = batch_mean_variance(imgs)

    outdir = os.path.join(SCENES, name, 'reference')
    os.makedirs(outdir, exist_ok=True)
    stem = os.path.join(outdir, '%s-%d' % (name, res))

    def write(values, filename):
        t = mi.TensorXf(dr.scalar.ArrayXf(values), shape=(res, res, 3))
        mi.Bitmap(t).write(filename)

    write(mean, stem + '.exr')
    write(var, stem + '.var.exr')

    # statistics for the sidecar and the report
    chan_mean = [math.fsum(mean[c::3]) / (res * res) for c in range(3)]
    # standard error of the image mean per channel (pixels are independent)
    chan_se = [math.sqrt(math.fsum(var[c::3])) / (res * res) for c in range(3)]
    rel = []
    for p in range(res * res):
        lm = luminance(*mean[3 * p:3 * p + 3])
        # luminance variance (channels are correlated; this is an upper bound, fine for a summary)
        sd = math.sqrt(sum(var[3 * p + c] for c in range(3)) / 3.0)
        if lm > 1e-3:
            rel.append(sd / lm)
    rel.sort()
    q = lambda f: rel[min(len(rel) - 1, int(f * len(rel)))] if rel else float('nan')
    effective = scene_defaults(path)
    effective.update({k: str(v) for k, v in params.items()})
    effective['spp'] = str(spp)
    effective = {k: (int(v) if v.lstrip('-').isdigit() else v) for k, v in effective.items()}
    info = {
        'scene': 'scenes/%s/scene.xml' % name,
        'renderer': 'Mitsuba %s' % mi.MI_VERSION,
        'mitsuba_version': mi.MI_VERSION,
        'variant': mi.variant(),
        # every <default> of the scene as used (spp = the total over all batches), and the
        # ones this script overrode
        'parameters': effective,
        'overridden': sorted(params),
        'spp': spp,
        'batches': batches,
        'spp_per_batch': per,
        'seeds': [seed0 + b for b in range(batches)],
        'rfilter': 'box',
        'files': {
            'mean': os.path.basename(stem + '.exr'),
            'variance_of_mean': os.path.basename(stem + '.var.exr'),
        },
        'variance_definition': 'per pixel and channel: unbiased sample variance across the batch means, '
                               'divided by the number of batches (variance of the stored mean)',
        'render_time_s': round(wall, 2),
        'render_time_note': 'sum of the batch render times (wall clock, on a 2-core machine shared with '
                            'other jobs); load time and statistics excluded',
        'threads': dr.thread_count(),
        'host': platform.node(),
        'mean_rgb': [round(v, 6) for v in chan_mean],
        'mean_rgb_standard_error': [float('%.3g' % v) for v in chan_se],
        'pixel_relative_stddev_quantiles': {
            'p50': round(q(0.5), 5), 'p90': round(q(0.9), 5), 'p99': round(q(0.99), 5), 'max': round(q(1.0), 5),
        },
        'command': 'python3 scripts/make_references.py %s --spp %d --batches %d --res %d --seed %d%s%s' % (
            name, spp, batches, res, seed0, '' if mi.variant() == 'scalar_rgb' else ' --variant ' + mi.variant(),
            ''.join(' -D %s=%s' % kv for kv in extra.items())),
    }
    with open(stem + '.json', 'w') as fp:
        json.dump(info, fp, indent=2)
        fp.write('\n')
    print('%s: %d spp (%d x %d) in %.1f s, mean RGB %s, pixel rel. stddev p50 %.4f p90 %.4f p99 %.4f -> %s.{exr,var.exr,json}'
          % (name, spp, batches, per, wall, ['%.5f' % v for v in chan_mean], q(0.5), q(0.9), q(0.99),
             os.path.relpath(stem)), flush=True)
    return info


def render_preview(mi, name, size, spp, extra):
    path = os.path.join(SCENES, name, 'scene.xml')
    params = dict(width=size, height=size)
    params.update(extra)
    scene = mi.load_file(path, **params)
    t0 = time.time()
    img = mi.render(scene, spp=spp, seed=12345)
    bmp = mi.Bitmap(img)
    os.makedirs('/tmp/caustica-previews', exist_ok=True)
    out = '/tmp/caustica-previews/%s-%d-%dspp' % (name, size, spp)
    bmp.write(out + '.exr')
    bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True).write(out + '.png')
    print('preview %s: %dx%d, %d spp, %.1f s -> %s.png' % (name, size, size, spp, time.time() - t0, out), flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('scenes', nargs='*', help='scene names (default: %s)' % ' '.join(CONFIG))
    ap.add_argument('--spp', type=int, help='total samples per pixel (default: per scene)')
    ap.add_argument('--batches', type=int, help='independent batches (default: per scene)')
    ap.add_argument('--res', type=int, help='width = height of the reference (default 64)')
    ap.add_argument('--seed', type=int, default=0, help='seed of the first batch (default 0)')
    ap.add_argument('--threads', type=int, default=2, help='render threads (default 2)')
    ap.add_argument('--cache', default='/tmp/caustica-refcache',
                    help='directory caching each batch image (default /tmp/caustica-refcache; "" disables)')
    ap.add_argument('-D', action='append', default=[], metavar='NAME=VALUE',
                    help='extra <default> parameter override, e.g. -D max_depth=-1')
    ap.add_argument('--variant', default='scalar_rgb',
                    help='Mitsuba variant (default scalar_rgb; llvm_ad_rgb is ~2.5x faster on 2 cores and needs '
                         'Debian\'s libllvm19 with DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1)')
    ap.add_argument('--preview', action='store_true', help='also write larger preview PNGs to /tmp/caustica-previews')
    ap.add_argument('--preview-only', action='store_true', help='write only the previews')
    args = ap.parse_args()

    import drjit as dr
    import mitsuba as mi
    mi.set_variant(args.variant)
    dr.set_thread_count(args.threads)

    extra = {}
    for d in args.D:
        k, _, v = d.partition('=')
        if not k or not _:
            sys.exit('bad -D %r (want NAME=VALUE)' % d)
        extra[k] = v

    names = args.scenes or list(CONFIG)
    for name in names:
        if name not in CONFIG:
            sys.exit('unknown scene %r (known: %s)' % (name, ', '.join(CONFIG)))
        cfg = CONFIG[name]
        if not args.preview_only:
            render_reference(mi, dr, name, args.spp or cfg['spp'], args.batches or cfg['batches'],
                             args.res or cfg['res'], args.seed, extra, args.cache)
        if args.preview or args.preview_only:
            render_preview(mi, name, cfg['preview'][0], cfg['preview'][1], extra)


if __name__ == '__main__':
    main()
