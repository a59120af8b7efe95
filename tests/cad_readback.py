"""Reading exported CAD files back with OpenCASCADE (OCP, in the dev venv only) and rhino3dm,
and measuring them against batten's own surface: for tests/test_cad_export.py."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Tool
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeSolid,
    BRepBuilderAPI_Sewing,
    BRepBuilderAPI_Transform,
)
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Trsf
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.Interface import Interface_Static
from OCP.ShapeAnalysis import ShapeAnalysis_FreeBounds, ShapeAnalysis_Surface
from OCP.ShapeFix import ShapeFix_Solid
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS


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


def volume_below(half, draft: float, size: float, tolerance: float) -> float:
    """OCCT's volume (BRepGProp.VolumeProperties) of the hull below the plane z = ``draft``:
    the sewn half shell mirrored and sewn to itself, cut at the waterplane (BRepAlgoAPI_Cut
    with a box above it), closed with a planar lid on each free boundary wire (the
    waterline, a transom's immersed edge) and sewn into a solid."""
    full, _ = sew([half, mirrored(half)], tolerance)
    box = BRepPrimAPI_MakeBox(gp_Pnt(-size, -size, draft), 2 * size, 2 * size, size).Shape()
    below = BRepAlgoAPI_Cut(full, box).Shape()
    wires = ShapeAnalysis_FreeBounds(below, tolerance, False, False).GetClosedWires()
    lids = []
    exp = TopExp_Explorer(wires, TopAbs_WIRE)
    while exp.More():
        lid = BRepBuilderAPI_MakeFace(TopoDS.Wire(exp.Current()), True)
        assert lid.IsDone(), "a planar lid on the free boundary"
        lids.append(lid.Face())
        exp.Next()
    closed, free = sew(faces(below) + lids, tolerance)
    assert free == 0, f"the lidded hull still has {free} free edges"
    exp = TopExp_Explorer(closed, TopAbs_SHELL)
    solid = ShapeFix_Solid(BRepBuilderAPI_MakeSolid(TopoDS.Shell(exp.Current())).Solid())
    solid.Perform()
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(solid.Solid(), props)
    return abs(props.Mass())


def rhino_surfaces(path: Path) -> list:
    """The NurbsSurface objects of a .3dm file."""
    import rhino3dm

    doc = rhino3dm.File3dm.Read(str(path))
    assert doc is not None, f"rhino3dm cannot read {path}"
    return [o.Geometry for o in doc.Objects if isinstance(o.Geometry, rhino3dm.NurbsSurface)]
