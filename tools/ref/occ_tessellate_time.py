"""fepre's read + tessellate + certify against OpenCASCADE's read + BRepMesh, every STEP file of
a folder, in one Python process (issue 14's speed line).

Per file, first `FEPRE tessellate FILE -o TMP.stl --json` in a child process: its wall time
(process start-up and the STL write included) and the phases it reports in its JSON
(`read_seconds`, `tessellate_seconds`, `certificate.seconds`; `phases` below is their sum,
the figure the acceptance line speaks of) and the absolute chord it used (`chord_mm`, its
default 2e-4 of the model's bounding-box diagonal). Then OpenCASCADE in this process, timed
with time.perf_counter (Python's start-up and imports not counted): STEPControl_Reader
ReadFile + TransferRoots + OneShape, then BRepMesh_IncrementalMesh at the same absolute linear
deflection and an angular deflection of ANGLE radians (default 0.349 = 20 degrees, fepre's
largest tangent turn along an edge segment; OCC's own default is 0.5). A file either tool
fails on is reported, never a crash. Triangles are counted outside the timings.

Usage: python tools/ref/occ_tessellate_time.py FEPRE CORPUS_DIR [--angle RAD] [--parallel]
         [--repeat N] [--timeout S] [--warm-up] [--json FILE]
  (cadquery-ocp 8.0.1, e.g. /work/main/.venv/bin/python). --parallel: BRepMesh in parallel
  (default off: fepre tessellates on one thread). --repeat N: each file N times (fepre, OCC,
  fepre, OCC, ...), every figure the median of the N (default 1). --warm-up: read and mesh the smallest file
  once, untimed, before the run (OCC's one-time STEP initialisation is otherwise charged to the
  first file). --timeout: seconds per fepre run (default 600).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

from OCP.STEPControl import STEPControl_Reader
from OCP.IFSelect import IFSelect_RetDone
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRep import BRep_Tool
from OCP.TopLoc import TopLoc_Location
from OCP.TopExp import TopExp_Explorer
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS
from OCP.Bnd import Bnd_Box
from OCP.BRepBndLib import BRepBndLib

STEP_EXT = ('.step', '.stp')


def step_files(folder):
    return sorted((f for f in os.listdir(folder) if f.lower().endswith(STEP_EXT)), key=str.lower)


def run_fepre(fepre, path, out, timeout):
    """fepre's figures for one file: wall, phases, chord, triangles, status."""
    r = dict(wall=None, read=None, tess=None, cert=None, phases=None, chord=None, tris=None, status='')
    t0 = time.perf_counter()
    try:
        p = subprocess.run([fepre, 'tessellate', path, '-o', out, '--json'], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        r['status'] = f'fepre timed out after {timeout} s'
        return r
    r['wall'] = time.perf_counter() - t0
    try:
        j = json.loads(p.stdout)
    except ValueError:
        msg = (p.stderr.strip().splitlines() or ['no output'])[-1]
        r['status'] = f'fepre exit {p.returncode}: {msg[:100]}'
        return r
    if j.get('tessellated'):
        # AP242 tessellated-only geometry: no chord, no phases beyond the total
        r.update(tris=j.get('triangles'), phases=j.get('seconds'), status='fepre: tessellated-only file')
        return r
    cert = j.get('certificate') or {}
    r.update(read=j.get('read_seconds'), tess=j.get('tessellate_seconds'), cert=cert.get('seconds'), chord=j.get('chord_mm'), tris=j.get('triangles'))
    if None not in (r['read'], r['tess'], r['cert']):
        r['phases'] = r['read'] + r['tess'] + r['cert']
    if p.returncode != 0:
        r['status'] = f"fepre exit {p.returncode}: certificate {'passed' if cert.get('passed') else 'FAILED'}"
    elif not cert.get('passed'):
        r['status'] = 'fepre: certificate failed'
    return r


def occ_read(path):
    rd = STEPControl_Reader()
    if rd.ReadFile(path) != IFSelect_RetDone:
        raise RuntimeError('ReadFile failed')
    rd.TransferRoots()
    shape = rd.OneShape()
    if shape.IsNull():
        raise RuntimeError('no shape transferred')
    return shape


def occ_diagonal(shape):
    b = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, b, False, False)
    if b.IsVoid():
        return None
    lo, hi = b.CornerMin(), b.CornerMax()
    return math.sqrt((hi.X() - lo.X()) ** 2 + (hi.Y() - lo.Y()) ** 2 + (hi.Z() - lo.Z()) ** 2)


def occ_triangles(shape):
    n, bare = 0, 0
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        t = BRep_Tool.Triangulation_s(TopoDS.Face(ex.Current()), TopLoc_Location())
        if t is None:
            bare += 1
        else:
            n += t.NbTriangles()
        ex.Next()
    return n, bare


class quiet_fds:
    """OCC's own messages (parse errors of a broken file) written to the C streams are
    dropped while it runs, so that they do not break the table."""

    def __enter__(self):
        sys.stdout.flush()
        sys.stderr.flush()
        self.saved = [os.dup(1), os.dup(2)]
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, 1)
        os.dup2(null, 2)
        os.close(null)

    def __exit__(self, *exc):
        for fd, saved in zip((1, 2), self.saved):
            os.dup2(saved, fd)
            os.close(saved)
        return False


def run_occ(path, chord, angle, parallel):
    """OCC's figures for one file: read and mesh seconds, triangles, status. `chord` None: 2e-4
    of OCC's own bounding-box diagonal (fepre gave none)."""
    r = dict(read=None, mesh=None, total=None, tris=None, chord=chord, diag=None, status='')
    try:
        t0 = time.perf_counter()
        shape = occ_read(path)
        t1 = time.perf_counter()
        r['read'] = t1 - t0
        if chord is None:
            d = occ_diagonal(shape)
            if not d:
                raise RuntimeError('empty bounding box')
            r['chord'] = chord = 2e-4 * d
            r['status'] = 'chord from OCC box'
            t1 = time.perf_counter()
        m = BRepMesh_IncrementalMesh(shape, chord, False, angle, parallel)
        t2 = time.perf_counter()
        r['mesh'] = t2 - t1
        r['total'] = r['read'] + r['mesh']
        if not m.IsDone():
            r['status'] = 'BRepMesh not done'
        r['tris'], bare = occ_triangles(shape)
        if bare:
            r['status'] = (r['status'] + '; ' if r['status'] else '') + f'{bare} faces unmeshed'
        r['diag'] = occ_diagonal(shape)
    except Exception as ex:  # noqa: BLE001 -- a file OCC fails on is reported, not a crash
        r['status'] = f'OCC: {ex!r}'[:100]
    return r


def median_of(runs):
    """The per-key median of the runs' numbers (a key missing from any run: the first run's
    value); the statuses joined."""
    out = dict(runs[0])
    for k, v in runs[0].items():
        xs = [r[k] for r in runs]
        if k == 'status':
            out[k] = '; '.join(dict.fromkeys(x for x in xs if x))
        elif all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in xs):
            xs = sorted(xs)
            n = len(xs)
            out[k] = xs[n // 2] if n % 2 else type(xs[0])((xs[n // 2 - 1] + xs[n // 2]) / 2)
    return out


def fmt(x, spec='.3f'):
    return '-' if x is None else format(x, spec)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('fepre')
    ap.add_argument('corpus')
    ap.add_argument('--angle', type=float, default=math.radians(20.0))
    ap.add_argument('--parallel', action='store_true')
    ap.add_argument('--timeout', type=float, default=600.0)
    ap.add_argument('--repeat', type=int, default=1)
    ap.add_argument('--warm-up', action='store_true')
    ap.add_argument('--json', metavar='FILE', help='also write the per-file figures as JSON lines')
    a = ap.parse_args()
    files = step_files(a.corpus)
    if not files:
        sys.exit(f'no STEP files in {a.corpus}')
    if a.warm_up:
        small = min(files, key=lambda f: os.path.getsize(os.path.join(a.corpus, f)))
        try:
            s = occ_read(os.path.join(a.corpus, small))
            BRepMesh_IncrementalMesh(s, 1.0, False, 0.5, False)
        except Exception:  # noqa: BLE001
            pass
    print(f'corpus {a.corpus}: {len(files)} STEP files; fepre {a.fepre}')
    print(f'OCC: STEPControl_Reader + BRepMesh_IncrementalMesh(linear = fepre chord_mm, absolute; angular {a.angle:.4f} rad = {math.degrees(a.angle):.1f} deg; parallel {a.parallel})')
    if a.repeat > 1:
        print(f'every figure the median of {a.repeat} runs of the file; totals the sums of the medians')
    print('fepre s = read + tessellate + certify as fepre reports them; wall = the fepre process, start-up and STL write included')
    hdr = f"{'file':<30} {'fepre s':>8} {'read':>6} {'tess':>6} {'cert':>6} {'wall':>6} {'OCC s':>7} {'read':>6} {'mesh':>6} {'ratio':>6} {'fepre tri':>10} {'OCC tri':>10} {'chord mm':>9}  status"
    print(hdr)
    print('-' * len(hdr))
    per_file = []  # (fepre seconds, file) of the files in the totals
    tot = dict(fp=0.0, fw=0.0, fr=0.0, ft=0.0, fc=0.0, occ=0.0, orr=0.0, om=0.0, ftri=0, otri=0, n=0)
    failed = []
    log = open(a.json, 'w') if a.json else None
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, 'x.stl')
        for f in files:
            path = os.path.join(a.corpus, f)
            frs, ors = [], []
            for _ in range(max(1, a.repeat)):
                frs.append(run_fepre(a.fepre, path, out, a.timeout))
                with quiet_fds():
                    ors.append(run_occ(path, frs[-1]['chord'], a.angle, a.parallel))
            fr, orr = median_of(frs), median_of(ors)
            status = '; '.join(s for s in (fr['status'], orr['status']) if s)
            # the chord fepre used against 2e-4 of OCC's box: a unit or box mismatch shows here
            if fr['chord'] and orr['diag'] and abs(fr['chord'] / (2e-4 * orr['diag']) - 1) > 0.05:
                status = (status + '; ' if status else '') + f"chord = {fr['chord'] / orr['diag']:.2e} of OCC's diagonal"
            ratio = fr['phases'] / orr['total'] if fr['phases'] is not None and orr['total'] else None
            print(f"{f[:30]:<30} {fmt(fr['phases']):>8} {fmt(fr['read']):>6} {fmt(fr['tess']):>6} {fmt(fr['cert']):>6} {fmt(fr['wall']):>6} "
                  f"{fmt(orr['total']):>7} {fmt(orr['read']):>6} {fmt(orr['mesh']):>6} {fmt(ratio, '.2f'):>6} "
                  f"{fmt(fr['tris'], 'd'):>10} {fmt(orr['tris'], 'd'):>10} {fmt(orr['chord'], '.2e'):>9}  {status}", flush=True)
            if log:
                log.write(json.dumps(dict(file=f, fepre=fr, occ=orr, ratio=ratio, status=status)) + '\n')
            if fr['phases'] is None or orr['total'] is None or fr['read'] is None:
                failed.append(f)
                continue
            tot['n'] += 1
            per_file.append((fr['phases'], f, fr['tess'], fr['cert']))
            tot['fp'] += fr['phases']
            tot['fw'] += fr['wall']
            tot['fr'] += fr['read']
            tot['ft'] += fr['tess']
            tot['fc'] += fr['cert']
            tot['occ'] += orr['total']
            tot['orr'] += orr['read']
            tot['om'] += orr['mesh']
            tot['ftri'] += fr['tris'] or 0
            tot['otri'] += orr['tris'] or 0
    if log:
        log.close()
    print('-' * len(hdr))
    print(f"{'TOTAL (' + str(tot['n']) + ' files)':<30} {tot['fp']:>8.3f} {tot['fr']:>6.3f} {tot['ft']:>6.3f} {tot['fc']:>6.3f} {tot['fw']:>6.3f} "
          f"{tot['occ']:>7.3f} {tot['orr']:>6.3f} {tot['om']:>6.3f} {tot['fp'] / tot['occ'] if tot['occ'] else float('nan'):>6.2f} {tot['ftri']:>10d} {tot['otri']:>10d}")
    print(f"fepre read+tessellate+certify {tot['fp']:.3f} s (process wall {tot['fw']:.3f} s), OCC read+BRepMesh {tot['occ']:.3f} s: "
          f"ratio {tot['fp'] / tot['occ'] if tot['occ'] else float('nan'):.2f} (wall {tot['fw'] / tot['occ'] if tot['occ'] else float('nan'):.2f}); "
          f"triangles fepre {tot['ftri']}, OCC {tot['otri']}")
    if per_file and tot['fp'] > 0:
        top = sorted(per_file, reverse=True)[:5]
        print('slowest in fepre: ' + ', '.join(f"{f} {t:.3f} s ({100 * t / tot['fp']:.0f} %: tessellate {ts:.3f}, certify {c:.3f})" for t, f, ts, c in top))
    if failed:
        print(f"left out of the totals (failed or tessellated-only in either tool): {', '.join(failed)}")


if __name__ == '__main__':
    main()
