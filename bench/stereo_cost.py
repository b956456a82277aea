#!/usr/bin/env python3
"""The second eye's cost (issue 21): for each integrator, a mono render and a stereo render
(`--stereo off-axis`) of the same scene at the same per-pixel budget (spp, sppm/ppm iterations, MLT
mutations per pixel), timed from `--stats-json` (render seconds, the BVH build excluded).

Why equal per-pixel budgets mean equal per-eye error: every eye of a stereo render draws exactly
what a mono render of that eye draws (path, direct: the same samples, tests/render/
stereo_render_test.cpp); an sppm eye's visible points meet the same photon passes a mono render's
meet (same photon count per iteration, same radius schedule); MLT's chains spread the same
mutations per pixel over twice the pixels. So extra = t_stereo / t_mono - 1 at equal error.

  bench/stereo_cost.py scenes/cornell-water/scene.xml --res 160x160 --repeat 3 --csv out/stereo.csv \\
      --case sppm:--spp=16 --case path:--spp=16 --case mlt:--spp=16

Each case is INTEGRATOR[:ARG=VALUE,...]; the best of --repeat runs is kept per row.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

from csv_out import write_csv

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..'))


def render_seconds(binary, scene, res, integrator, extra, stereo, threads):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, 'stats.json')
        cmd = [binary, 'render', scene, '--res', res, '--integrator', integrator, '-q', '--seed', '1',
               '-o', os.path.join(tmp, 'out.exr'), '--stats-json', stats, '--checkpoint-every', '0'] + extra
        if threads:
            cmd += ['--threads', str(threads)]
        if stereo:
            cmd += ['--stereo', 'off-axis']
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        with open(stats) as f:
            return json.load(f)['seconds']


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('scene')
    ap.add_argument('--res', default='160x160', help='one eye: WIDTHxHEIGHT')
    ap.add_argument('--case', action='append', required=True, help='INTEGRATOR[:ARG=VALUE,...]')
    ap.add_argument('--repeat', type=int, default=3)
    ap.add_argument('--threads', type=int, default=0)
    ap.add_argument('--binary', default=os.path.join(ROOT, 'build-cpu', 'caustica'))
    ap.add_argument('--csv', required=True)
    a = ap.parse_args()
    rows = []
    for case in a.case:
        integrator, _, args = case.partition(':')
        extra = []
        for item in filter(None, args.split(',')):
            k, _, v = item.partition('=')
            extra += [k, v] if v else [k]
        mono = min(render_seconds(a.binary, a.scene, a.res, integrator, extra, False, a.threads) for _ in range(a.repeat))
        both = min(render_seconds(a.binary, a.scene, a.res, integrator, extra, True, a.threads) for _ in range(a.repeat))
        rows.append({'integrator': integrator, 'args': ' '.join(extra), 'eye_res': a.res, 'mono_s': round(mono, 3),
                     'stereo_s': round(both, 3), 'second_eye_extra': round(both / mono - 1, 3)})
        print(rows[-1], flush=True)
    write_csv(a.csv, rows)


if __name__ == '__main__':
    sys.exit(main())
