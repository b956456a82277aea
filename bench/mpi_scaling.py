#!/usr/bin/env python3
"""Strong scaling over MPI ranks (docs/MPI.md): the same render (same total spp / mutations per
pixel / iterations) with 1 rank x T threads, then N ranks x T threads each, for each integrator.

Every case is one `mpirun -n N caustica render` (N = 1 included, so the launcher's start is
the same in every row) with --stats-json; the figures come from rank 0's statistics:
`run_seconds` (rendering only: scene load and acceleration build excluded), the speedup
against the 1-rank row of the same integrator, and `bytes_sent_per_iteration` (rank 0's bytes
handed to MPI per step / iteration, where the integrator reports it) and `collectives` (rank 0's
meetings of all ranks in the render: each waits for the slowest rank). `cpu_seconds` is the CPU
time of mpirun and all ranks (start, load and waiting included): on a machine shared with other
work it shows whether the ranks split the work without adding any, where wall times cannot. Ranks beyond the cores are
oversubscribed (--oversubscribe): such rows measure overhead, not scaling.

--ceiling measures what the machine itself allows: for each rank count N that fits the cores, N
copies of the 1-rank render (no MPI, the whole budget each, different seeds) run at once, and
`machine_ceiling` = N x (best 1-rank run_seconds) / (the slowest copy's run_seconds). On a machine
whose cores share execution units or caches (SMT siblings, a busy host) this is below N, and no
split of the work over ranks can beat it; `of_ceiling` = speedup / machine_ceiling is then the
share of the attainable speed-up that the ranks reach.

    bench/mpi_scaling.py scenes/cornell-box/scene.xml --res 128x96 --threads 1 --ranks 1,2,4 \\
        --case path:--spp=64 --case mlt:--spp=32 --case sppm:--spp=16 \\
        --csv bench/results/mpi-scaling-2026-11-26.csv

A case is INTEGRATOR[:EXTRA,ARGS] (commas separate the extra arguments). Writes CSV, one row per
(case, ranks, repetition) with the best of --repeat in `best_run_seconds`.
"""
import argparse
import json
import os
import resource
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

from csv_out import write_csv

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..'))


def parse_case(text):
    name, _, extra = text.partition(':')
    args = [a for a in extra.split(',') if a] if extra else []
    return name, ['--integrator', name] + args


def render(mpirun, binary, scene, ranks, threads, res, args, work):
    stats = os.path.join(work, 'stats.json')
    cmd = [mpirun, '--allow-run-as-root', '--oversubscribe', '-n', str(ranks), binary, 'render', scene, '--threads', str(threads), '-q', '--overwrite',
           '-o', os.path.join(work, 'image.exr'), '--stats-json', stats] + (['--res', res] if res else []) + args
    start, before = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
    # OpenMPI in a container: no single-copy transfers (they need ptrace); other MPIs ignore it.
    env = dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism='none')
    done = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall, after = time.monotonic() - start, resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    if done.returncode != 0:
        sys.exit('failed: ' + ' '.join(shlex.quote(c) for c in cmd) + '\n' + done.stdout + done.stderr)
    with open(stats) as f:
        return json.load(f), wall, cpu


def concurrent_copies(binary, scene, copies, threads, res, args, work):
    """run_seconds of `copies` single-process renders started together (seeds 1..copies)."""
    procs, stats = [], []
    for i in range(copies):
        path = os.path.join(work, f'copy{i}.json')
        cmd = [binary, 'render', scene, '--threads', str(threads), '-q', '--overwrite', '--seed', str(i + 1),
               '-o', os.path.join(work, f'copy{i}.exr'), '--stats-json', path] + (['--res', res] if res else []) + args
        procs.append((cmd, subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)))
        stats.append(path)
    for cmd, proc in procs:
        out, _ = proc.communicate()
        if proc.returncode != 0:
            sys.exit('failed: ' + ' '.join(shlex.quote(c) for c in cmd) + '\n' + out)
    seconds = []
    for path in stats:
        with open(path) as f:
            seconds.append(json.load(f)['run_seconds'])
    return seconds


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('scene')
    p.add_argument('--case', action='append', required=True, help='INTEGRATOR[:EXTRA,ARGS]')
    p.add_argument('--ranks', default='1,2,4', help='rank counts, the first the baseline (default 1,2,4)')
    p.add_argument('--threads', type=int, default=1, help='threads per rank (default 1)')
    p.add_argument('--res', default='', help='WIDTHxHEIGHT')
    p.add_argument('--repeat', type=int, default=1)
    p.add_argument('--binary', default=os.path.join(ROOT, 'build-cpu', 'caustica'))
    p.add_argument('--mpirun', default=shutil.which('mpirun') or 'mpirun')
    p.add_argument('--ceiling', action='store_true',
                   help='also run N single-process copies at once: the speed-up the machine allows')
    p.add_argument('--csv', required=True)
    a = p.parse_args()
    ranks = [int(n) for n in a.ranks.split(',')]
    cores = os.cpu_count() or 1
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for case in a.case:
            name, args = parse_case(case)
            baseline = None
            for n in ranks:
                runs = [render(a.mpirun, a.binary, a.scene, n, a.threads, a.res, args, work) for _ in range(a.repeat)]
                best = min(s['run_seconds'] for s, _, _ in runs)
                baseline = baseline or best
                stats, wall, _ = runs[0]
                row = {'case': case, 'integrator': name, 'ranks': n, 'threads_per_rank': a.threads,
                       'oversubscribed': n * a.threads > cores, 'spp': stats['spp'],
                       'best_run_seconds': round(best, 4), 'wall_seconds': round(wall, 3),
                       'speedup': round(baseline / best, 3) if best > 0 else 0,
                       'cpu_seconds': round(min(c for _, _, c in runs), 3),
                       'samples': stats['samples'],
                       'bytes_sent_per_iteration': stats.get('bytes_sent_per_iteration', 0),
                       'bytes_sent': stats.get('bytes_sent', 0),
                       'collectives': stats.get('collectives', 0)}
                if a.ceiling:
                    ceiling = ''
                    if 1 < n and n * a.threads <= cores:
                        slowest = [max(concurrent_copies(a.binary, a.scene, n, a.threads, a.res, args, work))
                                   for _ in range(a.repeat)]
                        ceiling = round(n * baseline / min(slowest), 3)
                    row['machine_ceiling'] = ceiling
                    row['of_ceiling'] = round(row['speedup'] / ceiling, 3) if ceiling else ''
                rows.append(row)
                print(', '.join(f'{k} {v}' for k, v in row.items()), flush=True)
    write_csv(a.csv, rows)


if __name__ == '__main__':
    main()
