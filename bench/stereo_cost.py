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

Each case is INTEGRATOR[:ARG=VALUE,...]; the best of --repeat runs (mono and stereo interleaved,
in the order A B B A so that a drift of the machine's speed hits both alike) is kept per row, as
render wall seconds and as CPU seconds of the process (load, BVH build and writing included; with
--threads 1 the robust figure on a shared machine). The row also gives the median over the
repeats of each neighbouring pair's stereo / mono ratio: on a VM whose speed drifts by 10% from
one run to the next, best-of-N of each side alone can land on different spells.
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import statistics
import tempfile

from csv_out import write_csv

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..'))


def render_seconds(binary, scene, res, integrator, extra, stereo, threads):
    """(render wall seconds from the statistics, CPU seconds of the whole process). With --threads 1
    the CPU seconds hardly depend on what else the machine runs; the wall seconds do."""
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, 'stats.json')
        cmd = [binary, 'render', scene, '--res', res, '--integrator', integrator, '-q', '--seed', '1',
               '-o', os.path.join(tmp, 'out.exr'), '--stats-json', stats, '--checkpoint-every', '0'] + extra
        if threads:
            cmd += ['--threads', str(threads)]
        if stereo:
            cmd += ['--stereo', 'off-axis']
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        with open(stats) as f:
            return json.load(f)['seconds'], cpu


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
        runs = {False: [], True: []}
        for i in range(a.repeat):  # interleaved A B B A, so that a busy spell hits both
            for stereo in ((False, True) if i % 2 == 0 else (True, False)):
                runs[stereo].append(render_seconds(a.binary, a.scene, a.res, integrator, extra, stereo, a.threads))
        pair_wall = statistics.median(s[0] / m[0] for m, s in zip(runs[False], runs[True]))
        pair_cpu = statistics.median(s[1] / m[1] for m, s in zip(runs[False], runs[True]))
        mono_wall, mono_cpu = min(r[0] for r in runs[False]), min(r[1] for r in runs[False])
        both_wall, both_cpu = min(r[0] for r in runs[True]), min(r[1] for r in runs[True])
        rows.append({'integrator': integrator, 'args': ' '.join(extra), 'eye_res': a.res,
                     'mono_wall_s': round(mono_wall, 3), 'stereo_wall_s': round(both_wall, 3),
                     'mono_cpu_s': round(mono_cpu, 3), 'stereo_cpu_s': round(both_cpu, 3),
                     'second_eye_extra_cpu': round(both_cpu / mono_cpu - 1, 3),
                     'second_eye_extra_wall': round(both_wall / mono_wall - 1, 3),
                     'repeats': a.repeat, 'median_pair_extra_cpu': round(pair_cpu - 1, 3),
                     'median_pair_extra_wall': round(pair_wall - 1, 3)})
        print(rows[-1], flush=True)
    write_csv(a.csv, rows)


if __name__ == '__main__':
    sys.exit(main())
