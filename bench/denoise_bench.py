#!/usr/bin/env python3
"""relMSE against the bundled Mitsuba references before and after denoising (docs/DENOISING.md).

For each scene and sample count N, caustica renders B independent batches of N/B spp (seeds 1..B)
at the reference's resolution; their mean is the noisy N-spp image and their spread divided by B
its per-pixel variance of the mean. Then:
  noisy     the mean itself
  nlm       caustica denoise --method nlm with albedo, normal, depth and the batch variance
  nlm-novar the same without --variance (the filter estimates the variance)
  oidn      caustica denoise --method oidn with albedo and normal (when OIDN is found)
relMSE comes from `caustica compare --json`; `seconds` is the batch renders' wall time for the
noisy row ('' when --reuse found them) and the `caustica denoise` process's for the others. The guides
(albedo, sh_normal, depth) of these rows are rendered by Mitsuba 3's `aov` integrator (scalar_rgb,
same scene file, resolution and camera, 64 spp): guides cleaner than the render's.

With --own-aovs (the default; --no-own-aovs leaves them out) the path a user takes, at the same N spp:
  own-noisy  `caustica render --spp N --seed 1 --aov alb:albedo,nn:sh_normal,dd:depth,var:variance
             --denoise nlm -o own-N.exr`: the render's own image, its AOVs as noisy as it (layers of
             the EXR; variance of its pixel samples); `seconds` the render's wall time (filter included)
  own-nlm    the render's own own-N.denoised.exr (`render --denoise nlm`)
  own-oidn   `caustica denoise own-N.exr --method oidn` (albedo and normal from the file's layers)

Run with a python that has mitsuba and numpy (the scene files' references were made with 3.9.1):
  /work/venv/bin/python bench/denoise_bench.py --caustica build-cpu/caustica --threads 2
"""
import argparse
import datetime
import json
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from csv_out import write_csv  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# scene -> reference resolution (the largest reference each scene has)
SCENES = {'cornell-water': 256, 'glass-caustic': 64}


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit('failed: ' + ' '.join(cmd) + '\n' + r.stdout + r.stderr)
    return r.stdout


def read_exr(mi, path):
    return np.array(mi.Bitmap(path), dtype=np.float32)[:, :, :3]


def write_exr(mi, path, rgb):
    mi.Bitmap(np.ascontiguousarray(rgb, dtype=np.float32), mi.Bitmap.PixelFormat.RGB).write(path)


def mitsuba_guides(mi, scene, res, out_dir):
    """albedo.exr, normal.exr, depth.exr of the scene's first hits, by Mitsuba 3's aov integrator."""
    sc = mi.load_file(os.path.join(ROOT, 'scenes', scene, 'scene.xml'), width=res, height=res)
    aov = mi.load_dict({'type': 'aov', 'aovs': 'albedo:albedo,nn:sh_normal,dd:depth'})
    mi.render(sc, integrator=aov, spp=64, seed=0)
    layers = dict(sc.sensors()[0].film().bitmap().split())
    paths = {}
    for key, layer in (('albedo', 'albedo'), ('normal', 'nn'), ('depth', 'dd')):
        a = np.array(layers[layer], dtype=np.float32)
        if a.ndim == 2:
            a = a[:, :, None]
        if a.shape[2] == 1:
            a = np.repeat(a, 3, axis=2)
        paths[key] = os.path.join(out_dir, key + '.exr')
        write_exr(mi, paths[key], a[:, :, :3])
    return paths


def relmse(caustica, image, reference):
    return json.loads(run([caustica, 'compare', '--json', image, reference]))['relmse']


def own_aov_rows(args, scene, res, spp, work, ref, env, base):
    """own-noisy, own-nlm, own-oidn: one render with caustica's own AOVs and --denoise nlm."""
    base = dict(base, spp=spp, batches=1)
    noisy = os.path.join(work, f'own-{spp}.exr')
    t0 = time.time()
    run([args.caustica, 'render', os.path.join(ROOT, 'scenes', scene, 'scene.xml'), '-o', noisy, '--spp', str(spp),
         '--seed', '1', '--res', f'{res}x{res}', '--threads', str(args.threads), '-q',
         '--aov', 'alb:albedo,nn:sh_normal,dd:depth,var:variance', '--denoise', 'nlm'])
    rows = [dict(base, method='own-noisy', relmse=relmse(args.caustica, noisy, ref), seconds=round(time.time() - t0, 2)),
            dict(base, method='own-nlm', relmse=relmse(args.caustica, os.path.join(work, f'own-{spp}.denoised.exr'), ref),
                 seconds='')]
    out = os.path.join(work, f'own-oidn-{spp}.exr')
    t0 = time.time()
    r = subprocess.run([args.caustica, 'denoise', noisy, '-o', out, '--method', 'oidn', '--threads', str(args.threads),
                        '-q'] + (['--oidn-library', args.oidn_library] if args.oidn_library else []),
                       capture_output=True, text=True, env=env)
    if r.returncode != 0:
        print(f'{scene} {spp} spp own-oidn: skipped: {(r.stdout + r.stderr).strip()}')
    else:
        rows.append(dict(base, method='own-oidn', relmse=relmse(args.caustica, out, ref), seconds=round(time.time() - t0, 2)))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--caustica', default=os.path.join(ROOT, 'build-cpu', 'caustica'))
    ap.add_argument('--scenes', nargs='+', default=list(SCENES))
    ap.add_argument('--spp', nargs='+', type=int, default=[16, 64, 256])
    ap.add_argument('--batches', type=int, default=4)
    ap.add_argument('--threads', type=int, default=2)
    ap.add_argument('--oidn-library', default='')
    ap.add_argument('--work', default='/tmp/caustica-denoise-bench')
    ap.add_argument('--reuse', action='store_true', help='keep batch renders already in --work')
    ap.add_argument('--own-aovs', action=argparse.BooleanOptionalAction, default=True,
                    help="also render with caustica's own AOVs and render --denoise (own-* rows)")
    ap.add_argument('--csv', default=os.path.join(ROOT, 'bench', 'results',
                                                  'denoise-' + datetime.date.today().isoformat() + '.csv'))
    args = ap.parse_args()
    import mitsuba as mi
    mi.set_variant('scalar_rgb')
    # Running in a virtual environment: let caustica's OIDN lookup see its site-packages (pyoidn).
    env = dict(os.environ, VIRTUAL_ENV=sys.prefix) if sys.prefix != sys.base_prefix else None
    rows = []
    for scene in args.scenes:
        res = SCENES[scene]
        ref = os.path.join(ROOT, 'scenes', scene, 'reference', f'{scene}-{res}.exr')
        work = os.path.join(args.work, scene)
        os.makedirs(work, exist_ok=True)
        guides = mitsuba_guides(mi, scene, res, work)
        for spp in args.spp:
            batch_spp = max(1, spp // args.batches)
            t0 = time.time()
            batches = []
            rendered = False
            for b in range(args.batches):
                path = os.path.join(work, f'batch-{spp}-{b}.exr')
                if not (args.reuse and os.path.exists(path)):
                    rendered = True
                    run([args.caustica, 'render', os.path.join(ROOT, 'scenes', scene, 'scene.xml'), '-o', path,
                         '--spp', str(batch_spp), '--seed', str(b + 1), '--res', f'{res}x{res}',
                         '--threads', str(args.threads), '-q'])
                batches.append(read_exr(mi, path))
            render_s = round(time.time() - t0, 2) if rendered else ''  # '' when reused
            stack = np.stack(batches)
            noisy = os.path.join(work, f'noisy-{spp}.exr')
            var = os.path.join(work, f'var-{spp}.exr')
            write_exr(mi, noisy, stack.mean(axis=0))
            write_exr(mi, var, stack.var(axis=0, ddof=1) / args.batches)
            first = len(rows)
            base = dict(scene=scene, res=res, spp=batch_spp * args.batches, batches=args.batches)
            rows.append(dict(base, method='noisy', relmse=relmse(args.caustica, noisy, ref), seconds=render_s))
            common = ['--albedo', guides['albedo'], '--normal', guides['normal'], '--threads', str(args.threads), '-q']
            runs = [('nlm', ['--method', 'nlm', '--depth', guides['depth'], '--variance', var]),
                    ('nlm-novar', ['--method', 'nlm', '--depth', guides['depth']]),
                    ('oidn', ['--method', 'oidn'] + (['--oidn-library', args.oidn_library] if args.oidn_library else []))]
            for method, extra in runs:
                out = os.path.join(work, f'{method}-{spp}.exr')
                t0 = time.time()
                r = subprocess.run([args.caustica, 'denoise', noisy, '-o', out] + common + extra,
                                   capture_output=True, text=True, env=env)
                seconds = time.time() - t0
                if r.returncode != 0:
                    print(f'{scene} {spp} spp {method}: skipped: {(r.stdout + r.stderr).strip()}')
                    continue
                rows.append(dict(base, method=method, relmse=relmse(args.caustica, out, ref), seconds=round(seconds, 2)))
            if args.own_aovs:
                rows += own_aov_rows(args, scene, res, spp, work, ref, env, base)
            for row in rows[first:]:
                print(f"{row['scene']:14s} {row['spp']:4d} spp {row['method']:10s} relMSE {row['relmse']:.5f}"
                      f"  {row['seconds']} s")
    write_csv(args.csv, rows)


if __name__ == '__main__':
    main()
