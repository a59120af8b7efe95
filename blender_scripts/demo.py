"""batten demo, headless: draw each example network as Blender curves, then write
``<out>/<name>.blend``, a report ``<out>/<name>.json`` and a render ``<out>/<name>.png``; then
import the real ships' sections (``shared/hulls`` beside the checkout) with every setting at its
default, build them the same way and render them from the bow, the stern and the side, and
write their hydrostatics at the design draft (logged beside the reference figures, and in
``<name>_hydrostatics.csv``), their sectional area curve ``<name>_sac.png`` and curves of form
``<name>_curves_of_form.png`` (and ``.csv``); the examples' too, at the draft the panel
starts at. Each hull's lines plan is written as ``<name>_lines_plan.svg`` and ``.png``,
and the whole hull (both halves, no curves) is rendered with its DWL from a three-quarter bow
view and from the side, framed to fill the picture: ``<name>_hull_bow.png``,
``<name>_hull_side.png``. Surface fairing is shown before and after on the Wigley lines
(Gaussian-curvature maps, ``fairing_*_gaussian_curvature.png``) and on KCS with noise of 30 %
of a 10 mm tolerance (reflection lines of the entrance, ``kcs_fairing_*_zebra.png``).

    make demo                                                   # from a checkout
    python blender_scripts/demo.py -- --out out                  # bpy module, batten on PYTHONPATH
    blender -b -P blender_scripts/demo.py -- --out out           # desktop Blender, batten installed

Options after ``--``: ``--out DIR`` (default ``out``), ``--examples DIR`` (default the repo's
``examples/``), ``--ships DIR`` (default ``../shared/hulls``), ``--engine WORKBENCH|CYCLES``,
``--size WxH``, ``--resolution N`` (segments per patch side), ``--zebra`` (also render
reflection lines, ``<name>_zebra.png``, on a mesh of at least 32 segments per patch side).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import bpy
import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def _log(msg: str) -> None:
    print(f"[batten demo] {msg}", flush=True)


def _import_batten():
    """batten from an installed extension, else from this checkout's addon/ folder."""
    import addon_utils

    for mod in addon_utils.modules():
        if mod.__name__.endswith(".batten") or mod.__name__ == "batten":
            addon_utils.enable(mod.__name__, default_set=True)
            return sys.modules[mod.__name__]
    sys.path.insert(0, str(ROOT / "addon"))
    import batten

    batten.register()
    return batten


def _args():
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="demo.py")
    ap.add_argument("--out", type=Path, default=Path("out"))
    ap.add_argument("--examples", type=Path, default=ROOT / "examples")
    ap.add_argument("--ships", type=Path, default=ROOT.parent / "shared" / "hulls")
    ap.add_argument("--engine", choices=["WORKBENCH", "CYCLES"], default="WORKBENCH")
    ap.add_argument("--size", default="1280x720")
    ap.add_argument("--resolution", type=int, default=12)
    ap.add_argument("--zebra", action="store_true")
    return ap.parse_args(argv)


def _bounds(objects):
    import numpy as np

    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for obj in objects:
        for corner in obj.bound_box:
            p = np.array(obj.matrix_world) @ np.array([*corner, 1.0])
            lo, hi = np.minimum(lo, p[:3]), np.maximum(hi, p[:3])
    return lo, hi


#: Tube radius on the curves, as a share of the model's largest extent: a ship is long and
#: slender, and its close-up views of the ends need finer tubes.
EXAMPLE_TUBE = 0.0025
SHIP_TUBE = 0.0008

#: Views: the camera's direction from the model (three-quarter bow: forward, to port, above;
#: three-quarter stern; the side from port, nearly level) and the share of the model's length
#: (aft, forward) it frames: a ship's ends are framed on their own, where its shape is.
VIEWS = {
    "model": ((0.7, 1.0, 0.45), (0.0, 1.0)),
    "bow": ((0.7, 1.0, 0.35), (0.68, 1.0)),
    "stern": ((-0.7, 1.0, 0.35), (0.0, 0.3)),
    "side": ((0.0, 1.0, 0.08), (0.0, 1.0)),
    "body": ((1.0, 0.0, 0.0), (0.0, 1.0)),
}


def aim_camera(scene, view: str, lo, hi) -> None:
    """Put the scene's camera for ``view`` (:data:`VIEWS`) on the box ``lo``–``hi``: on the
    view's direction from the centre of the framed part of the box, far enough that that part's
    bounding sphere fills the view."""
    from mathutils import Vector

    direction, (aft, fwd) = VIEWS[view]
    lo, hi = lo.copy(), hi.copy()
    length = hi[0] - lo[0]
    lo[0], hi[0] = lo[0] + aft * length, lo[0] + fwd * length
    cam = scene.camera
    centre = Vector(((lo + hi) / 2).tolist())
    d = Vector(direction).normalized()
    radius = 0.5 * float(((hi - lo) ** 2).sum() ** 0.5)
    half_fov = math.atan(0.5 * cam.data.sensor_width / cam.data.lens)
    cam.location = centre + d * (1.05 * radius / math.sin(half_fov))
    cam.rotation_euler = (-d).to_track_quat("-Z", "Y").to_euler()


def _stage(collection, engine: str, size: str, surface=None, tube: float = 0.0025):
    """Tubes on the curves (radius ``tube`` × the model's largest extent), the smooth surface,
    a three-quarter bow camera, light and world."""
    scene = bpy.context.scene
    lo, hi = _bounds(list(collection.objects) + ([surface] if surface is not None else []))
    extent = float(max(hi - lo))
    mat = bpy.data.materials.new("batten curve")
    mat.diffuse_color = (0.05, 0.2, 0.55, 1.0)
    for obj in collection.objects:
        obj.data.bevel_depth = tube * extent
        obj.data.bevel_resolution = 2
        obj.data.materials.append(mat)
        if obj.batten.role in {"keel", "stem", "transom", "deck", "knuckle"}:
            obj.data.bevel_depth *= 1.8
    if surface is not None:
        hull = bpy.data.materials.new("batten hull")
        hull.diffuse_color = (0.82, 0.80, 0.74, 1.0)
        hull.roughness = 0.35
        surface.data.materials.append(hull)
    cam_data = bpy.data.cameras.new("camera")
    cam_data.lens = 50
    cam = bpy.data.objects.new("camera", cam_data)
    scene.collection.objects.link(cam)
    scene.camera = cam
    aim_camera(scene, "model", lo, hi)
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(30))
    scene.collection.objects.link(sun)
    if scene.world is None:
        scene.world = bpy.data.worlds.new("world")
    scene.world.color = (0.95, 0.95, 0.97)
    w, h = (int(v) for v in size.lower().split("x"))
    scene.render.resolution_x, scene.render.resolution_y = w, h
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.view_settings.view_transform = "Standard"
    if engine == "CYCLES":
        scene.render.engine = "CYCLES"
        scene.cycles.device = "CPU"
        scene.cycles.samples = 32
    else:
        scene.render.engine = "BLENDER_WORKBENCH"
        scene.display.shading.light = "STUDIO"
        scene.display.shading.color_type = "MATERIAL"
        scene.display.render_aa = "8"
        scene.display.shading.background_type = "VIEWPORT"
        scene.display.shading.background_color = (0.95, 0.95, 0.97)


# Reflection lines: ZEBRA_STRIPES dark and as many light stripes across the matcap, evenly
# spaced in the vertical component of the view-space normal (about 13° of normal tilt per pair
# facing the camera), on ZEBRA_MATCAP_SIZE² texels; the surface is rebuilt with at least
# ZEBRA_RESOLUTION intervals per patch side for the render.
ZEBRA_STRIPES = 9
ZEBRA_MATCAP_SIZE = 1024
ZEBRA_RESOLUTION = 32


def zebra_matcap(path: Path, stripes: int = ZEBRA_STRIPES, size: int = ZEBRA_MATCAP_SIZE) -> Path:
    """Write a reflection-line matcap to ``path`` (PNG): ``stripes`` horizontal black and white
    stripe pairs, evenly spaced in the view-space normal's vertical component, with soft edges
    and nothing else.

    Blender's own ``check_reflection_horizontal`` matcap overlays its 11 stripe pairs with a
    fine checker (it is meant to show texture stretching); sampled through the normals of a
    hull a few hundred pixels across, that checker aliases into moiré, whatever the render's
    anti-aliasing. These stripes have no texture, and their edges are linear ramps of about a
    tenth of a period (some 10 texels), so the matcap is band-limited and the anti-aliasing
    samples resolve the stripes where the surface turns quickly.
    """
    import numpy as np

    v = (np.arange(size) + 0.5) / size * 2.0 - 1.0  # texel centres, bottom to top: normal y
    wave = np.cos(np.pi * stripes * v)
    ramp = 0.3  # |wave| below this is the soft edge: 2·asin(0.3)/π ≈ 0.19 of a half period
    grey = 0.05 + 0.9 * np.clip(0.5 + 0.5 * wave / ramp, 0.0, 1.0)
    pixels = np.ones((size, size, 4), dtype=np.float32)
    pixels[..., :3] = grey[:, None, None]
    image = bpy.data.images.new("batten zebra matcap", size, size, alpha=False)
    image.pixels.foreach_set(pixels.ravel())
    image.filepath_raw = str(path)
    image.file_format = "PNG"
    image.save()
    bpy.data.images.remove(image)
    return path


def render_zebra(scene, collection, filepath: Path) -> None:
    """Render reflection lines, as naval architects judge fairness: Workbench with the
    :func:`zebra_matcap` on the surface, the curve tubes hidden (their own stripes would hide
    the surface's), 32 anti-aliasing samples. Scene settings and tubes are restored after."""
    import tempfile

    shading = scene.display.shading
    saved = (shading.light, shading.studio_light, shading.color_type, tuple(shading.single_color))
    saved_render = (scene.render.engine, scene.display.render_aa)
    lights = bpy.context.preferences.studio_lights
    with tempfile.TemporaryDirectory(prefix="batten_zebra_") as tmp:
        light = lights.load(str(zebra_matcap(Path(tmp) / "batten_zebra.png")), "MATCAP")
        tubes = [o for o in collection.objects if not o.hide_render]
        try:
            for obj in tubes:
                obj.hide_render = True
            scene.render.engine = "BLENDER_WORKBENCH"
            shading.light = "MATCAP"
            shading.studio_light = light.name
            shading.color_type = "SINGLE"
            shading.single_color = (1.0, 1.0, 1.0)
            scene.display.render_aa = "32"
            scene.render.filepath = str(filepath.resolve())
            bpy.ops.render.render(write_still=True)
        finally:
            for obj in tubes:
                obj.hide_render = False
            shading.light, shading.studio_light, shading.color_type, shading.single_color = saved
            scene.render.engine, scene.display.render_aa = saved_render
            lights.remove(light)


def render_curvature(api, scene, collection, filepath: Path, kind: str, scale: float | None = None) -> dict:
    """Render the hull's curvature map (:func:`batten.api.show_curvature`, ``kind``): Workbench
    with the mesh's colour attribute unlit (flat: the colours are the figures, not shading),
    the curve tubes hidden. The map is
    cleared and the scene settings and tubes restored after. Returns the map's figures."""
    shading = scene.display.shading
    saved = (shading.light, shading.color_type)
    saved_render = scene.render.engine
    info = api.show_curvature(collection, kind=kind, scale=scale)
    tubes = [o for o in collection.objects if not o.hide_render]
    try:
        for obj in tubes:
            obj.hide_render = True
        scene.render.engine = "BLENDER_WORKBENCH"
        shading.light = "FLAT"
        shading.color_type = "VERTEX"
        scene.render.filepath = str(filepath.resolve())
        bpy.ops.render.render(write_still=True)
    finally:
        for obj in tubes:
            obj.hide_render = False
        shading.light, shading.color_type = saved
        scene.render.engine = saved_render
        api.clear_curvature(collection)
    return info


def run_example(api, path: Path, out: Path, engine: str, size: str, resolution: int, zebra: bool) -> dict:
    """An example network file: drawn as curves, built, reported, rendered, saved."""
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    t0 = time.perf_counter()
    coll = api.load_network(path)
    t_load = time.perf_counter() - t0
    _log(f"{coll.name}: drew {len(coll.objects)} curves from {path.name} in {t_load * 1e3:.1f} ms")
    report = deliver(
        api, coll, path, {"load_ms": round(t_load * 1e3, 3)}, out, engine, size, resolution, zebra
    )
    plot_hydrostatics(api, coll, out)
    present(api, coll, out, bpy.context.scene.batten.draft)
    return report


def run_ship(api, path: Path, out: Path, engine: str, size: str, resolution: int, zebra: bool) -> dict:
    """A real ship's sections (``shared/hulls/<ship>/network.json``, or an example's in
    ``examples/sections/``), imported and built with every setting at its default, as a new
    user would; rendered from the bow, the stern and the side."""
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    t0 = time.perf_counter()
    name = path.parent.name if path.stem == "network" else path.stem
    coll, fits = api.import_sections(path, collection=name)
    t_load = time.perf_counter() - t0
    worst = max(fits, key=lambda r: r["max_deviation"])
    _log(
        f"{coll.name}: imported {len(fits)} sections from {path} in {t_load:.2f} s; worst point "
        f"{worst['max_deviation'] * 1e3:.2f} mm from curve {worst['curve']}; "
        f"{sum(r['nodes'] > 0 for r in fits)} curves moved through their nodes "
        f"(largest move {max(r['snap_move'] for r in fits) * 1e3:.2f} mm)"
    )
    extra = {"import_s": round(t_load, 3), "fits": fits}
    reference = _reference(path)
    if reference is not None:
        # The ship's own perpendiculars (its x runs forward from the AP) and design draft, for
        # the API and the Hydrostatics panel (which starts at that draft).
        coll[api.LPP_PROPERTY] = coll[api.FP_PROPERTY] = reference["Lpp"]
        coll[api.DESIGN_DRAFT_PROPERTY] = reference["T"]
    report = deliver(
        api,
        coll,
        path,
        extra,
        out,
        engine,
        size,
        resolution,
        zebra,
        views=("bow", "stern", "side"),
        tube=SHIP_TUBE,
    )
    if reference is not None:
        plot_hydrostatics(api, coll, out, reference)
    present(api, coll, out, reference["T"] if reference else bpy.context.scene.batten.draft)
    return report


def _reference(path: Path) -> dict | None:
    """A real ship's ``reference.json`` beside its network (None for other section files)."""
    ref = path.parent / "reference.json"
    return json.loads(ref.read_text()) if path.stem == "network" and ref.is_file() else None


#: The curves of form of a hull span these shares of its design draft.
CURVES_OF_FORM_SPAN = (0.2, 1.2)
CURVES_OF_FORM_DRAFTS = 11


def _batten_module(api, name: str):
    """A module of the batten package ``api`` belongs to (installed as an extension, its
    package is not ``batten``)."""
    import importlib

    return importlib.import_module(f"{api.__package__}.{name}")


#: (figure key, key in a ship's ``reference.json`` "computed") compared in the log.
REFERENCE_KEYS = (
    ("volume", "displaced_volume"),
    ("lcb", "LCB_from_AP"),
    ("vcb", "VCB_above_baseline_brep"),
    ("waterplane_area", "waterplane_area"),
    ("lcf", "LCF_from_AP"),
    ("wetted_area", "wetted_surface_below_T"),
)


def plot_hydrostatics(api, coll, out: Path, reference: dict | None = None) -> None:
    """A hull's hydrostatics at its design draft (a real ship's, about its perpendiculars,
    beside its ``reference`` figures in the log; an example's at the draft the Hydrostatics
    panel starts at), in ``<name>_hydrostatics.csv``, its sectional area curve
    ``<name>_sac.png`` and curves of form ``<name>_curves_of_form.png`` (and ``.csv``). A
    hydrostatics error (a hole under water) is logged, and written on the sectional area curve,
    whose plane sections need no closed surface."""
    import numpy as np

    hydro_plot, hydro_table = _batten_module(api, "hydro_plot"), _batten_module(api, "hydro_table")
    name = coll.name
    draft = reference["T"] if reference else bpy.context.scene.batten.draft
    t0 = time.perf_counter()
    try:
        fig, note = api.hydrostatics(coll, draft), ""
    except api.BattenError as e:
        fig, note = None, str(e)
        _log(f"{name}: no figures ({e})")
    else:
        _log(f"{name}: hydrostatics at T = {draft:.3f} m in {(time.perf_counter() - t0) * 1e3:.1f} ms")
        ref = reference["computed"] if reference else {}
        for key, ref_key in REFERENCE_KEYS:
            if ref_key in ref:
                diff = 100 * (fig[key] / ref[ref_key] - 1)
                _log(f"{name}: {key} {fig[key]:.3f} (reference {ref[ref_key]}, {diff:+.3f} %)")
        hydro_table.hydrostatics_csv(fig, out / f"{name}_hydrostatics.csv")
    xs, areas = api.sectional_areas(coll, draft, 41)
    sac = out / f"{name}_sac.png"
    marks = fig or {"x_ap": xs[0], "x_fp": xs[-1], "draft_mid": draft}
    hydro_plot.sac_png(name, xs, areas, marks, sac, note=note)
    _log(f"{name}: sectional area curve {sac}")
    drafts = draft * np.linspace(*CURVES_OF_FORM_SPAN, CURVES_OF_FORM_DRAFTS)
    t0 = time.perf_counter()
    try:
        rows = api.curves_of_form(coll, drafts)
    except api.BattenError as e:
        _log(f"{name}: no curves of form: {e}")
        return
    t_cof = time.perf_counter() - t0
    cof = out / f"{name}_curves_of_form.png"
    hydro_plot.curves_of_form_png(name, rows, cof)
    hydro_table.curves_of_form_csv(rows, cof.with_suffix(".csv"))
    _log(f"{name}: curves of form ({len(rows)} drafts in {t_cof:.2f} s) {cof} and .csv")


def deliver(
    api,
    coll,
    path,
    extra: dict,
    out: Path,
    engine,
    size,
    resolution,
    zebra,
    views=("model",),
    tube: float = EXAMPLE_TUBE,
) -> dict:
    """Build the surface of ``coll``, log and write its report, render it (curve tubes of
    radius ``tube`` × its extent) from each of ``views`` (``<name>.png`` for the first,
    ``<name>_<view>.png`` for the others) with its reflection lines, and save the .blend."""
    bpy.context.scene.batten.source = coll
    curves = api.read_curves(coll)
    name = coll.name
    report = {
        "example": name,
        "source": str(path),
        "curves": [
            {
                "name": c.name,
                "role": c.role,
                "degree": c.degree,
                "control_points": len(c.control_points),
                "length_m": round(c.arc_length(1e-9), 6),
                "corners": len(c.corners()),
            }
            for c in curves
        ],
        **extra,
    }
    t0 = time.perf_counter()
    result = api.build(coll, resolution=resolution)
    t_build = time.perf_counter() - t0
    b = result.report
    sides = ", ".join(f"{c} {n}-sided" for n, c in sorted(b["faces_by_sides"].items()))
    faces = f"{b['faces']} patches ({sides}), {b['mesh_faces']} mesh faces"
    _log(f"{name}: built {faces} in {t_build * 1e3:.1f} ms")
    _log(
        f"{name}: max gap {b['max_gap']:.2e} m, max normal jump {b['max_normal_angle_deg']:.4f} deg, "
        f"{b['holes']} hole(s), {b['folds']} fold(s), "
        f"enclosed volume {b['enclosed_volume']:.2f} m3, {len(b['warnings'])} warning(s)"
    )
    for w in b["warnings"]:
        _log(f"{name}: warning ({w['kind']}): {w['message']}")
    report["surface"] = b
    report["surface"]["faces_by_sides"] = {str(k): v for k, v in b["faces_by_sides"].items()}
    report["build_ms"] = round(t_build * 1e3, 3)
    lo, hi = _bounds(coll.objects)
    report["bounds_m"] = {"min": lo.round(6).tolist(), "max": hi.round(6).tolist()}
    _stage(coll, engine, size, result.object, tube=tube)
    out.mkdir(parents=True, exist_ok=True)
    scene = bpy.context.scene
    view_lo, view_hi = _bounds(list(coll.objects) + [result.object])
    for i, view in enumerate(views):
        aim_camera(scene, view, view_lo, view_hi)
        png = out / (f"{name}.png" if i == 0 else f"{name}_{view}.png")
        scene.render.filepath = str(png.resolve())
        t0 = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        _log(f"{name}: rendered {png} ({engine}, {view}) in {time.perf_counter() - t0:.1f} s")
    if zebra:
        # Workbench interpolates the mesh's vertex normals linearly across each triangle, so a
        # coarse mesh shows its facets in the stripes where the hull turns quickly (the ends):
        # render a denser mesh, then put the reported one back.
        zebra_resolution = max(resolution, ZEBRA_RESOLUTION)
        if zebra_resolution != resolution:
            api.build(coll, resolution=zebra_resolution)
        for i, view in enumerate(views):
            aim_camera(scene, view, view_lo, view_hi)
            zpng = out / (f"{name}_zebra.png" if i == 0 else f"{name}_{view}_zebra.png")
            render_zebra(scene, coll, zpng)
            _log(f"{name}: rendered reflection lines {zpng} (resolution {zebra_resolution}, {view})")
        if zebra_resolution != resolution:
            api.build(coll, resolution=resolution)
    aim_camera(scene, views[0], view_lo, view_hi)
    report["curvature"] = {}
    for kind in CURVATURE_KINDS:
        cpng = out / f"{name}_{kind}_curvature.png"
        t0 = time.perf_counter()
        info = render_curvature(api, scene, coll, cpng, kind)
        report["curvature"][kind] = info
        _log(
            f"{name}: rendered the {kind} curvature {cpng} (blue {-info['scale']:.3g}, red "
            f"{info['scale']:.3g}; range {info['min']:.3g} to {info['max']:.3g}) in "
            f"{time.perf_counter() - t0:.1f} s"
        )
    blend = out / f"{name}.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend.resolve()))
    _log(f"{name}: saved {blend}")
    (out / f"{name}.json").write_text(json.dumps(report, indent=2) + "\n")
    _log(f"{name}: report {out / (name + '.json')}")
    return report


#: The curvature maps rendered for each hull (:func:`render_curvature`), from its first view.
CURVATURE_KINDS = ("gaussian", "mean")

#: The whole-hull renders: the camera's direction from the hull (three-quarter bow from port and
#: above; the side from starboard, level, so the bow is to the right as in a profile) and whether
#: the camera is orthographic (the side: its picture then as tall as the hull's shape asks).
HULL_VIEWS = {"bow": ((0.75, 1.0, 0.38), False), "side": ((0.0, -1.0, 0.0), True)}
#: The side view's picture is at least this share of its width tall.
SIDE_MIN_HEIGHT = 0.15
#: Share of the picture left free around a framed hull, each side.
FRAME_MARGIN = 0.04
#: Radius of the DWL's tube, as a share of the hull's length.
DWL_TUBE = 0.0012


def present(api, coll, out: Path, draft: float) -> None:
    """The lines plan of ``coll`` at ``draft`` (``<name>_lines_plan.svg`` and ``.png``), and
    renders of its whole hull with the DWL (``<name>_hull_<view>.png``). An error is logged."""
    name = coll.name
    t0 = time.perf_counter()
    try:
        drawing = api.lines_plan_drawing(coll, draft=draft)
        written = [api.write_lines_plan(drawing, out / f"{name}_lines_plan{ext}") for ext in (".svg", ".png")]
    except api.BattenError as e:
        _log(f"{name}: no lines plan ({e})")
    else:
        _log(f"{name}: lines plan {', '.join(map(str, written))} in {time.perf_counter() - t0:.1f} s")
    surface = next((o for o in bpy.data.objects if o.get(api.SURFACE_TAG) == name), None)
    if surface is None:
        _log(f"{name}: no surface to render")
        return
    render_hull(api, coll, surface, out, draft)


def _hull_points(surface):
    """The vertices of the surface as shown (its Mirror modifier applied), world coordinates."""
    import numpy as np

    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = surface.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        co = np.empty(len(mesh.vertices) * 3)
        mesh.vertices.foreach_get("co", co)
    finally:
        evaluated.to_mesh_clear()
    m = np.array(surface.matrix_world)
    return co.reshape(-1, 3) @ m[:3, :3].T + m[:3, 3]


def frame_points(scene, cam, points, direction, ortho: bool) -> None:
    """Aim ``cam`` along ``-direction`` at ``points`` ((n, 3)) so that they fill the picture
    (:data:`FRAME_MARGIN` left each side): orthographic, the scale of their extent across the
    view; in perspective, the distance at which the widest of them just fits, the camera moved
    across the view to centre them."""
    import numpy as np
    from mathutils import Vector

    d = Vector(direction).normalized()
    rot = (-d).to_track_quat("-Z", "Y")
    cam.rotation_euler = rot.to_euler()
    m = np.array(rot.to_matrix())  # columns: the camera's right, up and backward axes
    centre = points.mean(axis=0)
    local = (points - centre) @ m  # (right, up, back) about the centre
    aspect = scene.render.resolution_x / scene.render.resolution_y
    fill = 1.0 - 2.0 * FRAME_MARGIN
    lo, hi = local.min(axis=0), local.max(axis=0)
    cam.data.clip_end = max(cam.data.clip_end, 20.0 * float((hi - lo).max()))
    if ortho:
        # As tall as the points' shape asks (within SIDE_MIN_HEIGHT and the picture's own).
        shape = (hi[1] - lo[1]) / max(hi[0] - lo[0], 1e-300)
        x = scene.render.resolution_x
        scene.render.resolution_y = min(
            scene.render.resolution_y, max(round(x * shape), round(x * SIDE_MIN_HEIGHT))
        )
        aspect = x / scene.render.resolution_y
        cam.data.type = "ORTHO"
        cam.data.ortho_scale = max(hi[0] - lo[0], (hi[1] - lo[1]) * aspect) / fill
        mid = 0.5 * (lo + hi)
        cam.location = Vector((centre + m @ np.array([mid[0], mid[1], hi[2] + (hi - lo).max()])).tolist())
        return
    cam.data.type = "PERSP"
    half_w = math.atan(0.5 * cam.data.sensor_width / cam.data.lens)
    tan_x = math.tan(half_w) * fill
    tan_y = tan_x / aspect
    # Two rounds: centre the picture across the view, then the distance that fits every point.
    offset = np.zeros(2)
    for _ in range(2):
        u, v, w = local[:, 0] - offset[0], local[:, 1] - offset[1], local[:, 2]
        dist = float(np.max(np.maximum(w + np.abs(u) / tan_x, w + np.abs(v) / tan_y)))
        depth = dist - w
        pu, pv = u / depth, v / depth
        offset += 0.5 * np.array([pu.min() + pu.max(), pv.min() + pv.max()]) * float(np.median(depth))
    cam.location = Vector((centre + m @ np.array([offset[0], offset[1], dist])).tolist())


def render_hull(api, coll, surface, out: Path, draft: float) -> None:
    """Render the whole hull (the mirrored surface, the curves hidden) with its DWL (the
    waterline section at ``draft``, both sides) from each of :data:`HULL_VIEWS`."""
    import numpy as np

    scene = bpy.context.scene
    points = _hull_points(surface)
    length = float(np.ptp(points[:, 0]))
    dwl = None
    try:
        waterlines = api.sections(coll, waterlines=[draft])["waterlines"]
    except api.BattenError as e:
        _log(f"{coll.name}: no DWL drawn ({e})")
        waterlines = []
    if waterlines:
        curve = bpy.data.curves.new(f"{coll.name} DWL", "CURVE")
        curve.dimensions, curve.bevel_depth, curve.bevel_resolution = "3D", DWL_TUBE * length, 2
        for section in waterlines:
            for half in section.polylines:
                for side in (1.0, -1.0):
                    spline = curve.splines.new("POLY")
                    spline.points.add(len(half) - 1)
                    co = np.column_stack([half * (1.0, side, 1.0), np.ones(len(half))])
                    spline.points.foreach_set("co", co.ravel())
        mat = bpy.data.materials.new("batten DWL")
        mat.diffuse_color = (0.0, 0.3, 0.85, 1.0)
        curve.materials.append(mat)
        dwl = bpy.data.objects.new(f"{coll.name} DWL", curve)
        scene.collection.objects.link(dwl)
    hidden = [o for o in coll.objects if not o.hide_render]
    cam = scene.camera
    saved = (cam.data.type, cam.data.clip_end, cam.location.copy(), cam.rotation_euler.copy())
    height = scene.render.resolution_y
    try:
        for obj in hidden:
            obj.hide_render = True
        for view, (direction, ortho) in HULL_VIEWS.items():
            scene.render.resolution_y = height
            frame_points(scene, cam, points, direction, ortho)
            png = out / f"{coll.name}_hull_{view}.png"
            scene.render.filepath = str(png.resolve())
            t0 = time.perf_counter()
            bpy.ops.render.render(write_still=True)
            _log(f"{coll.name}: rendered the whole hull {png} ({view}) in {time.perf_counter() - t0:.1f} s")
    finally:
        for obj in hidden:
            obj.hide_render = False
        cam.data.type, cam.data.clip_end, cam.location, cam.rotation_euler = saved
        scene.render.resolution_y = height
        if dwl is not None:
            bpy.data.objects.remove(dwl)


#: The surface-fairing showcase (seed 003 §5, as tests/test_fair_surface.py): the Wigley lines
#: plan with noise of this share of the tolerance on every station and waterline, faired.
FAIRING_TOLERANCE = 0.01
FAIRING_NOISE = 0.3
FAIRING_SEED = 3


def _example_in_empty_scene(examples: Path, name: str) -> Path | None:
    """The example network file ``name`` in ``examples``, Blender's scene emptied for it; None
    (the scene untouched) when the file is missing."""
    path = examples / name
    if not path.is_file():
        return None
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    return path


def fairing_showcase(api, examples: Path, out: Path, engine: str, size: str) -> None:
    """Surface fairing before and after, as images: the Wigley lines plan made noisy (30 % of
    a 10 mm tolerance), its Gaussian-curvature map (``fairing_noisy_gaussian_curvature.png``), then
    faired (:func:`batten.api.fair_surface`) and mapped again at the same scale
    (``fairing_faired_gaussian_curvature.png``), beside the clean hull's
    (``fairing_clean_gaussian_curvature.png``). An error is logged."""
    import batten_native
    from batten.bridge import curves_out

    path = _example_in_empty_scene(examples, "wigley_lines.json")
    if path is None:
        return
    try:
        coll = api.load_network(path)
        coll.name = "fairing"
        scene = bpy.context.scene
        result = api.build(coll)
        _stage(coll, engine, size, result.object, tube=EXAMPLE_TUBE)
        lo, hi = _bounds(list(coll.objects) + [result.object])
        aim_camera(scene, "model", lo, hi)
        clean = render_curvature(api, scene, coll, out / "fairing_clean_gaussian_curvature.png", "gaussian")
        scale = clean["scale"]
        curves = api.read_curves(coll)
        noisy = batten_native.section_noise(curves, FAIRING_NOISE * FAIRING_TOLERANCE, FAIRING_SEED)
        objects = {o.name: o for o in api.curve_objects(coll)}
        curves_out.replace_splines_of([(objects[c.name], [c]) for c in noisy])
        api.build(coll)
        render_curvature(api, scene, coll, out / "fairing_noisy_gaussian_curvature.png", "gaussian", scale)
        t0 = time.perf_counter()
        report = api.fair_surface(coll, tolerance=FAIRING_TOLERANCE)
        t_fair = time.perf_counter() - t0
        api.build(coll)
        render_curvature(api, scene, coll, out / "fairing_faired_gaussian_curvature.png", "gaussian", scale)
        before, after = report["before"], report["after"]
        _log(
            f"fairing: Wigley lines with {FAIRING_NOISE:.0%} of {FAIRING_TOLERANCE * 1e3:.0f} mm noise "
            f"faired in {report['rounds']} round(s), {t_fair:.2f} s: curvature variation "
            f"{before['curvature_variation']:.4g} -> {after['curvature_variation']:.4g} /m3, "
            f"inflections {before['inflections']} -> {after['inflections']}; Gaussian-curvature "
            f"maps (clean, noisy, faired; full colour at {scale:.3g} /m2) in "
            f"{out}/fairing_*_gaussian_curvature.png"
        )
    except api.BattenError as e:
        _log(f"fairing: {type(e).__name__}: {e}")


def ship_fairing_showcase(api, ships: Path, out: Path, engine: str, size: str) -> None:
    """Surface fairing on a real ship (issue 17's case): KCS as :func:`batten.api.import_sections`
    draws it, noise of 30 % of a 10 mm tolerance on every station and waterline control point,
    then faired at the defaults; reflection lines on its entrance, clean, noisy and faired
    (``kcs_fairing_{clean,noisy,faired}_zebra.png``: the noise breaks them up, the fairing joins
    them again). Nothing when ``ships`` has no KCS; an error is logged."""
    import batten_native
    from batten.bridge import curves_out

    path = ships / "kcs" / "network.json"
    if not path.is_file():
        return
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    try:
        coll, _ = api.import_sections(path, collection="kcs_fairing")
        scene = bpy.context.scene
        result = api.build(coll)
        _stage(coll, engine, size, result.object, tube=SHIP_TUBE)
        lo, hi = _bounds(list(coll.objects) + [result.object])
        aim_camera(scene, "bow", lo, hi)
        images = {k: out / f"kcs_fairing_{k}_zebra.png" for k in ("clean", "noisy", "faired")}
        render_zebra(scene, coll, images["clean"])
        curves = api.read_curves(coll)
        # The outline (profile, upper edge, chines) is fixed by name: the import draws it free.
        outline = [c.name for c in curves if c.name.startswith(("profile", "deck", "chine"))]
        noise = FAIRING_NOISE * FAIRING_TOLERANCE
        noisy = batten_native.section_noise(curves, noise, FAIRING_SEED, fixed_curves=outline)
        objects = {o.name: o for o in api.curve_objects(coll)}
        curves_out.replace_splines_of([(objects[c.name], [c]) for c in noisy])
        api.build(coll)
        render_zebra(scene, coll, images["noisy"])
        t0 = time.perf_counter()
        fixed = (*api.SURFACE_FAIR_FIXED_ROLES, *outline)
        report = api.fair_surface(coll, tolerance=FAIRING_TOLERANCE, fixed=fixed)
        t_fair = time.perf_counter() - t0
        api.build(coll)
        render_zebra(scene, coll, images["faired"])
        before, after = report["before"], report["after"]
        _log(
            f"fairing: KCS with {FAIRING_NOISE:.0%} of {FAIRING_TOLERANCE * 1e3:.0f} mm noise faired in "
            f"{t_fair:.2f} s ({report['smoothed']} sections smoothed along themselves at "
            f"{report['smoothing_length']:.2f} m, {report['moves']} relaxation move(s)): curvature variation "
            f"{before['curvature_variation']:.4g} -> {after['curvature_variation']:.4g} /m3, inflections "
            f"{before['inflections']} -> {after['inflections']}, largest move "
            f"{report['max_deviation'] * 1e3:.2f} mm; reflection lines of the entrance (clean, noisy, "
            f"faired) in {out}/kcs_fairing_*_zebra.png"
        )
    except api.BattenError as e:
        _log(f"fairing KCS: {type(e).__name__}: {e}")


#: The hierarchy showcase: the hard-chine boat's chine moved (m) at its middle control point,
#: out and up.
HIERARCHY_CHINE_MOVE = (0.0, 0.3, 0.15)


def hierarchy_showcase(api, examples: Path, out: Path, engine: str, size: str) -> None:
    """The curve network hierarchy and curve attributes (seed 002 §5, §7.1) on the hard-chine
    boat: every station's keel end attached to the keel, its sheer end to the sheer and the
    point where it crosses the chine to the chine (a knuckle curve, so those points are knuckle
    points); then the chine is pulled out and up at its middle and the stations follow it,
    the surface rebuilt. Renders of the curves looking aft along the hull before and after
    (``hard_chine_hierarchy_before.png``, ``hard_chine_hierarchy_after.png``: the old stations
    and chine in red beside the new), of the new surface
    (``hard_chine_hierarchy_surface.png``), and the .blend with its attachments
    (``hard_chine_hierarchy.blend``). An error is logged."""
    path = _example_in_empty_scene(examples, "hard_chine.json")
    if path is None:
        return
    try:
        coll = api.load_network(path)
        coll.name = "hard_chine_hierarchy"
        scene = bpy.context.scene
        scene.batten.source = coll
        objects = {o.name: o for o in api.curve_objects(coll)}
        stations = [o for name, o in objects.items() if name.startswith("station")]
        api.attach(stations, objects["keel"], end="start")
        api.attach(stations, objects["sheer"], end="end")
        api.attach(stations, objects["chine"], point="nearest")
        api.set_curve_attribute(objects["chine"], "knuckle")
        before = api.build(coll)
        _stage(coll, engine, size, before.object, tube=EXAMPLE_TUBE)
        lo, hi = _bounds(list(coll.objects) + [before.object])
        hi = hi + np.asarray(HIERARCHY_CHINE_MOVE)  # room for the wider hull after the change

        def render(name: str, view: str, surface: bool) -> None:
            api.build(coll).object.hide_render = not surface
            cam = scene.camera
            if view == "body":
                # A body plan: orthographic, looking aft, framing the sections.
                from mathutils import Euler, Vector

                cam.data.type = "ORTHO"
                centre = (lo + hi) / 2
                aspect = scene.render.resolution_x / scene.render.resolution_y
                cam.data.ortho_scale = 1.2 * max(hi[1] - lo[1], (hi[2] - lo[2]) * aspect)
                cam.location = Vector((hi[0] + 10.0, centre[1], centre[2]))
                cam.rotation_euler = Euler((math.pi / 2, 0.0, math.pi / 2))
            else:
                cam.data.type = "PERSP"
                aim_camera(scene, view, lo, hi)
            scene.render.filepath = str((out / name).resolve())
            bpy.ops.render.render(write_still=True)

        # Looking aft along the hull at its curves (a body plan), before the change.
        render("hard_chine_hierarchy_before.png", "body", False)
        # The stations and chine as they were, thin and red, to stay beside the new ones.
        ghost = bpy.data.materials.new("batten before")
        ghost.diffuse_color = (0.85, 0.15, 0.1, 1.0)
        for o in [*stations, objects["chine"]]:
            copy = o.copy()
            copy.data = o.data.copy()
            copy.pop("batten_attachments", None)  # a picture of the curve, attached to nothing
            copy.data.bevel_depth *= 0.6
            copy.data.materials.clear()
            copy.data.materials.append(ghost)
            scene.collection.objects.link(copy)
        points = api.read_curves(stations)
        chine = objects["chine"].data.splines[0].points[1]
        chine.co = (*(np.asarray(chine.co[:3]) + HIERARCHY_CHINE_MOVE), chine.co[3])
        t0 = time.perf_counter()
        moved = api.update_hierarchy(coll)
        t_update = time.perf_counter() - t0
        report = api.build(coll).report
        shift = max(
            float(np.abs(np.asarray(a.control_points) - np.asarray(b.control_points)).max())
            for a, b in zip(points, api.read_curves(stations), strict=True)
        )
        _log(
            f"hierarchy: {len(stations)} stations attached to keel, sheer and chine (a knuckle "
            f"curve); the chine moved {HIERARCHY_CHINE_MOVE} m at its middle, {len(moved)} "
            f"curve(s) followed in {t_update * 1e3:.1f} ms (largest control point move "
            f"{shift:.3f} m); rebuilt: {report['faces']} faces, {len(report['warnings'])} "
            f"warning(s), max normal jump {report['max_normal_angle_deg']:.2g} deg"
        )
        render("hard_chine_hierarchy_after.png", "body", False)
        render("hard_chine_hierarchy_surface.png", "model", True)
        blend = out / "hard_chine_hierarchy.blend"
        bpy.ops.wm.save_as_mainfile(filepath=str(blend.resolve()))
        _log(f"hierarchy: renders {out}/hard_chine_hierarchy_{{before,after,surface}}.png, scene {blend}")
    except api.BattenError as e:
        _log(f"hierarchy: {type(e).__name__}: {e}")


#: The form showcase: the frigate's design draft (m) and its breadth change.
FORM_DRAFT = 4.8
FORM_BREADTH_FACTOR = 1.05


def form_showcase(api, examples: Path, out: Path) -> None:
    """A change by form topology (seed 002) compared with the original (§9): the frigate made
    5 % wider into a copy on its stack, then both hulls measured side by side
    (``frigate_breadth_comparison.json``: dimensions and hydrostatics, original, copy and
    change) and their sectional area curves drawn together
    (``frigate_breadth_comparison_sac.png``). An error is logged."""
    hydro_plot = _batten_module(api, "hydro_plot")
    path = _example_in_empty_scene(examples, "frigate_network.json")
    if path is None:
        return
    try:
        coll = api.load_network(path)
        breadth = api.form_topology(coll, draft=FORM_DRAFT)["parameters"]["breadth"]
        t0 = time.perf_counter()
        result = api.transform(coll, breadth=FORM_BREADTH_FACTOR * breadth, draft=FORM_DRAFT)
        t_transform = time.perf_counter() - t0
        comparison = api.compare(result, draft=FORM_DRAFT)
        png, _ = hydro_plot.sac_comparison_png(comparison, out / "frigate_breadth_comparison_sac.png")
        table = {k: v for k, v in comparison.items() if k != "sac"}
        (out / "frigate_breadth_comparison.json").write_text(json.dumps(table, indent=2) + "\n")
        rows = {r["key"]: r for r in comparison["dimensions"] + comparison["hydrostatics"]}
        changes = ", ".join(
            f"{rows[k]['label']} {rows[k]['change_pct']:+.2f} %"
            for k in ("breadth", "bwl", "volume", "cb", "kmt")
        )
        _log(
            f"form: frigate breadth x{FORM_BREADTH_FACTOR} into '{result.collection.name}' in "
            f"{t_transform * 1e3:.0f} ms; beside the original at T = {FORM_DRAFT} m: {changes}; "
            f"sectional areas in {png}"
        )
    except api.BattenError as e:
        _log(f"form: {type(e).__name__}: {e}")


#: The hydrostatic-transformation showcases (seed 002 §8), each (example, name of the
#: outputs, draft, targets from the original's hydrostatics): the PMB barge at its design
#: draft taken to Cb + 0.01 with its LCB 0.25 % Lpp forward by moving its PMB's ends, and the
#: frigate (no parallel middle body) made 0.005 finer in Cb, its LCB held, by flattening the
#: faces of its ends.
HYDRO_SHOWCASES = (
    (
        "pmb_barge.json",
        "pmb_barge",
        8.0,
        lambda h: {"cb": h["cb"] + 0.01, "lcb": h["lcb"] + 0.0025 * h["lpp"]},
    ),  # noqa: E501
    ("frigate_network.json", "frigate", FORM_DRAFT, lambda h: {"cb": h["cb"] - 0.005}),
)


def hydrostatic_showcase(api, examples: Path, out: Path) -> None:
    """Hydrostatic transformations (seed 002 §8) beside their originals, for each of
    :data:`HYDRO_SHOWCASES`: the solve's report and the comparison
    (``<name>_hydrostatic.json``) and both sectional area curves
    (``<name>_hydrostatic_sac.png``). An error is logged."""
    hydro_plot = _batten_module(api, "hydro_plot")
    for example, name, draft, targets in HYDRO_SHOWCASES:
        path = _example_in_empty_scene(examples, example)
        if path is None:
            continue
        try:
            coll = api.load_network(path)
            coll[api.DESIGN_DRAFT_PROPERTY] = draft
            t0 = time.perf_counter()
            result = api.transform_hydrostatic(coll, **targets(api.hydrostatics(coll, draft)))
            seconds = time.perf_counter() - t0
            r = result.report
            comparison = api.compare(result, draft=draft)
            png, _ = hydro_plot.sac_comparison_png(comparison, out / f"{name}_hydrostatic_sac.png")
            keys = ("mode", "target_figure", "target_value", "target_volume", "target_lcb", "pmb_length")
            solve = {k: r[k] for k in keys + ("bulge", "evaluations", "stop", "limit", "description")}
            for when in ("before", "after"):
                solve[when] = {k: r[when][k] for k in ("volume", "cb", "cp", "lcb", "bwl")}
            table = {"solve": solve, "comparison": {k: v for k, v in comparison.items() if k != "sac"}}
            (out / f"{name}_hydrostatic.json").write_text(json.dumps(table, indent=2) + "\n")
            how = (
                f"PMB {r['pmb_length'][0]:.2f} → {r['pmb_length'][1]:.2f} m"
                if r["mode"] == "pmb"
                else f"bulges {', '.join(f'{b:+.3f} m' for b in r['bulge']['offsets'])}"
            )
            _log(
                f"hydrostatic: {name} to {r['description']} in {r['evaluations']} hull evaluations, "
                f"{seconds:.2f} s ({r['stop']}): ∇ {r['before']['volume']:.1f} → {r['after']['volume']:.1f} "
                f"m³ (target {r['target_volume']:.1f}), LCB {r['before']['lcb']:.3f} → "
                f"{r['after']['lcb']:.3f} m, {how}; sectional areas in {png}"
            )
        except api.BattenError as e:
            _log(f"hydrostatic: {name}: {type(e).__name__}: {e}")


def main() -> None:
    args = _args()
    batten = _import_batten()
    api = sys.modules[batten.__name__ + ".api"] if batten.__name__ + ".api" in sys.modules else None
    if api is None:
        import importlib

        api = importlib.import_module(batten.__name__ + ".api")
    examples = sorted(args.examples.glob("*.json"))
    if not examples:
        sys.exit(f"demo: no example networks in {args.examples}")
    for path in examples:
        run_example(api, path, args.out, args.engine, args.size, args.resolution, args.zebra)
    fairing_showcase(api, args.examples, args.out, args.engine, args.size)
    ship_fairing_showcase(api, args.ships, args.out, args.engine, args.size)
    form_showcase(api, args.examples, args.out)
    hydrostatic_showcase(api, args.examples, args.out)
    hierarchy_showcase(api, args.examples, args.out, args.engine, args.size)
    ships = sorted(args.ships.glob("*/network.json")) if args.ships.is_dir() else []
    if not ships:
        _log(f"no real ships in {args.ships} (the shared/hulls folder beside the checkout)")
    ships += sorted((args.examples / "sections").glob("*.json"))
    for path in ships:
        run_ship(api, path, args.out, args.engine, args.size, args.resolution, args.zebra)
    _log(f"done: {len(examples)} example network(s) and {len(ships)} section file(s) in {args.out}/")


if __name__ == "__main__":
    main()
