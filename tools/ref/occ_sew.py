"""OpenCASCADE's sewing of a STEP file, for comparing fepre's (`sewing` in `fepre tessellate
--json`): BRepBuilderAPI_Sewing at 1e-6 of the bounding-box diagonal (fepre's tolerance), then
the free edges left as closed wires (ShapeAnalysis_FreeBounds): edges, length, centre.

Usage: python tools/ref/occ_sew.py FILE...   (cadquery-ocp, e.g. /work/main/.venv/bin/python)
"""
import sys
from OCP.STEPControl import STEPControl_Reader
from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing
from OCP.ShapeAnalysis import ShapeAnalysis_FreeBounds
from OCP.TopExp import TopExp_Explorer
from OCP.TopAbs import TopAbs_EDGE, TopAbs_WIRE
from OCP.GProp import GProp_GProps
from OCP.BRepGProp import BRepGProp
from OCP.Bnd import Bnd_Box
from OCP.BRepBndLib import BRepBndLib

for path in sys.argv[1:]:
    rd = STEPControl_Reader()
    rd.ReadFile(path)
    rd.TransferRoots()
    s = rd.OneShape()
    box = Bnd_Box()
    BRepBndLib.Add_s(s, box)
    lo, hi = box.CornerMin(), box.CornerMax()
    size = ((hi.X() - lo.X()) ** 2 + (hi.Y() - lo.Y()) ** 2 + (hi.Z() - lo.Z()) ** 2) ** 0.5
    sw = BRepBuilderAPI_Sewing(1e-6 * size)
    sw.Add(s)
    sw.Perform()
    print(path.split('/')[-1], 'tolerance %.3e' % (1e-6 * size), 'free edges', sw.NbFreeEdges(), 'multiple', sw.NbMultipleEdges())
    wires = ShapeAnalysis_FreeBounds(sw.SewedShape()).GetClosedWires()
    ex = TopExp_Explorer(wires, TopAbs_WIRE)
    while ex.More():
        g = GProp_GProps()
        BRepGProp.LinearProperties_s(ex.Current(), g)
        c = g.CentreOfMass()
        e = TopExp_Explorer(ex.Current(), TopAbs_EDGE)
        n = 0
        while e.More():
            n += 1
            e.Next()
        print('  free wire: %d edges, %.6f mm, centre (%.4f, %.4f, %.4f)' % (n, g.Mass(), c.X(), c.Y(), c.Z()))
        ex.Next()
