#!/bin/bash
# The quadtree 2D figures of docs/benchmarks.md: fepre mesh2d --json on the 20 closed-solid
# corpus STEP files, one table row each. Usage: tools/bench_mesh2d.sh FEPRE CORPUS
# (writes its JSON, timings and errors under /tmp/qt_*).
B=$1; C=$2
for f in occt-cube.step occt-cylinder.step red_cube_blue_cylinder.step base_interface_AP214.STEP Angled.step featuretype.STEP Kurbelwelle.stp Zylkopf.stp wing_fuselage.step part.step t20_data.step abc-0035.step mambo_s34.step linkrods.step box_sides.STEP abc-0000.step bug32745_pmi1.stp as1-tu-203.stp screw.step occt-sphere.step; do
  /usr/bin/time -f "%e" -o /tmp/qt_time_$f $B mesh2d $C/$f --json > /tmp/qt_json_$f 2>/tmp/qt_err_$f || echo "FAIL $f $(head -c 300 /tmp/qt_err_$f)"
done
python3 - <<'PY'
import json
files="occt-cube.step occt-cylinder.step red_cube_blue_cylinder.step base_interface_AP214.STEP Angled.step featuretype.STEP Kurbelwelle.stp Zylkopf.stp wing_fuselage.step part.step t20_data.step abc-0035.step mambo_s34.step linkrods.step box_sides.STEP abc-0000.step bug32745_pmi1.stp as1-tu-203.stp screw.step occt-sphere.step".split()
T=dict(planar=0,meshed=0,failed=0,tri=0); mins=dict(inside=999,band=999,off=999,at=999); tt=0; ms=0; allbal=True
print("| file | planar faces | meshed | failed | triangles | levels | inside min | band min (at boundary) | band min off boundary | smallest input angle | mesh s | total s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for f in files:
    try: r=json.load(open('/tmp/qt_json_'+f))
    except Exception as e: print("|",f,"| error |"); continue
    t=float(open('/tmp/qt_time_'+f).read().split()[-1])
    at=min([p['angles']['band_at_boundary'][0] for p in r['per_face'] if p['angles']['band_at_boundary'][0] is not None] or [float('nan')])
    nn=lambda x: float('nan') if x is None else x
    r['inside_angles']=[nn(x) for x in r['inside_angles']]; r['band_angles']=[nn(x) for x in r['band_angles']]; r['band_off_boundary_min']=nn(r['band_off_boundary_min']); r['input_smallest_angle']=nn(r['input_smallest_angle'])
    T['planar']+=r['planar_faces']; T['meshed']+=r['meshed']; T['failed']+=len(r['failed']); T['tri']+=r['triangles']
    allbal &= r['balanced']
    if r['meshed'] and r['band_angles'][0]==r['band_angles'][0]:
        mins['inside']=min(mins['inside'],r['inside_angles'][0]); mins['band']=min(mins['band'],r['band_angles'][0]); mins['off']=min(mins['off'],r['band_off_boundary_min']); mins['at']=min(mins['at'],at)
    tt+=t; ms+=r['seconds'][1]
    fmt=lambda x: "-" if x is None or x==float('inf') or x!=x else "%.2f"%x
    print(f"| {f} | {r['planar_faces']} | {r['meshed']} | {len(r['failed'])} | {r['triangles']} | {r['levels'][0] if r['meshed'] else '-'}..{r['levels'][1] if r['meshed'] else '-'} | {fmt(r['inside_angles'][0])} | {fmt(r['band_angles'][0])} ({fmt(at)}) | {fmt(r['band_off_boundary_min'])} | {fmt(r['input_smallest_angle'])} | {r['seconds'][1]:.3f} | {t:.2f} |")
    for x in r['failed']: print("  failed:", f, x)
print(f"| **all 20** | {T['planar']} | {T['meshed']} | {T['failed']} | {T['tri']} | | {mins['inside']:.2f} | {mins['band']:.2f} ({mins['at']:.2f}) | {mins['off']:.2f} | | {ms:.2f} | {tt:.2f} |")
print("balanced everywhere:", allbal)
PY
