"""batten.api.lines_plan on the Wigley hull's patch surface: each format written and read back,
a station of the DXF against the formula, the Lines Plan operator's scene and the export
operator giving what the API gives, and bad input leaving no file."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import batten.api as api
import bpy
import ezdxf
import numpy as np
import pytest
from batten_native import InvalidArgumentError, NetworkFileError

L, B, T = 100.0, 10.0, 6.25
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture
def wigley(addon):
    return api.load_example("wigley_lines.json")


def wigley_y(x, z):
    """The Wigley hull's half-breadth (examples/wigley.py), wall-sided above T."""
    depth = np.where(z < T, 1.0 - ((T - z) / T) ** 2, 1.0)
    return 0.5 * B * (1.0 - (2.0 * x / L) ** 2) * depth


def test_dxf_station_is_the_surface_section(wigley, tmp_path):
    # x = 12.5 is a station of the network: the surface passes through that curve exactly.
    path = api.lines_plan(wigley, tmp_path / "wigley.dxf", stations=[-37.5, 0.0, 12.5], draft=T)
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    assert {"stations", "waterlines", "buttocks", "diagonals", "knuckles", "grid"} <= {
        layer.dxf.name for layer in doc.layers
    }
    stations = msp.query('LWPOLYLINE[layer=="stations"]')
    assert len(stations) >= 4  # aft, midship on both halves, fore (a section may come in pieces)
    drawing = api.lines_plan_drawing(wigley, stations=[-37.5, 0.0, 12.5], draft=T)
    cl = drawing.marks["body_plan_cl"]
    fore = [np.array([(p[0], p[1]) for p in e.get_points()]) for e in stations]
    # Right of the centreline (from the keel on it), narrower than the midship station.
    widest = cl + wigley_y(0.0, T) - 1e-3
    fore = [p for p in fore if p[:, 0].min() > cl - 1e-9 and cl + 1.0 < p[:, 0].max() < widest]
    assert fore, "the fore station at x = 12.5 is right of the body plan's centreline"
    pts = np.vstack(fore)
    y, z = pts[:, 0] - cl, pts[:, 1]
    assert np.abs(y - wigley_y(12.5, z)).max() < 1e-3
    # Default waterlines: T/5 apart to the deck at 8.75 m (6 of them), default buttocks: 4.
    assert len(msp.query('LWPOLYLINE[layer=="waterlines"]')) == 6
    assert len(msp.query('LWPOLYLINE[layer=="buttocks"]')) >= 4


def test_svg_pdf_png(wigley, tmp_path):
    svg = api.lines_plan(wigley, tmp_path / "w.svg", draft=T)
    root = ET.parse(svg).getroot()
    groups = {g.get("id"): g for g in root.iter(f"{SVG}g")}
    # Stations 1–19, the midship one on both halves, the AP (a line on the centreline); the FP
    # plane only touches the stem: no section.
    assert len(groups["stations"].findall(f"{SVG}path")) == 21
    texts = [t.text for t in root.iter(f"{SVG}text")]
    assert "DWL" in texts and "wigley_lines: lines plan" in texts
    # The title block's volume is the surface's own.
    volume = api.hydrostatics(wigley, T)["volume"]
    assert f"{volume:,.2f} m³" in texts
    pdf = api.lines_plan(wigley, tmp_path / "w.pdf", draft=T)
    data = pdf.read_bytes()
    # The plan, then the offsets: half-breadths and heights (21 stations fit one page each).
    assert data.startswith(b"%PDF") and b"/Count 3" in data
    assert b"(wigley_lines: half-breadths \\(m\\) at the stations) Tj" in data
    png = api.lines_plan(wigley, tmp_path / "w.png", draft=T)
    image = bpy.data.images.load(str(png))
    assert image.size[0] == 2400 and image.size[1] > 600
    assert sorted(p.name for p in tmp_path.iterdir()) == ["w.pdf", "w.png", "w.svg"]


def test_design_draft_is_the_default(wigley, tmp_path):
    with pytest.raises(InvalidArgumentError, match="give draft="):
        api.lines_plan(wigley, tmp_path / "w.svg")
    wigley[api.DESIGN_DRAFT_PROPERTY] = T
    d = api.lines_plan_drawing(wigley, waterlines=(), buttocks=())
    assert [s for s in d.strokes if s.layer in ("waterlines", "buttocks")] == []
    dwl = [s.points for s in d.strokes if s.layer == "dwl"]
    assert dwl and all(np.allclose(p[:, 1], T) for p in dwl)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"draft": float("nan")}, "draft"),
        ({"draft": -1.0}, "draft"),
        ({"draft": T, "stations": 1}, "at least 2"),
        ({"draft": T, "stations": [float("inf")]}, "finite"),
    ],
)
def test_bad_arguments_leave_no_file(wigley, tmp_path, kwargs, match):
    with pytest.raises(InvalidArgumentError, match=match):
        api.lines_plan(wigley, tmp_path / "w.svg", **kwargs)
    assert list(tmp_path.iterdir()) == []


def test_bad_paths(wigley, tmp_path):
    with pytest.raises(InvalidArgumentError, match="not '.txt'"):
        api.lines_plan(wigley, tmp_path / "w.txt", draft=T)
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(NetworkFileError, match="lines plan"):
        api.lines_plan(wigley, blocker / "w.pdf", draft=T)
    with pytest.raises(InvalidArgumentError, match="path"):
        api.lines_plan(wigley, 42, draft=T)
    assert [p.name for p in tmp_path.iterdir()] == ["file"]


def test_operator_scene_is_the_api_drawing(wigley):
    scene = bpy.context.scene
    scene.batten.source = wigley
    scene.batten.draft = T
    assert bpy.ops.batten.lines_plan(stations=11) == {"FINISHED"}
    plan = bpy.data.scenes["wigley_lines lines plan"]
    assert plan.camera is not None and plan.camera.data.type == "ORTHO"
    # The live 3D sections too, with a camera for each view.
    assert "wigley_lines sections" in plan.collection.children
    for view in ("profile", "half-breadth", "body plan"):
        assert bpy.data.objects[f"wigley_lines {view} camera"].data.type == "ORTHO"
    drawing = api.lines_plan_drawing(wigley, stations=11, draft=T)
    stations = bpy.data.objects["wigley_lines stations"]
    assert len(stations.data.splines) == sum(s.layer == "stations" for s in drawing.strokes)
    texts = [o.data.body for o in plan.collection.all_objects if o.type == "FONT"]
    assert sorted(texts) == sorted(lab.text for lab in drawing.labels)
    # Drawn again (from the plan's own scene, now the window's), the plan is replaced, not
    # added to, and what the designer put in its scene stays.
    count = len(bpy.data.objects)
    note = bpy.data.objects.new("note", None)
    plan.collection.objects.link(note)
    assert bpy.ops.batten.lines_plan(stations=11) == {"FINISHED"}
    assert len(bpy.data.objects) == count + 1 and note.name in plan.collection.objects


def test_export_operator(wigley, tmp_path):
    bpy.context.scene.batten.source = wigley
    bpy.context.scene.batten.draft = T
    path = tmp_path / "plan.dxf"
    assert bpy.ops.batten.export_lines_plan(filepath=str(path), file_format=".dxf") == {"FINISHED"}
    ours = api.lines_plan(wigley, tmp_path / "api.dxf", draft=T)
    assert path.read_text().count("LWPOLYLINE") == ours.read_text().count("LWPOLYLINE")
    with pytest.raises(RuntimeError, match="not '.txt'"):
        bpy.ops.batten.export_lines_plan(filepath=str(tmp_path / "plan.txt"), file_format=".dxf")
