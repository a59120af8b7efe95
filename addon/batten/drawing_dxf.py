"""A :class:`~batten.drawing.Drawing` as a DXF file, one layer per family (no Blender needed).

Written with ezdxf (bundled in the extension as a wheel): DXF R2010, model space in metres
at full size (``$INSUNITS`` = 6), each stroke an LWPOLYLINE and each label a TEXT on the
layer of its family (stations, waterlines, buttocks, diagonals, knuckles, outline, dwl,
grid, title), coloured as in the other formats; dashed strokes use the DASHED line type.
"""

from __future__ import annotations

import io

from .atomic_write import write_atomically
from .drawing import DASH, LAYER_STYLE, LAYERS, Drawing, baseline

#: DXF version written (AutoCAD 2010: UTF-8 text, true colours, lineweights).
DXF_VERSION = "R2010"
#: The DXF alignments (ezdxf's TextEntityAlignment names) of the drawing's horizontal ones,
#: on the baseline.
ALIGNMENT = {"left": "LEFT", "center": "CENTER", "right": "RIGHT"}
#: DXF lineweights are hundredths of a millimetre from a fixed list; the pens as printed on
#: an A3 sheet (thin grid, medium sections, thick outline).
LINEWEIGHT = {"grid": 13, "title": 18, "dwl": 18, "knuckles": 35, "outline": 35}
SECTION_LINEWEIGHT = 25


def dxf_document(drawing: Drawing):
    """The ezdxf document of ``drawing``."""
    import ezdxf
    from ezdxf import units
    from ezdxf.enums import TextEntityAlignment

    doc = ezdxf.new(DXF_VERSION, setup=["linetypes"])
    doc.units = units.M
    doc.header["$MEASUREMENT"] = 1  # metric
    on, off = (v * drawing.text_height for v in DASH)
    doc.linetypes.add("BATTEN_DASHED", pattern=[on + off, on, -off], description="DWL dashes")
    for layer in LAYERS:
        rgb, _ = LAYER_STYLE[layer]
        entry = doc.layers.add(layer)
        entry.rgb = tuple(round(255 * c) for c in rgb)
        entry.dxf.lineweight = LINEWEIGHT.get(layer, SECTION_LINEWEIGHT)
    msp = doc.modelspace()
    for s in drawing.strokes:
        attribs = {"layer": s.layer}
        if s.dashed:
            attribs["linetype"] = "BATTEN_DASHED"
        msp.add_lwpolyline(s.points.tolist(), dxfattribs=attribs)
    for lab in drawing.labels:
        text = msp.add_text(lab.text, height=lab.height, dxfattribs={"layer": lab.layer, "style": "Standard"})
        text.set_placement((lab.x, baseline(lab)), align=TextEntityAlignment[ALIGNMENT[lab.align]])
    doc.header["$EXTMIN"], doc.header["$EXTMAX"] = _extents(drawing)
    return doc


def _extents(drawing: Drawing):
    x0, y0, x1, y1 = drawing.bounds()
    return (x0, y0, 0.0), (x1, y1, 0.0)


def dxf_text(drawing: Drawing) -> str:
    """The DXF file of ``drawing`` as text."""
    out = io.StringIO()
    dxf_document(drawing).write(out)
    return out.getvalue()


def write_dxf(drawing: Drawing, path) -> None:
    """Write ``drawing`` to ``path`` as DXF, whole or not at all."""
    write_atomically(path, dxf_text(drawing))
