"""Drawings and tables as a vector PDF, written directly (no Blender, no PDF library).

PDF 1.4 with uncompressed content streams: lines as paths, text in the standard Helvetica
font (WinAnsi encoding, so ², ³, °, · and — print as themselves) and the Greek ∇ and Δ of the
hydrostatics in the standard Symbol font; base-14 fonts need nothing embedded (PDF Reference
1.7, §5.5.1 and Appendix D). Each page is A3 landscape; a page is a list of PDF operators
built by :func:`drawing_page` (a drawing to scale) or :func:`table_page` (rows of text).
"""

from __future__ import annotations

import io

from .drawing import DASH, EM_PER_CAP, LAYER_STYLE, LAYERS, MARGIN_MM, Drawing, Page, baseline, fit_page

#: PostScript points per millimetre.
PT_PER_MM = 72.0 / 25.4
#: Glyph widths of Helvetica (1/1000 em) for the printable ASCII characters, from its AFM
#: file (Adobe Core 14 font metrics), for placing centred and right-aligned text.
HELVETICA_WIDTHS = (
    278, 278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278,
    556, 556, 556, 556, 556, 556, 556, 556, 556, 556, 278, 278, 584, 584, 584, 556,
    1015, 667, 667, 722, 722, 667, 611, 778, 722, 278, 500, 667, 556, 833, 722, 778,
    667, 778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 278, 278, 278, 469, 556,
    333, 556, 556, 500, 556, 556, 278, 556, 556, 222, 222, 500, 222, 833, 556, 556,
    556, 556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334, 260, 334, 584,
)  # fmt: skip
#: Widths of the non-ASCII Helvetica glyphs batten writes (²  ³  °  ·  —), and the default.
HELVETICA_EXTRA = {"²": 333, "³": 333, "°": 400, "·": 278, "—": 1000, "×": 584}
DEFAULT_WIDTH = 556
#: Characters set in the Symbol font: its code and glyph width (Symbol's AFM).
SYMBOL = {"∇": (0xD1, 713), "Δ": (0x44, 612), "ρ": (0x72, 549)}


def _runs(text: str) -> list[tuple[str, bytes, float]]:
    """``text`` split into runs of one font: (font resource, encoded bytes, width in em)."""
    runs: list[tuple[str, bytearray, float]] = []
    for ch in text:
        if ch in SYMBOL:
            font, code, width = "/F2", bytes([SYMBOL[ch][0]]), SYMBOL[ch][1]
        else:
            font = "/F1"
            code = ch.encode("cp1252", errors="replace")
            o = ord(ch)
            width = HELVETICA_WIDTHS[o - 32] if 32 <= o < 127 else HELVETICA_EXTRA.get(ch, DEFAULT_WIDTH)
        if runs and runs[-1][0] == font:
            f, b, w = runs[-1]
            runs[-1] = (f, b + code, w + width / 1000.0)
        else:
            runs.append((font, bytearray(code), width / 1000.0))
    return [(f, bytes(b), w) for f, b, w in runs]


def text_width(text: str) -> float:
    """The width of ``text`` in em as this writer sets it."""
    return sum(w for _f, _b, w in _runs(text))


def _literal(data: bytes) -> str:
    """A PDF literal string of ``data`` (Latin-1 text of the bytes, with ( ) \\ escaped)."""
    return "(" + data.decode("latin-1").replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)") + ")"


def text_ops(x_mm: float, y_mm: float, text: str, em_mm: float, align: str = "left") -> str:
    """The operators setting ``text`` with its baseline at ``(x_mm, y_mm)``, ``em_mm`` tall,
    aligned ``align`` at x."""
    size = em_mm * PT_PER_MM
    x = x_mm * PT_PER_MM - {"left": 0.0, "center": 0.5, "right": 1.0}[align] * text_width(text) * size
    parts = [f"BT {x:.2f} {y_mm * PT_PER_MM:.2f} Td"]
    for font, data, _w in _runs(text):
        parts.append(f"{font} {size:.2f} Tf {_literal(data)} Tj")
    parts.append("ET")
    return " ".join(parts)


def drawing_page(drawing: Drawing, page: Page | None = None) -> str:
    """The content stream of a page showing ``drawing`` to scale on ``page`` (default:
    :func:`~batten.drawing.fit_page`), with the scale written at the bottom left."""
    page = page or fit_page(drawing)
    k = page.mm_per_unit
    ops = ["1 J 1 j"]
    for layer in LAYERS:
        rgb, _ = LAYER_STYLE[layer]
        colour = " ".join(f"{c:.3f}" for c in rgb)
        ops.append(f"{colour} RG {colour} rg {drawing.pen(layer) * k * PT_PER_MM:.3f} w")
        for s in (s for s in drawing.strokes if s.layer == layer):
            if s.dashed:
                on, off = (v * drawing.text_height * k * PT_PER_MM for v in DASH)
                ops.append(f"[{on:.2f} {off:.2f}] 0 d")
            pts = page.to_paper(s.points) * PT_PER_MM
            ops.append(
                f"{pts[0, 0]:.2f} {pts[0, 1]:.2f} m "
                + " ".join(f"{x:.2f} {y:.2f} l" for x, y in pts[1:])
                + " S"
            )
            if s.dashed:
                ops.append("[] 0 d")
        for lab in (lab for lab in drawing.labels if lab.layer == layer):
            ((x, y),) = page.to_paper([(lab.x, baseline(lab))])
            ops.append(text_ops(x, y, lab.text, lab.height * EM_PER_CAP * k, lab.align))
    ops.append("0 0 0 rg " + text_ops(MARGIN_MM, 0.5 * MARGIN_MM, f"Scale 1:{page.scale} (A3)", 3.5))
    return "\n".join(ops)


def table_page(title: str, header: list[str], rows: list[list[str]], size=(420.0, 297.0)) -> list[str]:
    """Content streams of pages showing a table: ``title`` on top, the ``header`` and then
    ``rows`` (text cells, numbers right-aligned in equal columns), as many pages as it takes."""
    em = 2.6 if len(header) <= 16 else 2.0
    line = 1.5 * em
    width = size[0] - 2 * MARGIN_MM
    col = width / max(len(header), 1)
    per_page = max(int((size[1] - 2 * MARGIN_MM - 4 * line) // line), 1)
    pages = []
    for start in range(0, max(len(rows), 1), per_page):
        y = size[1] - MARGIN_MM - em
        ops = ["0 0 0 rg", text_ops(MARGIN_MM, y, title, 1.5 * em)]
        y -= 2.2 * line
        for i, cell in enumerate(header):
            ops.append(text_ops(MARGIN_MM + (i + 1) * col - 0.3 * em, y, cell, em, "right"))
        ops.append(
            f"0.5 w {MARGIN_MM * PT_PER_MM:.2f} {(y - 0.4 * em) * PT_PER_MM:.2f} m "
            f"{(MARGIN_MM + width) * PT_PER_MM:.2f} {(y - 0.4 * em) * PT_PER_MM:.2f} l S"
        )
        for row in rows[start : start + per_page]:
            y -= line
            for i, cell in enumerate(row):
                ops.append(text_ops(MARGIN_MM + (i + 1) * col - 0.3 * em, y, cell, em, "right"))
        pages.append("\n".join(ops))
    return pages


def pdf_bytes(pages: list[str], size=(420.0, 297.0), title: str = "") -> bytes:
    """A PDF document of the content streams ``pages``, each page ``size`` mm."""
    w, h = (v * PT_PER_MM for v in size)
    objects: list[bytes] = []

    def add(body: str | bytes) -> int:
        objects.append(body.encode("latin-1") if isinstance(body, str) else body)
        return len(objects)

    catalog = add("")  # filled in below, once the page tree's number is known
    info = add(f"<< /Producer (batten) /Title {_literal(title.encode('cp1252', errors='replace'))} >>")
    helvetica = add("<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>")
    symbol = add("<< /Type /Font /Subtype /Type1 /BaseFont /Symbol >>")
    tree = add("")
    kids = []
    for content in pages:
        data = content.encode("latin-1")
        stream = add(b"<< /Length %d >>\nstream\n" % len(data) + data + b"\nendstream")
        kids.append(
            add(
                f"<< /Type /Page /Parent {tree} 0 R /MediaBox [0 0 {w:.2f} {h:.2f}] /Contents {stream} 0 R "
                f"/Resources << /Font << /F1 {helvetica} 0 R /F2 {symbol} 0 R >> >> >>"
            )
        )
    objects[catalog - 1] = f"<< /Type /Catalog /Pages {tree} 0 R >>".encode()
    objects[tree - 1] = (
        f"<< /Type /Pages /Kids [{' '.join(f'{k} 0 R' for k in kids)}] /Count {len(kids)} >>".encode()
    )
    out = io.BytesIO()
    out.write(b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n")
    offsets = []
    for i, body in enumerate(objects, start=1):
        offsets.append(out.tell())
        out.write(b"%d 0 obj\n" % i + body + b"\nendobj\n")
    xref = out.tell()
    out.write(b"xref\n0 %d\n0000000000 65535 f \n" % (len(objects) + 1))
    for off in offsets:
        out.write(b"%010d 00000 n \n" % off)
    out.write(
        b"trailer\n<< /Size %d /Root %d 0 R /Info %d 0 R >>\nstartxref\n%d\n%%%%EOF\n"
        % (len(objects) + 1, catalog, info, xref)
    )
    return out.getvalue()


def drawing_pdf(drawing: Drawing, tables: list[tuple[str, list[str], list[list[str]]]] = ()) -> bytes:
    """A PDF of ``drawing`` to scale on its first page, then each of ``tables`` (title,
    header, rows) on pages of its own."""
    pages = [drawing_page(drawing)]
    for title, header, rows in tables:
        pages += table_page(title, header, rows)
    return pdf_bytes(pages, title=f"{drawing.title} lines plan")
