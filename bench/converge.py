#!/usr/bin/env python3
"""Error against time: renders a scene with several integrator configurations at a series of
equal time budgets and measures each image's error against a reference.

Every (configuration, budget, repetition) is an independent `caustica render --time T` (bootstrap
and acceleration build included in T is the renderer's business: --time bounds the render
itself). The error is `caustica compare`'s relMSE; with the reference's variance image (REF.var.exr
next to REF.exr, as scripts/make_references.py writes) the reference's own noise is subtracted
(`relMSE (reference noise removed)`), which makes a noisy reference usable for small errors.

Writes CSV (one row per render) and, when matplotlib is installed, a log-log PNG plot of the mean
error per configuration against time.

Examples:
  bench/converge.py scenes/cornell-water/scene.xml \\
      --ref scenes/cornell-water/reference/cornell-water-64.exr --res 64x64 \\
      --config path --config "mlt:--integrator mlt" --times 2,4,8,16 --csv out/converge.csv
  # MLT with k = 1, 2, 4 proposals (the paper's figure 5):
  bench/converge.py SCENE --ref REF.exr --config "k1:--integrator mlt" \\
      --config "k2:--integrator mlt --mlt-proposals 2" --config "k4:--integrator mlt --mlt-proposals 4" ...

A configuration is NAME or NAME:EXTRA-ARGS; a bare name is an integrator (path, direct, mlt).
"""
import argparse
import json
import os
import shlex
import subprocess
import sys
import tempfile

from csv_out import write_csv

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..'))


def parse_config(text):
    name, _, extra = text.partition(':')
    args = shlex.split(extra) if extra else ['--integrator', name]
    return name, args


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit('failed (%d): %s\n%s' % (p.returncode, ' '.join(cmd), p.stderr.strip()))
    return p.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('scene')
    ap.add_argument('--ref', required=True,
                    help='reference image (.exr or .pfm); REF.var.exr (REF.var.pfm) is used if present')
    ap.add_argument('--config', action='append', required=True, help='NAME or NAME:EXTRA-ARGS (repeatable)')
    ap.add_argument('--times', default='2,4,8,16', help='time budgets in seconds, comma separated')
    ap.add_argument('--repeat', type=int, default=1, help='independent renders per budget (seeds S..S+N-1)')
    ap.add_argument('--first-seed', type=int, default=1,
                    help='S, the seed of the first repeat (to add repeats to an earlier run)')
    ap.add_argument('--res', help='WIDTHxHEIGHT (default: the reference size must match the scene)')
    ap.add_argument('--threads', type=int, help='render threads')
    ap.add_argument('--caustica', default=os.path.join(ROOT, 'build', 'caustica'))
    ap.add_argument('--csv', default='converge.csv')
    ap.add_argument('--plot', help='PNG plot (default: the CSV name with .png)')
    ap.add_argument('--title', default='')
    a = ap.parse_args()

    stem, ext = os.path.splitext(a.ref)
    var = stem + '.var' + ext  # REF.var.exr beside REF.exr, REF.var.pfm beside REF.pfm
    if not os.path.exists(var):
        var = None
    times = [float(t) for t in a.times.split(',')]
    configs = [parse_config(c) for c in a.config]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, extra in configs:
            for t in times:
                for rep in range(a.repeat):
                    img = os.path.join(tmp, 'img.exr')
                    stats = os.path.join(tmp, 'stats.json')
                    cmd = [a.caustica, 'render', a.scene, '--time', str(t), '-q', '-o', img,
                           '--stats-json', stats, '--seed', str(a.first_seed + rep), '--checkpoint-every', '0']
                    if a.res:
                        cmd += ['--res', a.res]
                    if a.threads:
                        cmd += ['--threads', str(a.threads)]
                    run(cmd + extra)
                    with open(stats) as f:
                        st = json.load(f)
                    cmp = [a.caustica, 'compare', img, a.ref, '--json'] + (['--ref-var', var] if var else [])
                    m = json.loads(run(cmp))
                    row = {'config': name, 'budget_s': t, 'repeat': a.first_seed - 1 + rep, 'seconds': st['seconds'],
                           'samples': st['samples'], 'rays': st['rays'], 'relmse': m['relmse'],
                           'relmse_ref_noise_removed': m.get('relmse_ref_noise_removed', ''),
                           'relmse_worst_1pct_share': m.get('relmse_worst_1pct_share', ''),
                           'mean_ratio': m.get('mean_ratio', ''),
                           'mlt_b': st.get('mlt_b', ''), 'mlt_iterations': st.get('mlt_iterations', ''),
                           'mlt_splat_seconds': st.get('mlt_splat_seconds', ''),
                           'mlt_sort_seconds': st.get('mlt_sort_seconds', ''),
                           'mlt_bytes_per_chain': st.get('mlt_bytes_per_chain', '')}
                    rows.append(row)
                    err = row['relmse_ref_noise_removed'] if var else row['relmse']
                    print('%-12s %6.1f s  relMSE %.4g%s' % (name, st['seconds'], err,
                          ' (reference noise removed)' if var else ''), flush=True)
    write_csv(a.csv, rows)

    # Mean error per configuration and budget, and the ratio to the first configuration.
    key = 'relmse_ref_noise_removed' if var else 'relmse'
    summary = {}
    for r in rows:
        summary.setdefault((r['config'], r['budget_s']), []).append(float(r[key]))
    print('\n%-12s' % 'budget (s)' + ''.join('%14s' % n for n, _ in configs))
    for t in times:
        base = sum(summary[(configs[0][0], t)]) / a.repeat
        cells = []
        for n, _ in configs:
            e = sum(summary[(n, t)]) / a.repeat
            cells.append('%8.3g (%.2fx)' % (e, base / e if e > 0 else float('nan')))
        print('%-12g' % t + ''.join('%14s' % c for c in cells))

    try:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
    except ImportError:
        print('matplotlib not installed: no plot')
        return
    plot = a.plot or os.path.splitext(a.csv)[0] + '.png'
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for n, _ in configs:
        xs = [t for t in times]
        ys = [max(1e-9, sum(summary[(n, t)]) / a.repeat) for t in times]
        ax.loglog(xs, ys, 'o-', label=n)
    ax.set_xlabel('time budget (s)')
    ax.set_ylabel('relMSE' + (' (reference noise removed)' if var else ''))
    ax.set_title(a.title or os.path.basename(a.scene))
    ax.grid(True, which='both', alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(plot, dpi=120)
    print('wrote', plot)


if __name__ == '__main__':
    main()
