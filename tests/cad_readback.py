"""Reading exported CAD files back with OpenCASCADE (OCP, in the dev venv only) and rhino3dm,
and measuring them against batten's own surface: for tests/test_cad_export.py."""

from __future__ import annotations

from itertools import pairwise
from pathlib import Path

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeSolid,
    BRepBuilderAPI_MakeWire,
    BRepBuilderAPI_Sewing,
    BRepBuilderAPI_Transform,
)
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
from OCP.gp import gp_Ax2, gp_Dir, gp_Pln, gp_Pnt, gp_Trsf
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.Interface import Interface_Static
from OCP.ShapeAnalysis import ShapeAnalysis_FreeBounds, ShapeAnalysis_Surface
from OCP.ShapeFix import ShapeFix_Solid
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

#: The relative error OCCT's volume integration is asked for: far below the 1e-4 checked.
VOLUME_RELATIVE_ERROR = 1e-9


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


def _sub_shapes(shape, kind, cast) -> list:
    """The sub-shapes of ``shape`` of TopAbs ``kind``, each cast (TopoDS.Face, TopoDS.Edge)."""
    out = []
    exp = TopExp_Explorer(shape, kind)
    while exp.More():
        out.append(cast(exp.Current()))
        exp.Next()
    return out


def faces(shape) -> list:
    """The faces of ``shape``."""
    return _sub_shapes(shape, TopAbs_FACE, TopoDS.Face)


def edges(shape) -> list:
    """The edges of ``shape``."""
    return _sub_shapes(shape, TopAbs_EDGE, TopoDS.Edge)


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


def edge_points(edge, n: int = 9) -> np.ndarray:
    """``n`` points evenly spaced in parameter along ``edge``, its ends first and last."""
    c = BRepAdaptor_Curve(edge)
    ts = np.linspace(c.FirstParameter(), c.LastParameter(), n)
    return np.array([(p.X(), p.Y(), p.Z()) for p in map(c.Value, ts)])


def free_edges(shape, tolerance: float) -> list:
    """The edges of the free boundary of ``shape`` (ShapeAnalysis_FreeBounds at ``tolerance``)."""
    free = ShapeAnalysis_FreeBounds(shape, tolerance, False, False)
    return edges(free.GetClosedWires()) + edges(free.GetOpenWires())


def _plane_of(points: np.ndarray, tolerance: float) -> tuple[int, float] | None:
    """The axis-aligned plane (axis, value) all ``points`` lie in, if any."""
    for axis in range(3):
        if np.ptp(points[:, axis]) <= tolerance:
            return axis, float(points[0, axis])
    return None


def _wire(chain: list, tolerance: float):
    """The edges of ``chain`` (any order, any direction) joined end to end into a wire."""
    wire = BRepBuilderAPI_MakeWire()
    at = None
    while chain:
        for i, e in enumerate(chain):
            start, end = edge_points(e, 2)
            if at is None or min(np.linalg.norm(start - at), np.linalg.norm(end - at)) <= tolerance:
                at = end if at is None or np.linalg.norm(start - at) <= tolerance else start
                wire.Add(chain.pop(i))
                break
        else:
            raise AssertionError(f"the free edges of a lid do not join at {at}")
    assert wire.IsDone(), "a lid's wire"
    return wire.Wire()


def planar_lids(shell, planes: list[tuple[int, float]], tolerance: float) -> list:
    """Planar faces closing the free boundary of ``shell``, one per plane of ``planes``
    (axis, value; the first a free edge lies in takes it). Each plane's free edges form a
    chain; where it ends on the neighbouring lids, it is closed along the planes' common
    lines: straight back between its ends for two lids, through the point where all three
    planes meet for three (centreplane, waterplane and transom)."""
    chains: dict[int, list] = {}
    for e in free_edges(shell, tolerance):
        pts = edge_points(e)
        k = next((k for k, (a, v) in enumerate(planes) if np.all(np.abs(pts[:, a] - v) <= tolerance)), None)
        assert k is not None, f"a free edge from {pts[0]} to {pts[-1]} lies in none of {planes}"
        chains.setdefault(k, []).append(e)
    corner = np.zeros(3)
    for axis, value in planes:
        corner[axis] = value
    lids = []
    for k, chain in chains.items():
        ends = np.array([p for e in chain for p in edge_points(e, 2)])
        lone = [p for p in ends if np.sum(np.linalg.norm(ends - p, axis=1) <= tolerance) == 1]
        assert len(lone) in (0, 2), f"a lid's chain with {len(lone)} loose ends"
        if lone:
            a, b = lone
            path = [b, corner, a] if len(chains) == 3 else [b, a]
            chain += [BRepBuilderAPI_MakeEdge(gp_Pnt(*p), gp_Pnt(*q)).Edge() for p, q in pairwise(path)]
        # On the plane itself: a boundary off it by less than the tolerance (KCS's imported
        # profile curve lies up to 0.11 mm off the centreplane) still bounds a lid.
        axis, value = planes[k]
        origin, normal = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
        origin[axis], normal[axis] = value, 1.0
        lid = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(*origin), gp_Dir(*normal)), _wire(chain, tolerance), True)
        assert lid.IsDone(), "a planar lid"
        lids.append(lid.Face())
    return lids


def volume_below(half, draft: float, size: float, tolerance: float) -> float:
    """OCCT's volume (BRepGProp.VolumeProperties) of the whole hull below the plane z =
    ``draft``: the sewn half shell cut at the waterplane (BRepAlgoAPI_Cut with a box of side
    ``size`` above it), closed with planar lids on the centreplane, the waterplane and (where
    the hull has one) the transom's plane, sewn into a solid, doubled."""
    box = BRepPrimAPI_MakeBox(gp_Pnt(-size, -size, draft), 2 * size, 2 * size, size).Shape()
    below = BRepAlgoAPI_Cut(half, box).Shape()
    planes = [(1, 0.0), (2, draft)]
    rest = [
        p
        for e in free_edges(below, tolerance)
        for p in edge_points(e)
        if abs(p[1]) > tolerance and abs(p[2] - draft) > tolerance
    ]
    if rest:
        transom = _plane_of(np.array(rest), tolerance)
        assert transom is not None, "the free boundary off the centreplane and waterplane is not planar"
        planes.append(transom)
    closed, left = sew(faces(below) + planar_lids(below, planes, tolerance), tolerance)
    assert left == 0, f"the lidded hull still has {left} free edges"
    shell = _sub_shapes(closed, TopAbs_SHELL, TopoDS.Shell)[0]
    solid = ShapeFix_Solid(BRepBuilderAPI_MakeSolid(shell).Solid())
    solid.Perform()
    props = GProp_GProps()
    # Adaptive Gauss integration to this relative error: OCCT's default fixed rule is off by
    # 4e-5 on the frigate's stern faces.
    BRepGProp.VolumeProperties_s(solid.Solid(), props, VOLUME_RELATIVE_ERROR)
    return 2 * abs(props.Mass())


def rhino_surfaces(path: Path) -> list:
    """The NurbsSurface objects of a .3dm file."""
    import rhino3dm

    doc = rhino3dm.File3dm.Read(str(path))
    assert doc is not None, f"rhino3dm cannot read {path}"
    return [o.Geometry for o in doc.Objects if isinstance(o.Geometry, rhino3dm.NurbsSurface)]
