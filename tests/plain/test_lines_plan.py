"""The lines plan drawing of the Wigley hull (its sections from the formula): the views in
their places, the body plan halves on their sides, and each file format read back."""

import io
import re
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import wigley_sections as w
from batten import drawing, drawing_pdf, drawing_svg, lines_plan, lines_plan_files

SVG = "{http://www.w3.org/2000/svg}"
STATIONS = 21
#: Diagonals: (height at the centreplane, angle below the horizontal in degrees).
DIAGONALS = ((5.0, 35.0), (3.0, 20.0))


@pytest.fixture(scope="module")
def plan():
    sections = w.sections(STATIONS, diagonals=DIAGONALS)
    hull = lines_plan.Hull("Wigley", -w.L / 2, w.L / 2, w.T, w.figures())
    return sections, lines_plan.layout(sections, w.outline(), hull)


def _strokes(d, layer):
    return [s.points for s in d.strokes if s.layer == layer]


def test_every_station_in_the_body_plan_on_its_side(plan):
    sections, d = plan
    cl = d.marks["body_plan_cl"]
    strokes = _strokes(d, "stations")
    # 10 aft, 10 fore, the midship station on both halves.
    assert len(strokes) == STATIONS + 1
    # Stations 1–10 reach left of the centreline (station 0, at the AP, is a point on it).
    aft = [p for p in strokes if p[:, 0].min() < cl]
    assert len(aft) == 10 and all(p[:, 0].max() <= cl for p in aft)
    for s in sections["stations"]:
        (pts,) = s.polylines
        expected = [cl - pts[:, 1]] if s.offset < 0 else [cl + pts[:, 1]]
        if s.offset == 0.0:
            expected = [cl - pts[:, 1], cl + pts[:, 1]]
        for xs in expected:
            assert any(np.allclose(p[:, 0], xs) and np.allclose(p[:, 1], pts[:, 2]) for p in strokes)


def test_waterlines_in_the_plan_buttocks_in_the_profile(plan):
    sections, d = plan
    cl = d.marks["half_breadth_cl"]
    wl = _strokes(d, "waterlines")
    assert len(wl) == len(sections["waterlines"])
    for s, p in zip(sections["waterlines"], wl, strict=True):
        x = p[:, 0]
        np.testing.assert_allclose(cl - p[:, 1], w.half_breadth(x) * w.depth_factor(s.offset), atol=1e-12)
    bt = _strokes(d, "buttocks")
    assert len(bt) == 4
    # The buttock at y = 2 m dips to z = T(1 − √(1 − 2/5)) amidships.
    assert min(p[:, 1].min() for p in bt[1:2]) == pytest.approx(w.T * (1 - np.sqrt(1 - 2.0 / 5.0)), rel=1e-3)


def test_diagonals_expanded_true_length(plan):
    sections, d = plan
    origin, direction = lines_plan.diagonal_frame(sections["diagonals"][0].polylines)
    np.testing.assert_allclose(origin, [0.0, 5.0], atol=1e-9)
    np.testing.assert_allclose(direction, [np.cos(np.radians(35)), -np.sin(np.radians(35))], atol=1e-9)
    # Expanded above the plan's centreline, by its distance along the plane: the widest at
    # midships (where the diagonal meets the hull at the greatest distance).
    expanded = [p for p in _strokes(d, "diagonals") if len(p) == w.SAMPLES]
    assert len(expanded) == 2
    (pts,) = sections["diagonals"][0].polylines
    reach = np.hypot(pts[:, 1], pts[:, 2] - 5.0)
    np.testing.assert_allclose(expanded[0][:, 1] - d.marks["half_breadth_cl"], reach, atol=1e-9)


def test_labels(plan):
    _, d = plan
    texts = [lab.text for lab in d.labels]
    for n in range(STATIONS):
        assert texts.count(str(n)) >= 2, n  # under the profile and under the plan
    for t in (
        "DWL",
        "AP",
        "FP",
        "BODY PLAN",
        "PROFILE",
        "HALF-BREADTH PLAN",
        "WL 6.25",
        "2,777.78 m³",
        "0.4444",
    ):
        assert t in texts, t


def test_station_numbers_from_the_ap():
    hull = lines_plan.Hull("h", 10.0, 110.0, 5.0)
    assert [lines_plan.station_number(x, hull) for x in (10.0, 12.5, 60.0, 110.0, 5.0)] == [
        "0",
        "0.5",
        "10",
        "20",
        "-1",
    ]


def test_crowded_labels_thinned():
    assert lines_plan.spaced(np.array([0.0, 0.4, 1.0, 1.2, 3.0]), 1.0) == [0, 2, 4]


def test_default_planes():
    assert lines_plan.default_waterlines(5.0, 8.0) == pytest.approx([1, 2, 3, 4, 5, 6, 7])
    # A waterline just under the top would cut only the deck edge: left out.
    assert lines_plan.default_waterlines(5.0, 7.1) == pytest.approx([1, 2, 3, 4, 5, 6])
    assert lines_plan.default_buttocks(10.0) == pytest.approx([2, 4, 6, 8])


def test_no_sections_is_an_error():
    hull = lines_plan.Hull("h", 0.0, 1.0, 0.5)
    with pytest.raises(ValueError, match="no sections"):
        lines_plan.layout({"stations": []}, [], hull)
    with pytest.raises(ValueError, match="forward of AP"):
        lines_plan.layout(w.sections(), [], lines_plan.Hull("h", 1.0, 0.0, 0.5))


def test_scales():
    assert [drawing.nice_scale(r) for r in (0.5, 1.0, 1.5, 3.2, 23, 240, 323, 401, 900)] == [
        1,
        1,
        2,
        4,
        25,
        250,
        400,
        500,
        1000,
    ]


def test_svg(plan):
    _, d = plan
    text = drawing_svg.svg_text(d)
    root = ET.fromstring(text)
    groups = {g.get("id"): g for g in root.iter(f"{SVG}g")}
    assert {"stations", "waterlines", "buttocks", "diagonals", "grid", "outline", "title"} <= set(groups)
    paths = groups["stations"].findall(f"{SVG}path")
    assert len(paths) == STATIONS + 1
    page = drawing.fit_page(d)
    assert page.scale == 400
    # The fore station at x = 25 m, back from the sheet's millimetres to metres.
    (station,) = w.sections(STATIONS)["stations"][15].polylines
    mm = page.to_paper(np.column_stack([d.marks["body_plan_cl"] + station[:, 1], station[:, 2]]))
    want = np.column_stack([mm[:, 0], page.height - mm[:, 1]])
    got = [np.array(re.findall(r"[-\d.]+,[-\d.]+", p.get("d"))[0:], dtype=object) for p in paths]
    found = False
    for pts in got:
        xy = np.array([[float(v) for v in s.split(",")] for s in pts])
        if xy.shape == want.shape and np.allclose(xy, want, atol=1e-3):
            found = True
    assert found
    texts = [t.text for t in root.iter(f"{SVG}text")]
    assert "DWL" in texts and "Scale 1:400 (A3)" in texts


def test_dxf_layers_and_a_station_against_the_formula(plan, tmp_path):
    _, d = plan
    path = lines_plan_files.write(d, tmp_path / "wigley.dxf")
    doc = ezdxf.readfile(path)
    assert doc.units == ezdxf.units.M
    layers = {layer.dxf.name for layer in doc.layers}
    assert {"stations", "waterlines", "buttocks", "diagonals", "knuckles", "grid"} <= layers
    msp = doc.modelspace()
    count = {
        name: len(msp.query(f'LWPOLYLINE[layer=="{name}"]'))
        for name in ("stations", "waterlines", "buttocks")
    }
    assert count == {"stations": STATIONS + 1, "waterlines": 6, "buttocks": 4}
    cl = d.marks["body_plan_cl"]
    x = 25.0  # station 15, fore: right of the centreline
    found = 0
    for e in msp.query('LWPOLYLINE[layer=="stations"]'):
        pts = np.array([(p[0], p[1]) for p in e.get_points()])
        y, z = pts[:, 0] - cl, pts[:, 1]
        if y.max() > 0 and abs(y.max() - w.half_breadth(x)) < 1e-9:
            np.testing.assert_allclose(y, w.half_breadth(x) * w.depth_factor(z), atol=1e-9)
            found += 1
    assert found == 1
    assert any(t.dxf.text == "DWL" for t in msp.query("TEXT"))


def test_pdf_pages(plan, tmp_path):
    _, d = plan
    table = ("Offsets", ["x", "y"], [[f"{i}", f"{i / 3:.3f}"] for i in range(200)])
    data = drawing_pdf.drawing_pdf(d, [table])
    assert lines_plan_files.file_bytes(d, ".pdf").count(b"/Type /Page ") == 1  # the drawing's own: none
    assert data.startswith(b"%PDF-1.4") and data.rstrip().endswith(b"%%EOF")
    # 200 rows take several table pages after the drawing.
    pages = 1 + len(drawing_pdf.table_page(*table))
    assert pages > 2
    assert b"/Count %d" % pages in data
    assert data.count(b"/Type /Page ") == pages
    # The cross-reference table points at each object.
    xref = int(data.rsplit(b"startxref", 1)[1].split()[0])
    entries = data[xref:].split(b"\n")[3:]
    for n, line in enumerate(entries[: data.count(b" 0 obj\n")], start=1):
        offset = int(line.split()[0])
        assert data[offset:].startswith(b"%d 0 obj" % n)
    assert b"(DWL) Tj" in data
    assert b"/BaseFont /Symbol" in data  # the ∇ and Δ of the title block


def test_pdf_text_widths():
    assert drawing_pdf.text_width("0") == pytest.approx(0.556)
    assert drawing_pdf.text_width("Δ1") == pytest.approx(0.612 + 0.556)


def test_bad_suffix_and_unwritable_path(plan, tmp_path):
    _, d = plan
    with pytest.raises(ValueError, match="not '.jpg'"):
        lines_plan_files.write(d, tmp_path / "plan.jpg")
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(OSError):
        lines_plan_files.write(d, blocker / "plan.svg")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_svg_written_whole(plan, tmp_path):
    _, d = plan
    path = lines_plan_files.write(d, tmp_path / "plan.SVG")
    ET.parse(io.StringIO(path.read_text()))
    assert [p.name for p in tmp_path.iterdir()] == ["plan.SVG"]


def test_offsets_tables_read_off_the_stations(plan):
    sections, _ = plan
    hull = lines_plan.Hull("Wigley", -w.L / 2, w.L / 2, w.T)
    (breadths, bheader, brows), (heights, hheader, hrows) = lines_plan.offsets_tables(sections, hull)
    assert "half-breadths" in breadths and "heights" in heights
    assert bheader[1:] == [str(n) for n in range(STATIONS)]
    assert len(brows) == 6 and len(hrows) == 4
    # Station 15 (x = 25 m) at the waterline 2.5 m, and at the buttock 2 m.
    assert float(brows[1][16]) == pytest.approx(w.half_breadth(25.0) * w.depth_factor(2.5), abs=1e-3)
    z = w.T * (1 - np.sqrt(1 - 2.0 / w.half_breadth(25.0)))
    assert float(hrows[1][16]) == pytest.approx(z, abs=1e-3)
    # Station 0 (the AP, where the hull ends in a vertical line) has no breadth.
    assert brows[1][1] == "0.000"
