#!/usr/bin/env python3
"""Sweep fepre over the fetched CAD parts (STEP) and meshes (STL/OBJ).

Idempotent: a (file, fepre binary sha256) already in results_*.jsonl is skipped, so a re-run
with a newer binary (--fepre PATH) adds that binary's records next to the old ones; the
summary uses the records of the binary given.  OCC / trimesh references are computed once
(step/occ.jsonl, mesh/trimesh.jsonl).  One child process at a time, under nice.

  run_sweep.py [--fepre PATH] [--phase occ,tess,stepmesh,mesh] [--summary-only] [--limit N]
"""
import argparse, hashlib, json, os, re, shutil, statistics, subprocess, sys, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# the fetched parts (tools/fetch_parts.sh puts them there): never in the repository
HERE = os.path.abspath(os.environ.get('FEPRE_FETCHED', os.path.join(ROOT, '..', 'fetched')))
STEP_DIR, MESH_DIR = f'{HERE}/step', f'{HERE}/mesh'
OCC_JSONL, TRI_JSONL = f'{STEP_DIR}/occ.jsonl', f'{MESH_DIR}/trimesh.jsonl'
RES_STEP, RES_MESH = f'{HERE}/results_step.jsonl', f'{HERE}/results_mesh.jsonl'
PY = os.environ.get('FEPRE_PYTHON', sys.executable)
OCPREF = os.path.join(os.environ.get('FEPRE_SHARED', os.path.join(ROOT, '..', 'shared')), 'tools', 'occ', 'ocpref.py')
TMP = '/tmp/fepre_sweep'
TIMEOUT = 300  # per fepre mesh / tetgen run; --timeout


def sha(path):
    h = hashlib.sha256()
    with open(path, 'rb') as f:
        for b in iter(lambda: f.read(1 << 20), b''):
            h.update(b)
    return h.hexdigest()[:16]


def load(path):
    out = []
    if os.path.exists(path):
        for line in open(path):
            line = line.strip()
            if line:
                try:
                    out.append(json.loads(line))
                except Exception:
                    pass
    return out


def append(path, rec):
    with open(path, 'a') as f:
        f.write(json.dumps(rec) + '\n')


def run(cmd, timeout):
    t0 = time.time()
    try:
        p = subprocess.run(['nice', '-n', '10', 'timeout', '-k', '10', str(timeout)] + cmd,
                           capture_output=True, timeout=timeout + 30)
        rc, so, se = p.returncode, p.stdout.decode('utf8', 'replace'), p.stderr.decode('utf8', 'replace')
    except subprocess.TimeoutExpired:
        rc, so, se = 124, '', 'driver timeout'
    return rc, so, se, round(time.time() - t0, 3)


def parse_json(so):
    try:
        d = json.loads(so)
    except Exception:
        i = so.find('{')
        try:
            d = json.loads(so[i:]) if i >= 0 else None
        except Exception:
            d = None
    if isinstance(d, dict):
        for k in ('face_table', 'contacts_list'):
            d.pop(k, None)
    return d


def slim_tess(d):
    if not d:
        return None
    keep = ['solids', 'surface_model_shells', 'sewing', 'faces', 'triangles', 'watertight', 'watertight_of',
            'open_surface', 'euler', 'volume', 'area', 'units', 'deviation', 'chord_mm', 'dropped', 'notes',
            'failed_faces', 'seconds', 'certificate', 'warnings']
    r = {k: d.get(k) for k in keep if k in d}
    for k in ('euler', 'failed_faces', 'dropped', 'notes', 'warnings'):
        if isinstance(r.get(k), list) and len(json.dumps(r[k])) > 3000:
            r[k] = r[k][:10] + [f'... {len(d[k])} in all']
    return r


def slim_mesh(d):
    if not d:
        return None
    keep = ['seconds', 'nodes', 'tets', 'regions', 'volume', 'cad_volume', 'volume_error', 'min_dihedral_deg',
            'max_dihedral_deg', 'max_radius_edge', 'tets_under_5_deg', 'tets_under_1_deg', 'tets_under_10_deg',
            'tets_under_10_deg_unexplained', 'refinement_stopped', 'refinement_stop', 'small_input_angles',
            'smallest_input_angle', 'narrow', 'mesher', 'warnings', 'worst_tet']
    r = {k: d.get(k) for k in keep if k in d}
    if isinstance(r.get('narrow'), dict) and len(json.dumps(r['narrow'])) > 2000:
        r['narrow'] = {k: v for k, v in r['narrow'].items() if not isinstance(v, list)}
    return r


def tail(s, n=800):
    s = s.strip()
    return s[-n:]


# ---------------------------------------------------------------- references
def occ_phase(files, limit):
    done = {r['file'] for r in load(OCC_JSONL)}
    for f in files[:limit]:
        b = os.path.basename(f)
        if b in done:
            continue
        rc, so, se, dt = run([PY, OCPREF, f], 120)
        rec = None
        for line in so.splitlines():
            try:
                rec = json.loads(line)
            except Exception:
                pass
        if rec is None:
            rec = dict(file=b, error=f'rc={rc} ' + tail(se, 300))
        rec['occ_wall_s'] = dt
        append(OCC_JSONL, rec)
        print('occ', b, rec.get('solids'), rec.get('valid'), dt, flush=True)


TRI_CODE = r'''
import sys, json, trimesh, numpy as np
m = trimesh.load(sys.argv[1], force='mesh', process=True)
r = dict(triangles=int(len(m.faces)), vertices=int(len(m.vertices)),
         is_watertight=bool(m.is_watertight), is_winding_consistent=bool(m.is_winding_consistent))
try:
    r['bodies'] = len(m.split(only_watertight=False))
except Exception as ex:
    r['bodies'] = None; r['split_error'] = repr(ex)[:100]
try:
    r['volume'] = float(m.volume)
except Exception as ex:
    r['volume'] = None
r['bbox'] = [float(x) for x in m.extents]
print(json.dumps(r))
'''


def tri_phase(files, limit):
    done = {r['file'] for r in load(TRI_JSONL)}
    for f in files[:limit]:
        b = os.path.basename(f)
        if b in done:
            continue
        rc, so, se, dt = run([PY, '-c', TRI_CODE, f], 120)
        try:
            rec = json.loads(so.strip().splitlines()[-1])
        except Exception:
            rec = dict(error=f'rc={rc} ' + tail(se, 300))
        rec['file'] = b
        rec['format'] = ('binary' if not open(f, 'rb').read(6).lower().startswith(b'solid') else 'ascii') \
            if f.lower().endswith('.stl') else 'obj'
        rec['closed_single_body'] = bool(rec.get('is_watertight') and rec.get('bodies') == 1)
        append(TRI_JSONL, rec)
        print('tri', b, rec.get('closed_single_body'), dt, flush=True)


# ---------------------------------------------------------------- fepre
def tess_phase(fepre, fsha, files, limit):
    done = {r['file'] for r in load(RES_STEP) if r.get('fepre_sha') == fsha and 'tess_rc' in r}
    os.makedirs(TMP, exist_ok=True)
    for f in files[:limit]:
        b = os.path.basename(f)
        if b in done:
            continue
        rc, so, se, dt = run([fepre, 'tessellate', f, '-o', f'{TMP}/out.stl', '--json'], 300)
        rec = dict(file=b, fepre_sha=fsha, tess_rc=rc, tess_wall_s=dt, tess=slim_tess(parse_json(so)),
                   tess_stderr=tail(se))
        append(RES_STEP, rec)
        print('tess', b, rc, dt, flush=True)


def stepmesh_phase(fepre, fsha, limit):
    recs = [r for r in load(RES_STEP) if r.get('fepre_sha') == fsha]
    done = {r['file'] for r in recs if 'mesh_rc' in r}
    todo = [r['file'] for r in recs if r.get('tess_rc') == 0 and r['file'] not in done]
    for b in todo[:limit]:
        f = f'{STEP_DIR}/{b}'
        rc, so, se, dt = run([fepre, 'mesh', f, '-o', f'{TMP}/out.vtu', '--json'], TIMEOUT)
        rec = dict(file=b, fepre_sha=fsha, mesh_rc=rc, mesh_wall_s=dt, mesh=slim_mesh(parse_json(so)),
                   mesh_stderr=tail(se))
        append(RES_STEP, rec)
        print('stepmesh', b, rc, dt, (rec['mesh'] or {}).get('min_dihedral_deg'), flush=True)


def tetgen_stats(text):
    r = {}
    m = re.search(r'Smallest dihedral:\s*([0-9.eE+-]+)', text)
    if m:
        r['min_dihedral_deg'] = float(m.group(1))
    m = re.search(r'Mesh tetrahedra:\s*(\d+)', text)
    if m:
        r['tets'] = int(m.group(1))
    m = re.search(r'Mesh points:\s*(\d+)', text)
    if m:
        r['nodes'] = int(m.group(1))
    return r


def mesh_phase(fepre, fsha, files, limit):
    tri = {r['file']: r for r in load(TRI_JSONL)}
    done = {r['file'] for r in load(RES_MESH) if r.get('fepre_sha') == fsha}
    os.makedirs(TMP, exist_ok=True)
    for f in files[:limit]:
        b = os.path.basename(f)
        if b in done:
            continue
        rec = dict(file=b, fepre_sha=fsha)
        rc, so, se, dt = run([fepre, 'inspect', f, '--json'], 300)
        d = parse_json(so) or {}
        rec.update(inspect_rc=rc, inspect_wall_s=dt,
                   inspect={k: d.get(k) for k in ('components', 'closed', 'manifold', 'oriented', 'volume',
                                                  'self_intersections', 'genus', 'euler') if k in d},
                   inspect_stderr=tail(se, 300) if rc else '')
        rc, so, se, dt = run([fepre, 'mesh', f, '-o', f'{TMP}/out.vtu', '--json'], TIMEOUT)
        rec.update(mesh_rc=rc, mesh_wall_s=dt, mesh=slim_mesh(parse_json(so)), mesh_stderr=tail(se))
        if tri.get(b, {}).get('closed_single_body'):
            tg = f'{TMP}/tg'
            shutil.rmtree(tg, ignore_errors=True)
            os.makedirs(tg)
            # TetGen's STL reader takes ASCII only: convert (not timed)
            run([PY, '-c', "import trimesh,sys; trimesh.load(sys.argv[1], force='mesh').export(sys.argv[2], file_type='stl_ascii')",
                 f, f'{tg}/in.stl'], 120)
            rc, so, se, dt = run(['tetgen', '-pq1.414/18', '-V', f'{tg}/in.stl'], TIMEOUT)
            rec.update(tetgen_rc=rc, tetgen_wall_s=dt, tetgen=tetgen_stats(so + se),
                       tetgen_err=tail(so + se, 300) if rc else '')
            shutil.rmtree(tg, ignore_errors=True)
        append(RES_MESH, rec)
        print('mesh', b, rec['mesh_rc'], rec['mesh_wall_s'], rec.get('tetgen_wall_s'), flush=True)


# ---------------------------------------------------------------- summary
def merged_step(fsha):
    out = {}
    for r in load(RES_STEP):
        if r.get('fepre_sha') == fsha:
            out.setdefault(r['file'], {}).update(r)
    return out


def first_line(s):
    s = re.sub(re.escape(HERE) + r'/(step|mesh)/\S+?: ', '', (s or '').strip())
    lines = [l for l in s.splitlines() if l.strip()]
    for l in lines:
        if l.lower().startswith('error'):
            return l[:300]
    return (lines[-1] if lines else '')[:300]


def summarize(fsha, fepre):
    src = json.load(open(f'{HERE}/sources.json')) if os.path.exists(f'{HERE}/sources.json') else {}
    occ = {r['file']: r for r in load(OCC_JSONL)}
    tri = {r['file']: r for r in load(TRI_JSONL)}
    st = merged_step(fsha)
    L = [f'# fepre sweep on fetched parts', '', f'binary `{fepre}` sha256[:16] `{fsha}`', '']
    files = sorted(os.path.basename(f) for f in step_files())
    n = len(files)
    valid = [b for b in files if occ.get(b, {}).get('valid') is True and (occ[b].get('solids') or 0) >= 1]
    rows, agree, off, cnt_mismatch = [], [], [], []
    groups = {}
    for b in files:
        r, o = st.get(b, {}), occ.get(b, {})
        t = r.get('tess') or {}
        if 'tess_rc' not in r:
            continue
        fam = src.get(b, {}).get('family', '?')
        if r['tess_rc'] == 0:
            # fepre reports volume in mm^3 already (checked on inch files: as1_pe_203, STP3593), not file units
            fv = (t.get('volume') or 0)
            ov = o.get('solid_volume_mm3')
            rel = (fv - ov) / ov if ov else None
            r['_rel'] = rel
            same_n = t.get('solids') == o.get('solids')
            if o.get('valid') is True and (o.get('solids') or 0) >= 1 and same_n and rel is not None and abs(rel) <= 0.005:
                agree.append(b)
            else:
                if rel is None or abs(rel) > 0.005:
                    off.append(b)
                if not same_n:
                    cnt_mismatch.append(b)
        else:
            c = t.get('certificate') or {}
            if c.get('failures'):
                f0 = c['failures'][0]
                checks = sorted({x.get('check') for x in c['failures'] if isinstance(x, dict)})
                msg = re.sub(r'#?\d+(\.\d+)?(e[+-]?\d+)?', 'N', str(f0.get('message', f0)))
                msg = re.sub(r"'[^']*'|\([^)]*\)", '…', msg)
                key = f"certificate {f0.get('check')}: {msg[:110]}"
                ex = f"{len(c['failures'])} failures, checks {checks}; first: {f0.get('message')}"[:300]
            elif r['tess_rc'] in (124, 137):
                key, ex = 'timeout 300 s', ''
            else:
                msg = first_line(r.get('tess_stderr'))
                key = re.sub(r'#?\d+(\.\d+)?(e[+-]?\d+)?', 'N', msg)[:140]
                ex = msg
            groups.setdefault(key, []).append((b, fam, ex))
    ndone = sum(1 for b in files if 'tess_rc' in st.get(b, {}))
    L += ['## STEP', '', f'- files: {n}; tessellated so far: {ndone}; OCC-valid with ≥1 solid: {len(valid)}',
          f'- fepre exit 0: {sum(1 for b in files if st.get(b, {}).get("tess_rc") == 0)}',
          f'- exit 0 AND OCC-valid AND same solid count AND |ΔV| ≤ 0.5 %: {len(agree)}',
          f'- exit 0 with |ΔV| > 0.5 % vs OCC solid volume: {len(off)}; exit 0 with solid count ≠ OCC: {len(cnt_mismatch)}', '']
    if off or cnt_mismatch:
        L += ['### exit 0 but disagrees with OpenCASCADE', '', '| file | system | fepre solids | OCC solids | OCC valid | fepre V mm³ | OCC solid V mm³ | rel | units |', '|---|---|---|---|---|---|---|---|---|']
        for b in sorted(set(off) | set(cnt_mismatch)):
            r, o = st[b], occ.get(b, {})
            t = r['tess']
            to_mm = 1.0  # volume already in mm^3
            L.append(f"| {b} | {src.get(b, {}).get('family', '?')} | {t.get('solids')} | {o.get('solids')} | {o.get('valid')} | "
                     f"{(t.get('volume') or 0) * to_mm ** 3:.6g} | {o.get('solid_volume_mm3')} | "
                     f"{r['_rel'] if r.get('_rel') is None else round(r['_rel'] * 100, 3)}% | {(t.get('units') or {}).get('length')} |")
        L.append('')
    L += ['### tessellate failures by cause', '']
    for k, v in sorted(groups.items(), key=lambda kv: -len(kv[1])):
        fams = sorted({x[1] for x in v})
        L.append(f'- **{len(v)}** `{k}` — e.g. {", ".join(x[0] for x in v[:2])}; systems: {", ".join(fams)}')
        L.append(f'  - text: `{v[0][2][:300]}`')
    # mesh of STEP
    L += ['', '### fepre mesh on certified STEP', '']
    for label, pred in (('single solid', lambda t: t.get('solids') == 1), ('assembly (≥2 solids)', lambda t: (t.get('solids') or 0) >= 2)):
        sel = [b for b in files if st.get(b, {}).get('tess_rc') == 0 and pred(st[b]['tess']) and 'mesh_rc' in st[b]]
        ok10 = [b for b in sel if st[b]['mesh_rc'] == 0 and ((st[b].get('mesh') or {}).get('min_dihedral_deg') or 0) >= 10]
        rc0 = [b for b in sel if st[b]['mesh_rc'] == 0]
        L.append(f'- {label}: meshed {len(sel)}, exit 0 {len(rc0)}, min dihedral ≥ 10° {len(ok10)}')
    mg = {}
    for b in files:
        r = st.get(b, {})
        if r.get('mesh_rc') not in (None, 0):
            msg = 'timeout' if r['mesh_rc'] in (124, 137) else first_line(r.get('mesh_stderr'))
            mg.setdefault(re.sub(r'[-0-9.]+(e[+-]?\d+)?', 'N', msg)[:140], []).append((b, src.get(b, {}).get('family', '?'), msg))
    for k, v in sorted(mg.items(), key=lambda kv: -len(kv[1])):
        L.append(f'  - **{len(v)}** `{k}` — e.g. {", ".join(x[0] for x in v[:2])}; systems: {", ".join(sorted({x[1] for x in v}))}')
    lowd = [b for b in files if st.get(b, {}).get('mesh_rc') == 0 and ((st[b].get('mesh') or {}).get('min_dihedral_deg') or 0) < 10]
    for b in lowd[:10]:
        m = st[b]['mesh']
        L.append(f'  - exit 0 but min dihedral {m.get("min_dihedral_deg")}: {b} (small input angles {m.get("small_input_angles")}, smallest {m.get("smallest_input_angle")})')
    # meshes
    mr = {}
    for r in load(RES_MESH):
        if r.get('fepre_sha') == fsha:
            mr[r['file']] = r
    mfiles = sorted(os.path.basename(f) for f in mesh_files())
    closed = [b for b in mfiles if tri.get(b, {}).get('closed_single_body')]
    L += ['', '## Meshes (STL/OBJ)', '', f'- files: {len(mfiles)}; processed {len(mr)}; trimesh closed single body: {len(closed)}']
    c10 = [b for b in closed if b in mr and mr[b]['mesh_rc'] == 0 and ((mr[b].get('mesh') or {}).get('min_dihedral_deg') or 0) >= 10]
    a10 = [b for b in mfiles if b in mr and mr[b]['mesh_rc'] == 0 and ((mr[b].get('mesh') or {}).get('min_dihedral_deg') or 0) >= 10]
    L.append(f'- fepre mesh exit 0 with min dihedral ≥ 10°: closed single bodies {len(c10)}/{len([b for b in closed if b in mr])}, all files {len(a10)}/{len(mr)}')
    ratios, tr, ir = [], [], []
    tg10 = 0
    for b in closed:
        r = mr.get(b)
        if not r or r.get('tetgen_rc') != 0 or r['mesh_rc'] != 0:
            continue
        if (r.get('tetgen') or {}).get('min_dihedral_deg', 0) >= 10:
            tg10 += 1
        if r.get('tetgen_wall_s'):
            ratios.append(r['mesh_wall_s'] / r['tetgen_wall_s'])
            ir.append(r['inspect_wall_s'] / r['tetgen_wall_s'])
        if (r.get('tetgen') or {}).get('tets') and (r.get('mesh') or {}).get('tets'):
            tr.append(r['mesh']['tets'] / r['tetgen']['tets'])
    tgfail = [b for b in closed if b in mr and mr[b].get('tetgen_rc') not in (None, 0)]
    if ratios:
        L.append(f'- fepre mesh / tetgen wall time (both exit 0, n={len(ratios)}): median {statistics.median(ratios):.2f}, max {max(ratios):.2f}; fepre inspect / tetgen median {statistics.median(ir):.2f}, max {max(ir):.2f}')
    if tr:
        L.append(f'- tets fepre / tetgen: median {statistics.median(tr):.2f}, min {min(tr):.2f}, max {max(tr):.2f}; tetgen ≥ 10°: {tg10}; tetgen failed: {len(tgfail)} {tgfail[:3]}')
    mg = {}
    for b, r in mr.items():
        if r['mesh_rc'] != 0:
            msg = 'timeout' if r['mesh_rc'] in (124, 137) else first_line(r.get('mesh_stderr'))
            mg.setdefault(re.sub(r'[-0-9.]+(e[+-]?\d+)?', 'N', msg)[:140], []).append((b, msg, tri.get(b, {}).get('closed_single_body')))
    L.append('- fepre mesh failures:')
    for k, v in sorted(mg.items(), key=lambda kv: -len(kv[1])):
        L.append(f'  - **{len(v)}** (closed single bodies among them: {sum(1 for x in v if x[2])}) `{k}` — e.g. {", ".join(x[0] for x in v[:2])}')
        L.append(f'    - text: `{v[0][1][:300]}`')
    lowd = [b for b in closed if b in mr and mr[b]['mesh_rc'] == 0 and ((mr[b].get('mesh') or {}).get('min_dihedral_deg') or 0) < 10]
    for b in lowd[:10]:
        L.append(f'  - closed single body, exit 0, min dihedral {mr[b]["mesh"].get("min_dihedral_deg")}: {b}')
    open(f'{HERE}/summary.md', 'w').write('\n'.join(L) + '\n')
    print('\n'.join(L))


def step_files():
    return sorted(f'{STEP_DIR}/{b}' for b in os.listdir(STEP_DIR) if re.search(r'\.(step|stp)$', b, re.I))


def mesh_files():
    return sorted(f'{MESH_DIR}/{b}' for b in os.listdir(MESH_DIR) if re.search(r'\.(stl|obj)$', b, re.I))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--fepre', default=os.path.join(ROOT, 'target', 'release', 'fepre'))
    ap.add_argument('--phase', default='tess,occ,tri,mesh,stepmesh')
    ap.add_argument('--limit', type=int, default=10 ** 9)
    ap.add_argument('--summary-only', action='store_true')
    ap.add_argument('--timeout', type=int, default=300, help='seconds per fepre mesh / tetgen run')
    a = ap.parse_args()
    global TIMEOUT
    TIMEOUT = a.timeout
    fepre = os.path.abspath(a.fepre)
    fsha = sha(fepre)
    if not a.summary_only:
        for ph in a.phase.split(','):
            if ph == 'occ':
                occ_phase(step_files(), a.limit)
            elif ph == 'tri':
                tri_phase(mesh_files(), a.limit)
            elif ph == 'tess':
                tess_phase(fepre, fsha, step_files(), a.limit)
            elif ph == 'stepmesh':
                stepmesh_phase(fepre, fsha, a.limit)
            elif ph == 'mesh':
                mesh_phase(fepre, fsha, mesh_files(), a.limit)
    summarize(fsha, fepre)


if __name__ == '__main__':
    main()
