"""Reading exported CAD files back with OpenCASCADE (OCP, in the dev venv only) and rhino3dm,
and measuring them against batten's own surface: for tests/test_cad_export.py."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing, BRepBuilderAPI_Transform
from OCP.BRepGProp import BRepGProp_Domain, BRepGProp_Face, BRepGProp_Vinert
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
from OCP.Bnd import Bnd_Box
from OCP.gp import gp_Ax2, gp_Dir, gp_Pln, gp_Pnt, gp_Trsf
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.Interface import Interface_Static
from OCP.ShapeAnalysis import ShapeAnalysis_FreeBounds, ShapeAnalysis_Surface
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound


def read_shape(path: Path):
    """The shape of an IGES or STEP file (every root transferred), in metres: OCCT converts
    the file's own units (which batten writes as metres) to its session unit, set to metres
    here (its default is millimetres)."""
    reader = IGESControl_Reader() if path.suffix.lower() in (".igs", ".iges") else STEPControl_Reader()
    # The parameter exists once a reader has registered its controller.
    assert Interface_Static.SetCVal_s("xstep.cascade.unit", "M"), "OCCT's session unit"
    assert reader.ReadFile(str(path)) == IFSelect_RetDone, f"OCCT cannot read {path}"
    reader.TransferRoots()
    return reader.OneShape()


def faces(shape) -> list:
    """The faces of ``shape``."""
    out = []
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        out.append(TopoDS.Face(exp.Current()))
        exp.Next()
    return out


class Surfaces:
    """Surfaces with their bounding boxes, for the distance of points to the nearest one."""

    def __init__(self, surfaces: list, boxes: np.ndarray):
        self.analysers = [ShapeAnalysis_Surface(s) for s in surfaces]
        self.boxes = boxes

    @classmethod
    def of_faces(cls, fs: list) -> Surfaces:
        boxes = []
        for f in fs:
            box = Bnd_Box()
            BRepBndLib.Add_s(f, box)
            lo, hi = box.CornerMin(), box.CornerMax()
            boxes.append((lo.X(), lo.Y(), lo.Z(), hi.X(), hi.Y(), hi.Z()))
        return cls([BRep_Tool.Surface_s(f) for f in fs], np.array(boxes))

    def distances(self, points: np.ndarray, margin: float = 1e-3) -> np.ndarray:
        """Distance of each point to the nearest surface (foot points inside the surfaces'
        parameter ranges), trying the surfaces whose box (grown by ``margin``) holds it."""
        lo, hi = self.boxes[:, :3] - margin, self.boxes[:, 3:] + margin
        out = np.full(len(points), np.inf)
        for k, p in enumerate(points):
            inside = np.nonzero(np.all((p >= lo) & (p <= hi), axis=1))[0]
            q = gp_Pnt(*map(float, p))
            for i in inside:
                a = self.analysers[i]
                a.ValueOfUV(q, 1e-9)
                out[k] = min(out[k], a.Gap())
        return out


def sew(fs: list, tolerance: float):
    """The faces sewn (BRepBuilderAPI_Sewing at ``tolerance``) and the number of free edges."""
    sewing = BRepBuilderAPI_Sewing(tolerance)
    for f in fs:
        sewing.Add(f)
    sewing.Perform()
    return sewing.SewedShape(), sewing.NbFreeEdges()


def mirrored(shape):
    """``shape`` mirrored about the centreplane y = 0."""
    t = gp_Trsf()
    t.SetMirror(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0)))
    return BRepBuilderAPI_Transform(shape, t, True).Shape()


def compound(shapes: list):
    """The shapes as one compound."""
    c = TopoDS_Compound()
    b = BRep_Builder()
    b.MakeCompound(c)
    for s in shapes:
        b.Add(c, s)
    return c


def free_edge_count(shape) -> int:
    """Edges of the free boundary of ``shape``."""
    fb = ShapeAnalysis_FreeBounds(shape)
    n = 0
    for wires in (fb.GetClosedWires(), fb.GetOpenWires()):
        exp = TopExp_Explorer(wires, TopAbs_EDGE)
        while exp.More():
            n += 1
            exp.Next()
    return n


def volume_below(shape, draft: float, size: float) -> float:
    """OCCT's volume (BRepGProp_Vinert) between the half-hull faces of ``shape`` below the
    plane z = ``draft`` and the centreplane y = 0: the faces are cut at the waterplane
    (BRepAlgoAPI_Cut with a box above it), and each face's volume to the plane y = 0 summed
    (the lid at the waterplane is horizontal, so it adds nothing to a volume taken to y = 0)."""
    box = BRepPrimAPI_MakeBox(gp_Pnt(-size, -size, draft), 2 * size, 2 * size, size).Shape()
    below = BRepAlgoAPI_Cut(shape, box).Shape()
    plane = gp_Pln(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0))
    total = 0.0
    for f in faces(below):
        g = BRepGProp_Face(f)
        d = BRepGProp_Domain(f)
        total += BRepGProp_Vinert(g, d, plane, gp_Pnt(0, 0, 0)).Mass()
    return abs(total)


def rhino_surfaces(path: Path) -> list:
    """The NurbsSurface objects of a .3dm file."""
    import rhino3dm

    doc = rhino3dm.File3dm.Read(str(path))
    assert doc is not None, f"rhino3dm cannot read {path}"
    return [o.Geometry for o in doc.Objects if isinstance(o.Geometry, rhino3dm.NurbsSurface)]
