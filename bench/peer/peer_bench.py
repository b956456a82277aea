#!/usr/bin/env python3
"""caustica's path tracer against Mitsuba 3, side by side, on the same scene files, writing CSV.

For every scene: `caustica render --integrator path` and Mitsuba 3's `path` integrator in each
variant asked for (scalar_rgb, llvm_ad_rgb), all with the same samples per pixel, image size,
max_depth (Mitsuba's meaning) and thread count, in one run. Reported: seconds of the render, samples/s
(width * height * spp / seconds), caustica's rays/s (from its --stats-json; Mitsuba counts no rays),
caustica's samples/s over each renderer's, and every image's mean pixel value as a sanity check
(the same estimator gives close means; a warning is printed when they differ by more than 5%).

Timing, interleaved. Each Mitsuba variant runs in its own Python process that loads the scene once
(which builds its acceleration structure), renders it once to warm up (the full render for
llvm_ad_rgb, whose first render compiles the kernel; 1 spp for scalar_rgb) and then renders on
request. The script times --repeat rounds; in a round every renderer renders once, back to back,
the order rotating from round to round: caustica as one `caustica render` process, timed by the
`run_seconds` of its statistics (the rendering itself; parsing the scene and building the
acceleration structure are not in it), Mitsuba as `mi.render(scene, spp=...)` plus the conversion
of the image to numpy. On a shared VM whole renders drift by 10-50% within minutes, which moves
the renderers of one round alike: the ratio of caustica's samples/s to a peer's is therefore the
median over the rounds of the ratio within each round (its smallest and largest value reported
beside it), and `seconds` is each renderer's best round. A crash or a failing LLVM set-up only
skips that variant, with its reason. Threads: caustica --threads N; Mitsuba dr.set_thread_count(N)
(the nanothread pool both the scalar and the llvm variants render with).

Scenes: names of scenes/NAME/scene.xml, paths of Mitsuba 3 XML files, or `icosphere-330k`, a
generated scene (an icosahedron subdivided 7 times, 327,680 triangles, displaced by fractal noise,
on a ground quad under an area light; PLY + XML written once into --cache, default out/peer/).
A scene whose XML has <default> parameters spp, width, height and max_depth gets them as
`-D name=value` (caustica) and keyword arguments of mi.load_file (Mitsuba); any other scene is
rendered from a copy of its XML with those values written in (file names made absolute).

Without Mitsuba (`import mitsuba` fails in --python): prints one line and measures caustica alone.

Examples:
  .venv/bin/python bench/peer/peer_bench.py --caustica build-sppm/caustica
  .venv/bin/python bench/peer/peer_bench.py --scenes cornell-water --res 64x64 --spp 4 --variants scalar_rgb

Options the script does not know are passed on to every `caustica render`.
"""
import argparse
import datetime
import json
import os
import select
import statistics
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..', '..'))
sys.path.insert(0, os.path.join(ROOT, 'bench'))

LLVM_DEFAULT = '/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1'
DEFAULT_SCENES = 'cornell-water,glass-caustic,cornell-box,door-gap,icosphere-330k'
NEEDED_DEFAULTS = ('spp', 'width', 'height', 'max_depth')
COLUMNS = ['scene', 'triangles', 'res', 'spp', 'max_depth', 'threads', 'renderer', 'rounds', 'seconds',
           'samples_per_s', 'rays_per_s', 'ratio_caustica_over_this', 'ratio_min', 'ratio_max', 'image_mean', 'note']


# ---- the generated scene ------------------------------------------------------------------------

GENERATED = {'icosphere-330k': 7}  # name -> subdivision levels (20 * 4^levels triangles)
GENERATOR_VERSION = '2'


def icosphere(levels):
    import numpy as np
    g = (1 + 5 ** 0.5) / 2
    v = np.array([[-1, g, 0], [1, g, 0], [-1, -g, 0], [1, -g, 0], [0, -1, g], [0, 1, g], [0, -1, -g],
                  [0, 1, -g], [g, 0, -1], [g, 0, 1], [-g, 0, -1], [-g, 0, 1]], dtype=np.float64)
    f = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
                  [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
                  [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]], dtype=np.int64)
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    for _ in range(levels):
        e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])  # edges ab, bc, ca of every face
        key = np.minimum(e[:, 0], e[:, 1]) * len(v) + np.maximum(e[:, 0], e[:, 1])
        uniq, first, inv = np.unique(key, return_index=True, return_inverse=True)
        mid = v[e[first, 0]] + v[e[first, 1]]
        mid /= np.linalg.norm(mid, axis=1, keepdims=True)
        m = (len(v) + inv).reshape(3, -1)  # midpoints of ab, bc, ca
        ab, bc, ca = m[0], m[1], m[2]
        f = np.concatenate([np.stack([f[:, 0], ab, ca], 1), np.stack([f[:, 1], bc, ab], 1),
                            np.stack([f[:, 2], ca, bc], 1), np.stack([ab, bc, ca], 1)])
        v = np.concatenate([v, mid])
    return v, f


def value_noise(p):
    """Smooth 3D value noise in [-1, 1]: hashed lattice values, trilinear with smoothstep fade."""
    import numpy as np
    fl = np.floor(p)
    u = p - fl
    u = u * u * (3 - 2 * u)
    i = fl.astype(np.int64)

    def lattice(x, y, z):
        h = (x.astype(np.uint64) * np.uint64(0x9E3779B97F4A7C15)) ^ (y.astype(np.uint64) * np.uint64(0xC2B2AE3D27D4EB4F)) \
            ^ (z.astype(np.uint64) * np.uint64(0x165667B19E3779F9))
        h ^= h >> np.uint64(31)
        h *= np.uint64(0xBF58476D1CE4E5B9)
        h ^= h >> np.uint64(29)
        return (h >> np.uint64(11)).astype(np.float64) / float(1 << 53) * 2 - 1

    x, y, z = i[:, 0], i[:, 1], i[:, 2]
    c = {}
    for dx in (0, 1):
        for dy in (0, 1):
            for dz in (0, 1):
                c[dx, dy, dz] = lattice(x + dx, y + dy, z + dz)
    lx = lambda a, b: a + u[:, 0] * (b - a)
    c00, c10 = lx(c[0, 0, 0], c[1, 0, 0]), lx(c[0, 1, 0], c[1, 1, 0])
    c01, c11 = lx(c[0, 0, 1], c[1, 0, 1]), lx(c[0, 1, 1], c[1, 1, 1])
    c0, c1 = c00 + u[:, 1] * (c10 - c00), c01 + u[:, 1] * (c11 - c01)
    return c0 + u[:, 2] * (c1 - c0)


def write_ply(path, v, n, f):
    import numpy as np
    header = ('ply\nformat binary_little_endian 1.0\ncomment caustica bench/peer/peer_bench.py generated mesh\n'
              'element vertex %d\nproperty float x\nproperty float y\nproperty float z\n'
              'property float nx\nproperty float ny\nproperty float nz\n'
              'element face %d\nproperty list uchar int vertex_indices\nend_header\n' % (len(v), len(f)))
    verts = np.concatenate([v, n], axis=1).astype('<f4')
    faces = np.zeros(len(f), dtype=[('n', 'u1'), ('i', '<i4', (3,))])
    faces['n'] = 3
    faces['i'] = f
    tmp = path + '.tmp'
    with open(tmp, 'wb') as out:
        out.write(header.encode('ascii'))
        out.write(verts.tobytes())
        out.write(faces.tobytes())
    os.replace(tmp, path)


SCENE_XML = """<?xml version="1.0" encoding="utf-8"?>
<!-- Generated by bench/peer/peer_bench.py (version {version}): an icosahedron subdivided {levels} times
     ({tris} triangles, smooth vertex normals), projected to the unit sphere and displaced radially by
     fractal value noise, on a 40 x 40 ground quad, lit by a 1 x 1 area light; the camera of
     bench/bench_scenes.h's icosphere scene. Same file for caustica and Mitsuba 3. -->
<scene version="3.0.0">
    <default name="spp" value="64"/>
    <default name="width" value="256"/>
    <default name="height" value="256"/>
    <default name="max_depth" value="16"/>
    <default name="rr_depth" value="5"/>

    <integrator type="path">
        <integer name="max_depth" value="$max_depth"/>
        <integer name="rr_depth" value="$rr_depth"/>
    </integrator>

    <sensor type="perspective">
        <float name="fov" value="40"/>
        <string name="fov_axis" value="y"/>
        <transform name="to_world">
            <lookat origin="0.6, 0.9, 3.4" target="0, -0.15, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="$width"/>
            <integer name="height" value="$height"/>
            <rfilter type="box"/>
        </film>
    </sensor>

    <bsdf type="diffuse" id="clay">
        <rgb name="reflectance" value="0.65, 0.55, 0.45"/>
    </bsdf>
    <bsdf type="diffuse" id="grey">
        <rgb name="reflectance" value="0.5, 0.5, 0.5"/>
    </bsdf>

    <shape type="ply" id="icosphere">
        <string name="filename" value="{ply}"/>
        <ref id="clay"/>
    </shape>
    <shape type="rectangle" id="ground">
        <transform name="to_world">
            <scale value="20"/>
            <rotate x="1" angle="-90"/>
            <translate y="-1.25"/>
        </transform>
        <ref id="grey"/>
    </shape>
    <shape type="rectangle" id="light">
        <transform name="to_world">
            <scale value="0.5"/>
            <rotate x="1" angle="90"/>
            <translate x="1.5" y="4" z="1.5"/>
        </transform>
        <ref id="grey"/>
        <emitter type="area">
            <rgb name="radiance" value="60, 55, 48"/>
        </emitter>
    </shape>
</scene>
"""


def generated_scene(name, cache):
    """Writes CACHE/NAME/scene.xml and mesh.ply once (deterministic) and returns the XML path."""
    levels = GENERATED[name]
    d = os.path.join(cache, name)
    xml, ply = os.path.join(d, 'scene.xml'), os.path.join(d, 'mesh.ply')
    stamp = os.path.join(d, 'version')
    if os.path.exists(xml) and os.path.exists(ply) and os.path.exists(stamp) and \
            open(stamp).read().strip() == GENERATOR_VERSION:
        return xml
    import numpy as np
    os.makedirs(d, exist_ok=True)
    t = time.time()
    v, f = icosphere(levels)
    q = v * 3.0 + np.array([7.1, 3.3, 1.7])
    fbm, amp = np.zeros(len(v)), 0.5
    for _ in range(5):
        fbm += amp * value_noise(q)
        q, amp = q * 2.03, amp * 0.5
    v = v * (1 + 0.35 * fbm)[:, None]
    fn = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])  # area-weighted face normals
    n = np.stack([sum(np.bincount(f[:, k], weights=fn[:, c], minlength=len(v)) for k in range(3))
                  for c in range(3)], axis=1)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    write_ply(ply, v, n, f)
    with open(xml, 'w') as out:
        out.write(SCENE_XML.format(version=GENERATOR_VERSION, levels=levels, tris=len(f), ply='mesh.ply'))
    with open(stamp, 'w') as out:
        out.write(GENERATOR_VERSION + '\n')
    print('generated %s: %d vertices, %d triangles (%.1f s) in %s' % (name, len(v), len(f), time.time() - t, d),
          flush=True)
    return xml


# ---- scene files --------------------------------------------------------------------------------

def ply_face_count(path):
    with open(path, 'rb') as f:
        for _ in range(200):
            line = f.readline().decode('ascii', 'replace').split()
            if line[:2] == ['element', 'face']:
                return int(line[2])
            if line[:1] == ['end_header'] or not line:
                break
    return None


def triangle_count(xml_path):
    """Triangles of the scene's meshes (ply faces counted as triangles, rectangle 2, cube 12,
    disk 512); spheres are analytic in both renderers and not counted. None if unknown (obj, ...)."""
    root = ET.parse(xml_path).getroot()
    base = os.path.dirname(os.path.abspath(xml_path))
    total = 0
    for shape in root.iter('shape'):
        t = shape.get('type')
        if t == 'ply':
            fn = next((s.get('value') for s in shape.findall('string') if s.get('name') == 'filename'), None)
            n = ply_face_count(os.path.join(base, fn)) if fn and '$' not in fn else None
            if n is None:
                return None
            total += n
        elif t in ('rectangle', 'cube', 'disk'):
            total += {'rectangle': 2, 'cube': 12, 'disk': 512}[t]
        elif t in ('sphere', 'cylinder'):
            pass
        else:
            return None
    return total


def prepare_scene(xml_path, params, cache):
    """(path, defines): the scene's own file with `defines` if it declares every needed <default>,
    else a copy in CACHE with the values written in and file names made absolute (no defines)."""
    root = ET.parse(xml_path).getroot()
    declared = {d.get('name') for d in root.findall('default')}
    if all(k in declared for k in NEEDED_DEFAULTS):
        return xml_path, {k: params[k] for k in NEEDED_DEFAULTS}
    base = os.path.dirname(os.path.abspath(xml_path))
    for s in root.iter('string'):
        if s.get('name') == 'filename' and not os.path.isabs(s.get('value', '')):
            s.set('value', os.path.join(base, s.get('value')))

    def setv(parent, tag, name, value):
        el = next((e for e in parent.findall(tag) if e.get('name') == name), None)
        if el is None:
            el = ET.SubElement(parent, tag, name=name)
        el.set('value', str(value))

    integ = root.find('integrator')
    if integ is None:
        integ = ET.Element('integrator')
        root.insert(0, integ)
    integ.set('type', 'path')
    setv(integ, 'integer', 'max_depth', params['max_depth'])
    sensor = root.find('sensor')
    sampler = sensor.find('sampler')
    if sampler is None:
        sampler = ET.SubElement(sensor, 'sampler', type='independent')
    setv(sampler, 'integer', 'sample_count', params['spp'])
    film = sensor.find('film')
    if film is None:
        film = ET.SubElement(sensor, 'film', type='hdrfilm')
    setv(film, 'integer', 'width', params['width'])
    setv(film, 'integer', 'height', params['height'])
    name = os.path.basename(base) or 'scene'
    out = os.path.join(cache, 'patched', '%s-%dx%d-%d-%d.xml' % (
        name, params['width'], params['height'], params['spp'], params['max_depth']))
    os.makedirs(os.path.dirname(out), exist_ok=True)
    ET.ElementTree(root).write(out, encoding='utf-8', xml_declaration=True)
    return out, {}


def resolve_scene(spec, cache):
    """(name, xml path) of a scene name, a scenes/ folder name or an XML path."""
    if spec in GENERATED:
        return spec, generated_scene(spec, cache)
    if os.path.isfile(spec):
        d = os.path.basename(os.path.dirname(os.path.abspath(spec)))
        return (d if os.path.basename(spec) == 'scene.xml' else os.path.splitext(os.path.basename(spec))[0]), spec
    p = os.path.join(ROOT, 'scenes', spec, 'scene.xml')
    if os.path.isfile(p):
        return spec, p
    sys.exit('unknown scene %r (a name in scenes/, an XML file, or one of %s)' % (spec, ', '.join(GENERATED)))


# ---- images -------------------------------------------------------------------------------------

def pfm_mean(path):
    """Mean of all values of a PFM image (numpy-free)."""
    from array import array
    with open(path, 'rb') as f:
        kind = f.readline().strip()
        w, h = (int(x) for x in f.readline().split())
        scale = float(f.readline())
        data = array('f')
        data.frombytes(f.read(w * h * (3 if kind == b'PF' else 1) * 4))
    if (scale < 0) != (sys.byteorder == 'little'):
        data.byteswap()
    return sum(data) / len(data)


# ---- caustica -----------------------------------------------------------------------------------

def run_caustica(a, xml, defines, params, extra):
    """One `caustica render` process: its seconds, samples/s, rays/s and image mean, or a note."""
    with tempfile.TemporaryDirectory() as tmp:
        img, stats = os.path.join(tmp, 'img.pfm'), os.path.join(tmp, 'stats.json')
        cmd = [a.caustica, 'render', xml, '-q', '-o', img, '--stats-json', stats, '--checkpoint-every', '0',
               '--integrator', 'path', '--device', 'cpu', '--spp', str(params['spp']),
               '--res', '%dx%d' % (params['width'], params['height']), '--threads', str(a.threads)]
        for k, v in defines.items():
            cmd += ['-D', '%s=%s' % (k, v)]
        cmd += extra
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            return {'note': 'caustica failed (%d): %s' % (p.returncode, (p.stderr.strip() or p.stdout.strip())[-300:])}
        with open(stats) as f:
            st = json.load(f)
        sec = float(st['run_seconds'])
        r = {'seconds': sec, 'samples_per_s': float(st['samples']) / sec, 'rays_per_s': float(st['rays']) / sec,
             'image_mean': pfm_mean(img)}
        expect = params['width'] * params['height'] * params['spp']
        if int(st['samples']) != expect:
            r['note'] = 'caustica rendered %d samples, expected %d' % (int(st['samples']), expect)
        return r


# ---- Mitsuba (in a child process per variant) ---------------------------------------------------

def mitsuba_worker(spec):
    """Runs in its own process: loads the scene in one variant, warms up, times the renders."""
    job = json.loads(spec)
    import drjit as dr
    import mitsuba as mi
    import numpy as np
    dr.set_thread_count(job['threads'])
    mi.set_variant(job['variant'])
    dr.set_thread_count(job['threads'])
    mi.set_log_level(mi.LogLevel.Warn)
    t = time.time()
    scene = mi.load_file(job['xml'], **job['defines'])
    load = time.time() - t
    spp = job['spp']
    film = scene.sensors()[0].film()
    size = [int(x) for x in film.crop_size()]
    integ = scene.integrator()
    integ_params = mi.traverse(integ)
    info = {'load_seconds': load, 'size': size, 'integrator': integ.class_name() if hasattr(integ, 'class_name') else '',
            'version': mi.__version__, 'threads': dr.thread_count()}
    try:
        info['max_depth'] = int(integ_params['max_depth']) if 'max_depth' in integ_params else None
    except Exception:
        info['max_depth'] = None

    def render_once(n):
        t0 = time.perf_counter()
        img = mi.render(scene, spp=n)
        dr.eval(img)
        arr = np.array(img)
        return time.perf_counter() - t0, arr

    warm_spp = spp if job['variant'].startswith(('llvm', 'cuda')) else 1
    info['warmup_seconds'], _ = render_once(warm_spp)
    info['samples'] = size[0] * size[1] * spp
    print('READY ' + json.dumps(info), flush=True)
    for line in sys.stdin:  # one timed render per request line, until stdin closes
        sec, arr = render_once(spp)
        print('RESULT ' + json.dumps({'seconds': sec, 'image_mean': float(arr[..., :3].astype(np.float64).mean())}),
              flush=True)


class MitsubaSession:
    """A worker process of one Mitsuba variant with its scene loaded and warmed up; render() times
    one more render. `note` says why it is unusable (then `info` is None)."""

    def __init__(self, a, variant, xml, defines, params):
        self.a, self.info, self.note = a, None, ''
        job = {'variant': variant, 'xml': os.path.abspath(xml), 'defines': defines, 'spp': params['spp'],
               'threads': a.threads}
        self.proc = subprocess.Popen([a.python, os.path.abspath(__file__), '--mitsuba-worker', json.dumps(job)],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True, bufsize=1)
        line = self._reply('READY ')
        if line is None:
            return
        self.info = json.loads(line)
        notes = []
        if self.info['size'] != [params['width'], params['height']]:
            notes.append('Mitsuba film %dx%d' % tuple(self.info['size']))
        if self.info.get('max_depth') is not None and self.info['max_depth'] != params['max_depth']:
            notes.append('Mitsuba max_depth %d' % self.info['max_depth'])
        if self.info.get('threads') != a.threads:
            notes.append('drjit threads %s' % self.info.get('threads'))
        self.note = '; '.join(notes)

    def _reply(self, prefix):
        """The payload of the worker's next line starting with `prefix`, or None (note set) when it
        exits or stays silent for --timeout seconds."""
        deadline = time.time() + self.a.timeout
        while True:
            ready, _, _ = select.select([self.proc.stdout], [], [], max(0.0, deadline - time.time()))
            if not ready:
                self.close()
                self.note = 'skipped: no answer within --timeout %d s' % self.a.timeout
                return None
            line = self.proc.stdout.readline()
            if not line:
                err = (self.proc.stderr.read().strip() or 'no output').splitlines()
                self.proc.wait()
                reason = next((l for l in reversed(err) if 'Error' in l or 'error' in l or 'Exception' in l), err[-1])
                self.note = 'skipped: %s (exit %d)' % (reason.strip()[-300:], self.proc.returncode)
                self.info = None
                return None
            if line.startswith(prefix):
                return line[len(prefix):]

    def render(self):
        """One timed render: {'seconds', 'samples_per_s', 'image_mean'}, or {'note'} on failure."""
        if self.info is None:
            return {'note': self.note}
        self.proc.stdin.write('render\n')
        self.proc.stdin.flush()
        line = self._reply('RESULT ')
        if line is None:
            return {'note': self.note}
        r = json.loads(line)
        r['samples_per_s'] = self.info['samples'] / r['seconds']
        return r

    def close(self):
        if self.proc.poll() is None:
            self.proc.stdin.close()
            try:
                self.proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()


def mitsuba_version(python):
    try:
        p = subprocess.run([python, '-c', 'import mitsuba, drjit; print(mitsuba.__version__)'],
                           capture_output=True, text=True, timeout=120)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return p.stdout.strip() if p.returncode == 0 else None


# ---- main ---------------------------------------------------------------------------------------

def fmt(x, scale=1.0, spec='%.3f'):
    return '-' if x in (None, '') else spec % (float(x) / scale)


def main():
    if len(sys.argv) == 3 and sys.argv[1] == '--mitsuba-worker':
        return mitsuba_worker(sys.argv[2])
    from csv_out import write_csv
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--scenes', default=DEFAULT_SCENES,
                    help='comma separated: names in scenes/, XML paths, icosphere-330k (default %(default)s)')
    ap.add_argument('--res', default='256x256', help='WIDTHxHEIGHT (default %(default)s)')
    ap.add_argument('--spp', type=int, default=64)
    ap.add_argument('--max-depth', type=int, default=16, help="longest path, Mitsuba's meaning (default 16)")
    ap.add_argument('--threads', type=int, default=2)
    ap.add_argument('--repeat', type=int, default=3,
                    help='rounds; in each every renderer renders once, back to back (default %(default)s)')
    ap.add_argument('--variants', default='scalar_rgb,llvm_ad_rgb', help='Mitsuba variants, comma separated')
    ap.add_argument('--caustica', default=os.path.join(ROOT, 'build', 'caustica'))
    ap.add_argument('--python', default=sys.executable, help='Python with mitsuba (default: this one)')
    ap.add_argument('--cache', default=os.path.join(ROOT, 'out', 'peer'), help='generated scenes (default out/peer)')
    ap.add_argument('--timeout', type=int, default=1800,
                    help='seconds a Mitsuba worker may take to load and warm up, or for one render')
    ap.add_argument('--csv', default=os.path.join(ROOT, 'out', 'peer', 'peer-%s.csv' % datetime.date.today().isoformat()))
    a, extra = ap.parse_known_args()
    if a.repeat < 1:
        sys.exit('--repeat must be at least 1')
    try:
        w, h = (int(x) for x in a.res.lower().split('x'))
    except ValueError:
        sys.exit('--res must be WIDTHxHEIGHT')
    if not os.path.isfile(a.caustica):
        sys.exit('caustica binary not found: %s (--caustica PATH)' % a.caustica)
    if 'DRJIT_LIBLLVM_PATH' not in os.environ and os.path.exists(LLVM_DEFAULT):
        os.environ['DRJIT_LIBLLVM_PATH'] = LLVM_DEFAULT
    params = {'spp': a.spp, 'width': w, 'height': h, 'max_depth': a.max_depth}

    version = mitsuba_version(a.python)
    variants = [v for v in a.variants.split(',') if v]
    if version is None:
        print('Mitsuba 3 not found (pip install mitsuba): only caustica measured')
        variants = []
    else:
        print('Mitsuba %s (%s), DRJIT_LIBLLVM_PATH=%s' % (version, a.python, os.environ.get('DRJIT_LIBLLVM_PATH', '')))
    print('%s, integrator path, %dx%d, %d spp, max_depth %d, %d threads, %d interleaved rounds' % (
        a.caustica, w, h, a.spp, a.max_depth, a.threads, a.repeat), flush=True)

    rows = []
    for spec in [s for s in a.scenes.split(',') if s]:
        name, xml = resolve_scene(spec, a.cache)
        path, defines = prepare_scene(xml, params, a.cache)
        tris = triangle_count(path)
        base = {'scene': name, 'triangles': '' if tris is None else tris, 'res': '%dx%d' % (w, h), 'spp': a.spp,
                'max_depth': a.max_depth, 'threads': a.threads}
        sessions = {}
        for v in variants:  # loaded and warmed up before the timed rounds
            sessions['mitsuba-' + v] = MitsubaSession(a, v, path, defines, params)
        renderers = ['caustica'] + list(sessions)
        rounds = {r: [] for r in renderers}  # per round: its result dict
        for k in range(a.repeat):
            order = renderers[k % len(renderers):] + renderers[:k % len(renderers)]
            for renderer in order:
                r = run_caustica(a, path, defines, params, extra) if renderer == 'caustica' \
                    else sessions[renderer].render()
                rounds[renderer].append(r)
                print('%-16s round %d  %-19s %s' % (name, k + 1, renderer, summary(r)), flush=True)
        for sess in sessions.values():
            sess.close()
        own = rounds['caustica']
        cm = own[-1].get('image_mean')  # every round renders the same image (same seed)
        for renderer in renderers:
            done = [r for r in rounds[renderer] if r.get('samples_per_s')]
            best = min(done, key=lambda r: r['seconds']) if done else {}
            notes = [r.get('note') for r in rounds[renderer] if r.get('note')]
            if renderer != 'caustica' and sessions[renderer].note and sessions[renderer].info is not None:
                notes.insert(0, sessions[renderer].note)
            ratios = [c['samples_per_s'] / r['samples_per_s'] for c, r in zip(own, rounds[renderer])
                      if c.get('samples_per_s') and r.get('samples_per_s')]
            row = dict(base, renderer=renderer, rounds=len(done), seconds=best.get('seconds', ''),
                       samples_per_s=best.get('samples_per_s', ''), rays_per_s=best.get('rays_per_s', ''),
                       ratio_caustica_over_this=statistics.median(ratios) if ratios else '',
                       ratio_min=min(ratios) if ratios else '', ratio_max=max(ratios) if ratios else '',
                       image_mean=best.get('image_mean', ''), note='; '.join(dict.fromkeys(notes)))
            if renderer != 'caustica' and cm and best.get('image_mean'):
                rel = cm / best['image_mean'] - 1
                if abs(rel) > 0.05:
                    print('WARNING %s: caustica image mean %.5g differs from %s\'s %.5g by %+.1f%%' % (
                        name, cm, renderer, best['image_mean'], 100 * rel), flush=True)
                    row['note'] = '; '.join(x for x in (row['note'], 'mean differs %+.1f%%' % (100 * rel)) if x)
            rows.append(row)

    write_csv(a.csv, [{k: r[k] for k in COLUMNS} for r in rows])
    print()
    print('%-16s %9s %-20s %9s %10s %9s %9s %11s %10s  %s' % ('scene', 'triangles', 'renderer', 'seconds',
                                                              'Msamples/s', 'Mrays/s', 'caus/this', '(min-max)',
                                                              'mean', 'note'))
    for r in rows:
        spread = '' if r['ratio_min'] == '' else '%.2f-%.2f' % (r['ratio_min'], r['ratio_max'])
        print('%-16s %9s %-20s %9s %10s %9s %9s %11s %10s  %s' % (
            r['scene'], r['triangles'], r['renderer'], fmt(r['seconds']), fmt(r['samples_per_s'], 1e6),
            fmt(r['rays_per_s'], 1e6), fmt(r['ratio_caustica_over_this'], 1, '%.2f'), spread,
            fmt(r['image_mean'], 1, '%.5f'), r['note']))


def summary(r):
    if r.get('samples_per_s'):
        s = '%8.3f s  %8.4f Msamples/s' % (r['seconds'], r['samples_per_s'] / 1e6)
        if r.get('rays_per_s'):
            s += '  %8.3f Mrays/s' % (r['rays_per_s'] / 1e6)
        return s + '  mean %.5f' % r['image_mean'] + ('  (%s)' % r['note'] if r.get('note') else '')
    return r.get('note', 'no result')


if __name__ == '__main__':
    main()
