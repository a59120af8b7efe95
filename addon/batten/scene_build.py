"""Building a scene's hull with the scene's settings (the Build operator and Live both do)."""

import json

from . import api
from .network_markers import network_markers


def build_into_scene(scene) -> dict:
    """Build the scene's hull with its settings, keep the report in the scene (JSON) with the
    overlay's markers (from the report's nodes and warnings), and return it; a failure is kept
    as the report's error and raised again."""
    settings = scene.batten
    try:
        result = api.build(
            settings.source,
            tolerance=settings.tolerance,
            resolution=settings.resolution,
            mirror=settings.mirror,
        )
    except api.BattenError as e:
        settings.last_report = json.dumps({"error": str(e)})
        raise
    report = result.report
    report["markers"] = network_markers(report["node_positions"], report["node_kinds"], report["warnings"])
    settings.last_report = json.dumps(report)
    return report
