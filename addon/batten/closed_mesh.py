"""A closed copy of a hull's surface mesh for Blender's own STL and OBJ exporters: the surface
object as evaluated (its Mirror modifier applied: both halves), with a lid on its open rim
(the deck, and a transom where the hull has one) made of strips across the centreplane, so
that every edge has two faces."""

from __future__ import annotations

import bmesh
import bpy
from batten_native import ExportError

#: The suffix of the closed copy's name (``"<surface> closed"``).
CLOSED_SUFFIX = " closed"


def _remove_fins(bm, tolerance: float) -> None:
    """Remove the faces lying in the centreplane (every vertex within ``tolerance`` of y = 0):
    where the surface touches it (a quad at the corner of a keel and a stern post lying
    within the Mirror modifier's merge distance, or split along its diagonal in the plane),
    the mirror image of such a face is the face itself, a zero-volume fin whose edges have one,
    three or four faces. Edges and vertices left without faces go too."""
    fins = [f for f in bm.faces if all(abs(v.co.y) <= tolerance for v in f.verts)]
    bmesh.ops.delete(bm, geom=fins, context="FACES_ONLY")
    bmesh.ops.delete(bm, geom=[e for e in bm.edges if not e.link_faces], context="EDGES")
    bmesh.ops.delete(bm, geom=[v for v in bm.verts if not v.link_faces], context="VERTS")


def _boundary_loops(bm) -> list[list]:
    """The mesh's open boundary as closed loops of vertices, each in order along the loop."""
    following: dict = {}
    for e in bm.edges:
        if e.is_boundary:
            for a, b in ((e.verts[0], e.verts[1]), (e.verts[1], e.verts[0])):
                following.setdefault(a, []).append(b)
    if any(len(n) != 2 for n in following.values()):
        raise ExportError("the surface's open boundary touches itself; it cannot be closed with lids")
    loops, seen = [], set()
    for start in following:
        if start in seen:
            continue
        loop, previous, v = [start], None, start
        seen.add(start)
        while True:
            a, b = following[v]
            previous, v = v, (b if a is previous else a)
            if v is start:
                break
            loop.append(v)
            seen.add(v)
        loops.append(loop)
    return loops


def _strips(loop: list, tolerance: float) -> list[list]:
    """The lid of one rim ``loop`` of the mirrored surface: for every edge of the loop on the
    port side, the strip between it and its mirror image (a planar trapezoid, a triangle where
    it ends on the centreplane). Every strip is perpendicular to the centreplane (its normal
    has no y), as the lids of ``build``'s enclosed volume are: a flat deck becomes a lid in its
    plane, a transom one in the transom's."""
    # The Mirror modifier's images are exact (y negated, in the object's space).
    at = {tuple(v.co): v for v in loop}
    mirror = {}
    for v in loop:
        image = at.get((v.co.x, -v.co.y, v.co.z))
        if image is None:
            return []
        mirror[v] = image
    lid = []
    for a, b in zip(loop, loop[1:] + loop[:1], strict=True):
        if a.co.y < -tolerance or b.co.y < -tolerance or (mirror[a] is a and mirror[b] is b):
            continue
        corners = [a, b] + [v for v in (mirror[b], mirror[a]) if v not in (a, b)]
        lid.append(corners)
    return lid


def closed_copy(surface, tolerance: float):
    """A new mesh object ``"<surface> closed"`` (replacing an older one of that name) in the
    surface object's collections: ``surface`` as evaluated, in triangles without the
    centreplane's fins (:func:`_remove_fins`), with a lid on every open boundary loop at the
    top of the hull (:func:`_strips`), faces turned to point out of the solid; closed in the
    object's own space (where its mirror plane is y = 0), then placed in world coordinates.
    A loop below the top is a hole in the surface, and a loop without its mirror image a
    surface not mirrored: ExportError saying where, and nothing is made."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    mesh = bpy.data.meshes.new_from_object(surface.evaluated_get(depsgraph))
    bm = bmesh.new()
    try:
        bm.from_mesh(mesh)
        # Split as Blender's exporters split quads (corners 0–2): a fin may be half a quad.
        bmesh.ops.triangulate(bm, faces=bm.faces[:], quad_method="FIXED")
        _remove_fins(bm, tolerance)
        top = max(v.co.z for v in bm.verts)
        for loop in _boundary_loops(bm):
            if max(v.co.z for v in loop) < top - tolerance:
                at = min(loop, key=lambda v: v.co.z).co
                raise ExportError(
                    f"'{surface.name}': the surface has a hole near ({at.x:.3f}, {at.y:.3f}, "
                    f"{at.z:.3f}) m, below its top; build it without holes before closing it"
                )
            strips = _strips(loop, tolerance)
            if not strips:
                raise ExportError(
                    f"'{surface.name}': its open boundary through ({loop[0].co.x:.3f}, "
                    f"{loop[0].co.y:.3f}, {loop[0].co.z:.3f}) m is not symmetric about the "
                    "centreplane (no Mirror modifier, or a hole); build it mirrored and whole"
                )
            for corners in strips:
                bm.faces.new(corners)
        bmesh.ops.recalc_face_normals(bm, faces=bm.faces[:])
        bm.to_mesh(mesh)
        mesh.transform(surface.matrix_world)
    except BaseException:
        bpy.data.meshes.remove(mesh)
        raise
    finally:
        bm.free()
    name = surface.name + CLOSED_SUFFIX
    old = bpy.data.objects.get(name)
    if old is not None:
        bpy.data.objects.remove(old)
    mesh.name = name
    obj = bpy.data.objects.new(name, mesh)
    for collection in surface.users_collection:
        collection.objects.link(obj)
    return obj
