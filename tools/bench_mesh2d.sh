#!/bin/bash
# The 2D methods' figures on CAD faces in docs/benchmarks.md: fepre mesh2d --json on every
# planar face of the closed-solid corpus STEP files, once per method, one table row per method
# (faces meshed, elements, angles, the median element size over the size, the quads' scaled
# Jacobian, seconds). A method written M+quads runs `--method M --quads`.
# Usage: tools/bench_mesh2d.sh FEPRE CORPUS [METHODS...]   (writes its JSON under /tmp/m2d_*)
B=$1; C=$2; shift 2
METHODS=${*:-"delaunay ear recursive removal front quadtree"}
FILES="occt-cube.step occt-cylinder.step red_cube_blue_cylinder.step base_interface_AP214.STEP Angled.step featuretype.STEP Kurbelwelle.stp Zylkopf.stp wing_fuselage.step part.step t20_data.step abc-0035.step mambo_s34.step linkrods.step box_sides.STEP abc-0000.step bug32745_pmi1.stp as1-tu-203.stp screw.step occt-sphere.step"
for m in $METHODS; do
  for f in $FILES; do
    flags="--method ${m%+quads}"; [ "${m%+quads}" != "$m" ] && flags="$flags --quads"
    $B mesh2d $C/$f $flags --json > /tmp/m2d_${m}_$f.json 2>/tmp/m2d_${m}_$f.err || echo "FAIL $m $f $(head -c 300 /tmp/m2d_${m}_$f.err)"
  done
done
METHODS="$METHODS" FILES="$FILES" python3 - <<'PY'
import json, os, statistics
files = os.environ["FILES"].split(); methods = os.environ["METHODS"].split()
print("| method | planar faces | meshed | failed | triangles | quads | min angle ° | triangles < 20° | < 30° | median size ratio | quad SJ min (median) | mesh s |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for m in methods:
    T = dict(planar=0, meshed=0, failed=0, tri=0, quad=0, u20=0, u30=0, s=0.0); amin = 999.0; ratios = []; sjmin = float('inf'); sjmed = []
    for f in files:
        try: r = json.load(open(f"/tmp/m2d_{m}_{f}.json"))
        except Exception: T['failed'] += 1; continue
        T['planar'] += r['planar_faces']; T['meshed'] += r['meshed']; T['failed'] += len(r['failed'])
        T['tri'] += r['triangles']; T['quad'] += r['quads']; T['s'] += r['seconds'][1]
        for p in r['per_face']:
            q = p['quality']
            if q['angle_range'][0] is not None: amin = min(amin, q['angle_range'][0])
            T['u20'] += q['triangles_under'][0]; T['u30'] += q['triangles_under'][1]
            if q['size_ratio'][1] is not None: ratios.append(q['size_ratio'][1])
            if q['quad_scaled_jacobian'][0] is not None: sjmin = min(sjmin, q['quad_scaled_jacobian'][0]); sjmed.append(q['quad_scaled_jacobian'][1])
    med = statistics.median(ratios) if ratios else float('nan')
    sj = f"{sjmin:.3f} ({statistics.median(sjmed):.3f})" if sjmed else "-"
    print(f"| {m} | {T['planar']} | {T['meshed']} | {T['failed']} | {T['tri']:,} | {T['quad']:,} | {amin:.2f} | {T['u20']:,} | {T['u30']:,} | {med:.2f} | {sj} | {T['s']:.2f} |")
PY
