"""Curvature colour maps on a hull's surface mesh: the Gaussian and mean curvature at every
vertex (from the exact patches, :meth:`batten_native.HullModel.vertex_curvature`) written as
point attributes, and one of them as a colour attribute on a diverging scale, shown in the
viewport's Solid mode (*Attribute* colour) and by the Color Attribute node in a material.

Attributes: ``batten_gaussian_curvature`` (1/m²) and ``batten_mean_curvature`` (1/m, positive
where the hull bulges outwards), float, per point; ``batten_curvature`` (colour, per point):
blue for negative, white for zero, red for positive, full at ± the map's scale; grey where the
curvature is undefined (a singular point of a patch).
"""

from __future__ import annotations

import numpy as np

#: The attributes written on the surface mesh.
GAUSSIAN_ATTRIBUTE = "batten_gaussian_curvature"
MEAN_ATTRIBUTE = "batten_mean_curvature"
COLOUR_ATTRIBUTE = "batten_curvature"
#: The kinds of map and the attribute each shows.
KINDS = {"gaussian": GAUSSIAN_ATTRIBUTE, "mean": MEAN_ATTRIBUTE}
#: The default scale is this quantile of |value| over the defined vertices: the colours then
#: use their range on the hull itself, not on a few extreme vertices at a patch corner.
SCALE_QUANTILE = 0.95

#: Moreland's cool–warm diverging map (2009), sRGB: negative, zero, positive.
_COOL = (0.230, 0.299, 0.754)
_ZERO = (0.865, 0.865, 0.865)
_WARM = (0.706, 0.016, 0.150)
#: Vertices without a figure.
_UNDEFINED = (0.35, 0.35, 0.35)


def _linear(srgb) -> np.ndarray:
    """sRGB components (0–1) to scene-linear, as Blender's float colour attributes hold them."""
    c = np.asarray(srgb, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def colours(values: np.ndarray, defined: np.ndarray, scale: float) -> np.ndarray:
    """RGBA (n, 4), scene-linear: ``values`` on the diverging map at ± ``scale`` (clamped
    beyond), grey where not ``defined``."""
    t = np.clip(np.asarray(values, dtype=np.float64) / scale, -1.0, 1.0)[:, None]
    cool, zero, warm = _linear(_COOL), _linear(_ZERO), _linear(_WARM)
    rgb = np.where(t < 0.0, zero + (cool - zero) * (-t), zero + (warm - zero) * t)
    rgb[~np.asarray(defined, dtype=bool)] = _linear(_UNDEFINED)
    return np.concatenate([rgb, np.ones((len(rgb), 1))], axis=1)


def default_scale(values: np.ndarray, defined: np.ndarray) -> float:
    """The :data:`SCALE_QUANTILE` of |value| over the defined vertices (a positive number;
    1 when every defined value is 0 or none is defined)."""
    v = np.abs(np.asarray(values, dtype=np.float64)[np.asarray(defined, dtype=bool)])
    s = float(np.quantile(v, SCALE_QUANTILE)) if len(v) else 0.0
    return s if s > 0.0 and np.isfinite(s) else 1.0


def _point_attribute(mesh, name: str, kind: str):
    attr = mesh.attributes.get(name)
    if attr is not None and (attr.domain != "POINT" or attr.data_type != kind):
        mesh.attributes.remove(attr)
        attr = None
    return attr or mesh.attributes.new(name, kind, "POINT")


def write(mesh, gaussian, mean, defined, kind: str, scale: float) -> None:
    """Write both curvatures and the colour map of ``kind`` (``"gaussian"`` or ``"mean"``) at
    ``scale`` onto ``mesh`` (one value per vertex, in vertex order), and make the colour the
    mesh's active and render colour attribute."""
    values = {"gaussian": gaussian, "mean": mean}[kind]
    for name, figures in ((GAUSSIAN_ATTRIBUTE, gaussian), (MEAN_ATTRIBUTE, mean)):
        attr = _point_attribute(mesh, name, "FLOAT")
        attr.data.foreach_set("value", np.asarray(figures, dtype=np.float32))
    _point_attribute(mesh, COLOUR_ATTRIBUTE, "FLOAT_COLOR").data.foreach_set(
        "color", colours(values, defined, scale).astype(np.float32).ravel()
    )
    colour_attributes = mesh.color_attributes
    index = next(i for i, a in enumerate(colour_attributes) if a.name == COLOUR_ATTRIBUTE)
    colour_attributes.active_color_index = index
    colour_attributes.render_color_index = index
    mesh.update()


def clear(mesh) -> bool:
    """Remove the curvature attributes from ``mesh``; True when there were any."""
    found = False
    for name in (GAUSSIAN_ATTRIBUTE, MEAN_ATTRIBUTE, COLOUR_ATTRIBUTE):
        attr = mesh.attributes.get(name)
        if attr is not None:
            mesh.attributes.remove(attr)
            found = True
    if found:
        mesh.update()
    return found
