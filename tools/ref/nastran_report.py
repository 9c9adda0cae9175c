#!/usr/bin/env python3
"""Independent reading of a Nastran bulk data deck with pyNastran, for comparison with what
fepre's `write_nastran` says it wrote (tests/deck_nastran.rs).

Usage: nastran_report.py DECK...   -> one JSON object per deck, one a line, on stdout:
  sol, subcases {id: {SPC, LOAD, METHOD}}, grids {id: [x, y, z]}, elements {id: [pid, grids]},
  psolids {pid: mid}, materials {mid: [E, nu, rho]}, spc_dofs (grid-dof pairs on SPC1 and SPC
  cards, all sets), spc_values {sid: [[enforced value, SPC pairs with it]]}, force_cards, force_total (sum of F times N over FORCE cards),
  pload4_cards, pload4_total (sum of pressure x area x pyNastran's face normal, the face found
  from G1 and G4), grav {sid: [A N1, A N2, A N3]}, load_combinations {sid: [[scale, sid]]},
  eigrl {sid: ND}.
"""
import json
import sys

import numpy as np

# pyNastran 1.4.1 (the newest release) calls np.in1d, which numpy 2.4 removed; np.isin is the
# same function. With numpy < 2.4 this does nothing.
if not hasattr(np, "in1d"):
    np.in1d = np.isin

from pyNastran.bdf.bdf import read_bdf  # noqa: E402


def report(path):
    model = read_bdf(path, xref=True, punch=False, debug=None)
    subcases = {}
    for sid, sc in model.case_control_deck.subcases.items():
        if sid == 0:
            continue
        subcases[sid] = {key: sc.params[key][0] for key in ("SPC", "LOAD", "METHOD") if key in sc.params}
    grids = {nid: [float(c) for c in node.get_position()] for nid, node in model.nodes.items()}
    elements = {}
    for eid, elem in model.elements.items():
        assert elem.type == "CTETRA", elem.type
        elements[eid] = [elem.Pid(), [int(n) for n in elem.node_ids]]
    spc_dofs = 0
    spc_values = {}
    for sid, cards in model.spcs.items():
        for c in cards:
            if c.type == "SPC1":
                spc_dofs += len(c.nodes) * len(str(c.components))
            elif c.type == "SPC":
                spc_dofs += sum(len(str(comp)) for comp in c.components)
                for value in c.enforced:
                    counts = spc_values.setdefault(sid, {})
                    counts[float(value)] = counts.get(float(value), 0) + 1
            else:
                raise ValueError(c.type)
    force_cards, force_total = 0, np.zeros(3)
    pload4_cards, pload4_total = 0, np.zeros(3)
    grav = {}
    for sid, cards in model.loads.items():
        for c in cards:
            if c.type == "FORCE":
                force_cards += 1
                force_total += c.mag * np.asarray(c.xyz, dtype=float)
            elif c.type == "PLOAD4":
                pload4_cards += 1
                for elem in c.eids_ref:
                    _, area, _, normal = elem.get_face_area_centroid_normal(c.g1_ref.nid, c.g34_ref.nid)
                    pload4_total += c.pressures[0] * area * np.asarray(normal)
            elif c.type == "GRAV":
                grav[sid] = [float(v) for v in c.scale * np.asarray(c.N, dtype=float)]
            else:
                raise ValueError(c.type)
    load_combinations = {}
    for sid, cards in model.load_combinations.items():
        load_combinations[sid] = [[float(c.scale) * float(s), int(l)] for c in cards for s, l in zip(c.scale_factors, c.load_ids)]
    eigrl = {sid: method.nd for sid, method in model.methods.items() if method.type == "EIGRL"}
    return {
        "sol": model.sol,
        "subcases": subcases,
        "grids": grids,
        "elements": elements,
        "psolids": {pid: p.Mid() for pid, p in model.properties.items()},
        "materials": {mid: [m.e, m.nu, m.rho] for mid, m in model.materials.items()},
        "spc_dofs": spc_dofs,
        "spc_values": {sid: sorted([v, n] for v, n in counts.items()) for sid, counts in spc_values.items()},
        "force_cards": force_cards,
        "force_total": force_total.tolist(),
        "pload4_cards": pload4_cards,
        "pload4_total": pload4_total.tolist(),
        "grav": grav,
        "load_combinations": load_combinations,
        "eigrl": eigrl,
    }


if __name__ == "__main__":
    for deck in sys.argv[1:]:
        print(json.dumps(report(deck)))
