#!/usr/bin/env python3
"""Photon-mapping measurements of issue 18, each writing CSV (and a PNG where it plots):

  options   time per iteration and photon paths/s of sppm (or ppm) for each choice of direction,
            structure and coherence order (visible points in Morton order or k-means clusters, photons sorted by cell)
            at equal iterations; the images are bit-identical, so only time differs.
  structures  the same for each lookup structure (hash, grid, kdtree, multihash) in both
            directions and in the default `auto`, where each structure takes the direction its own
            timed passes favour (issue 19: SPPM time per iteration per structure, equal images).
  converge  relMSE against iterations (one render per iteration count, same seed, so each is the
            prefix of the longest), log-log plot with the fitted slope; SPPM's error falls as
            iterations^-alpha-ish (variance ~ 1/(i R_i^2) and bias^2 ~ R_i^4 with R_i^2 ~ i^(alpha-1)).
  memory    driver memory (peak device bytes from the statistics) at a resolution and photon count,
            e.g. 1920x1080 with 2^20 photons per iteration.
  roulette  the photon roulette rules (albedo, throughput) side by side: relMSE against --ref at
            equal time (--seconds per render) or equal iterations (--spp), rules alternating and a
            new seed each repeat, with time, iterations, rays and stored photons per photon path.

Every render is `caustica render ... --stats-json`; the error is `caustica compare`'s relMSE with
the reference's noise removed (REF.var.exr beside REF.exr, as scripts/make_references.py writes).

Examples:
  bench/sppm_bench.py options scenes/cornell-water/scene.xml --res 256x256 --spp 8 --csv out/sppm-options.csv
  bench/sppm_bench.py converge scenes/cornell-water/scene.xml --res 256x256 \\
      --ref scenes/cornell-water/reference/cornell-water-256.exr --iterations 4,8,16,32,64,128 --csv out/conv.csv
  bench/sppm_bench.py memory scenes/cornell-water/scene.xml --res 1920x1080 --photons 1048576 --sppm-direction gather
  bench/sppm_bench.py roulette scenes/cornell-water/scene.xml --res 256x256 --seconds 20 --repeat 3 \
      --ref scenes/cornell-water/reference/cornell-water-256.exr --csv out/roulette.csv

Options the script does not know are passed on to every `caustica render`.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

from csv_out import write_csv

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..'))

OPTIONS = [  # (name, extra arguments): every choice named, whatever the defaults are
    ('deposit hash', ['--sppm-direction', 'deposit', '--sppm-structure', 'hash']),
    ('deposit hash, no Morton order', ['--sppm-direction', 'deposit', '--sppm-structure', 'hash',
                                       '--sppm-order', 'none']),
    ('deposit grid', ['--sppm-direction', 'deposit', '--sppm-structure', 'grid']),
    ('gather hash', ['--sppm-direction', 'gather', '--sppm-structure', 'hash']),
    ('gather hash, photons unsorted', ['--sppm-direction', 'gather', '--sppm-structure', 'hash',
                                       '--sppm-sort-photons', 'false']),
    ('gather hash, no Morton order', ['--sppm-direction', 'gather', '--sppm-structure', 'hash',
                                      '--sppm-order', 'none']),
    ('gather hash, unsorted, no Morton', ['--sppm-direction', 'gather', '--sppm-structure', 'hash',
                                          '--sppm-sort-photons', 'false', '--sppm-order', 'none']),
    ('gather hash, k-means clusters', ['--sppm-direction', 'gather', '--sppm-structure', 'hash',
                                       '--sppm-order', 'kmeans']),
    ('deposit hash, k-means clusters', ['--sppm-direction', 'deposit', '--sppm-structure', 'hash',
                                        '--sppm-order', 'kmeans']),
    ('gather grid', ['--sppm-direction', 'gather', '--sppm-structure', 'grid']),
    ('auto grid (the defaults)', ['--sppm-direction', 'auto', '--sppm-structure', 'grid']),
]

# 'auto' (the default direction) lets each structure take the direction its own timed passes
# favour: what a render with that structure and no other option does.
STRUCTURES = [('%s %s' % (d, s), ['--sppm-direction', d, '--sppm-structure', s])
              for d in ('gather', 'deposit', 'auto') for s in ('hash', 'grid', 'kdtree', 'multihash')]


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit('failed (%d): %s\n%s' % (p.returncode, ' '.join(cmd), p.stderr.strip()))
    return p.stdout


def render(a, tmp, extra):
    img = os.path.join(tmp, 'img.exr')
    stats = os.path.join(tmp, 'stats.json')
    cmd = [a.caustica, 'render', a.scene, '-q', '-o', img, '--stats-json', stats, '--checkpoint-every', '0',
           '--integrator', a.integrator, '--seed', str(a.seed)]
    if a.res:
        cmd += ['--res', a.res]
    if a.threads:
        cmd += ['--threads', str(a.threads)]
    run(cmd + list(a.extra) + extra)
    with open(stats) as f:
        return img, json.load(f)


def phase_times(st):
    return {k: st.get('sppm_%s_seconds' % k, '') for k in ('eye', 'grid', 'photon', 'gather', 'update')}


def cmd_options(a, options=OPTIONS):
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for rep in range(a.repeat):
            for name, extra in options:
                _, st = render(a, tmp, ['--spp', str(a.spp)] + extra)
                it = float(st['sppm_iterations'])
                t = phase_times(st)
                busy = sum(float(v) for v in t.values() if v != '')
                row = {'option': name, 'repeat': rep, 'iterations': it, 'seconds': st['seconds'],
                       'seconds_per_iteration': busy / it,
                       'photon_paths_per_second': st['sppm_photon_paths_per_second'],
                       'peak_device_bytes': st.get('sppm_peak_device_bytes', '')}
                row.update({'%s_seconds' % k: v for k, v in t.items()})
                row['stored_photons'] = st.get('sppm_stored_photons', '')
                row['direction'] = st.get('sppm_direction', '')
                rows.append(row)
                print('%-36s %.4f s/iteration, %.3g photon paths/s (build %.4f, lookup %.4f s/iteration; %s)' % (
                    name, row['seconds_per_iteration'], float(row['photon_paths_per_second']),
                    float(t['grid'] or 0) / it, float(t['gather'] or 0) / it, row['direction']), flush=True)
    write_csv(a.csv, rows)


def compare(a, img):
    """`caustica compare --json` of img against --ref (with REF.var.exr when it is beside REF, so the
    reference's noise is removed) and the key of the relMSE to use."""
    stem, ext = os.path.splitext(a.ref)
    var = stem + '.var' + ext
    var = var if os.path.exists(var) else None
    m = json.loads(run([a.caustica, 'compare', img, a.ref, '--json'] + (['--ref-var', var] if var else [])))
    return m, 'relmse_ref_noise_removed' if var else 'relmse'


def cmd_converge(a):
    iterations = [int(x) for x in a.iterations.split(',')]
    rows, key = [], 'relmse'
    with tempfile.TemporaryDirectory() as tmp:
        for it in iterations:
            img, st = render(a, tmp, ['--spp', str(it)])
            m, key = compare(a, img)
            err = m[key]
            rows.append({'iterations': it, 'seconds': st['seconds'], 'relmse': m['relmse'],
                         'relmse_ref_noise_removed': m.get('relmse_ref_noise_removed', ''),
                         'mean_ratio': m.get('mean_ratio', ''), 'mean_radius': st.get('sppm_mean_radius', '')})
            print('%6d iterations %8.1f s  relMSE %.4g  mean ratio %.4f' % (it, st['seconds'], err,
                                                                           float(m.get('mean_ratio', 'nan'))),
                  flush=True)
    write_csv(a.csv, rows)
    xs = [math.log(r['iterations']) for r in rows if float(r[key]) > 0]
    ys = [math.log(float(r[key])) for r in rows if float(r[key]) > 0]
    slope = float('nan')
    if len(xs) >= 2:
        mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
        slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    print('log-log slope of relMSE against iterations: %.3f' % slope)
    try:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
    except ImportError:
        print('matplotlib not installed: no plot')
        return
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.loglog([r['iterations'] for r in rows], [max(1e-9, float(r[key])) for r in rows], 'o-',
              label='%s (slope %.2f)' % (a.integrator, slope))
    i0, e0 = rows[0]['iterations'], max(1e-9, float(rows[0][key]))
    for s, style in ((-1.0, ':'), (-2.0 / 3.0, '--')):
        ax.loglog([i0, rows[-1]['iterations']], [e0, e0 * (rows[-1]['iterations'] / i0) ** s], style, color='grey',
                  label='slope %.2f' % s)
    ax.set_xlabel('iterations')
    ax.set_ylabel('relMSE' + (' (reference noise removed)' if var else ''))
    ax.set_title(a.title or os.path.basename(os.path.dirname(a.scene)))
    ax.grid(True, which='both', alpha=0.3)
    ax.legend()
    fig.tight_layout()
    plot = a.plot or os.path.splitext(a.csv)[0] + '.png'
    fig.savefig(plot, dpi=110)
    print('wrote', plot)


def relmse(a, img):
    m, key = compare(a, img)
    return float(m[key])


def cmd_roulette(a):
    first_seed = a.seed
    budget = ['--time', str(a.seconds)] if a.seconds else ['--spp', str(a.spp)]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for rep in range(a.repeat):
            rules = ('albedo', 'throughput') if rep % 2 == 0 else ('throughput', 'albedo')
            a.seed = first_seed + rep
            for rule in rules:
                img, st = render(a, tmp, budget + ['--sppm-roulette', rule])
                paths = float(st['sppm_photon_paths'])
                row = {'rule': rule, 'repeat': rep, 'seed': a.seed, 'seconds': st['seconds'],
                       'iterations': st['sppm_iterations'], 'relmse': relmse(a, img),
                       'photon_paths_per_second': st['sppm_photon_paths_per_second'],
                       'rays_per_photon_path_eye_included': float(st['rays']) / paths if paths else '',
                       'stored_photons_last_iteration': st.get('sppm_stored_photons', ''),
                       'photon_seconds': st.get('sppm_photon_seconds', '')}
                rows.append(row)
                print('%-10s seed %d: %.1f s, %d iterations, relMSE %.5g, %.3g photon paths/s' % (
                    rule, row['seed'], float(row['seconds']), int(row['iterations']), row['relmse'],
                    float(row['photon_paths_per_second'])), flush=True)
    write_csv(a.csv, rows)
    for rule in ('albedo', 'throughput'):
        errs = sorted(r['relmse'] for r in rows if r['rule'] == rule)
        its = sorted(float(r['iterations']) for r in rows if r['rule'] == rule)
        print('%-10s relMSE median %.5g (%s), iterations median %g' % (
            rule, errs[len(errs) // 2], ', '.join('%.4g' % e for e in errs), its[len(its) // 2]))


def cmd_memory(a):
    with tempfile.TemporaryDirectory() as tmp:
        _, st = render(a, tmp, ['--spp', str(a.spp), '--sppm-photons', str(a.photons)])
    row = {'res': a.res, 'photons': a.photons, 'iterations': st['sppm_iterations'],
           'device_bytes': st.get('sppm_device_bytes', ''), 'peak_device_bytes': st.get('sppm_peak_device_bytes', ''),
           'stored_photons': st.get('sppm_stored_photons', ''), 'extra': ' '.join(a.extra)}
    print('peak driver memory %.1f MiB (%s, %d photons/iteration, %s)' % (
        float(row['peak_device_bytes']) / 2 ** 20, a.res, a.photons, row['extra'] or 'defaults'))
    write_csv(a.csv, [row])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('what', choices=['options', 'structures', 'converge', 'memory', 'roulette'])
    ap.add_argument('scene')
    ap.add_argument('--integrator', default='sppm', choices=['sppm', 'ppm'])
    ap.add_argument('--res', help='WIDTHxHEIGHT')
    ap.add_argument('--spp', type=int, default=8, help='iterations (options, memory)')
    ap.add_argument('--repeat', type=int, default=1, help='repetitions of the whole option list (options)')
    ap.add_argument('--photons', type=int, default=1 << 20, help='photon paths per iteration (memory)')
    ap.add_argument('--ref', help='reference image (converge, roulette)')
    ap.add_argument('--seconds', type=float, help='time budget per render (roulette; else --spp iterations)')
    ap.add_argument('--iterations', default='4,8,16,32,64,128', help='iteration counts (converge)')
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--threads', type=int)
    ap.add_argument('--caustica', default=os.path.join(ROOT, 'build', 'caustica'))
    ap.add_argument('--csv', default='sppm.csv')
    ap.add_argument('--plot')
    ap.add_argument('--title', default='')
    a, a.extra = ap.parse_known_args()  # anything else: further `caustica render` options
    if a.what in ('converge', 'roulette') and not a.ref:
        sys.exit(a.what + ' needs --ref')
    {'options': cmd_options, 'structures': lambda a: cmd_options(a, STRUCTURES), 'converge': cmd_converge,
     'memory': cmd_memory, 'roulette': cmd_roulette}[a.what](a)


if __name__ == '__main__':
    main()
