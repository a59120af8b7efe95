"""What differs between the Blender versions batten runs on (4.2 LTS to 5.0), in one place.

Each name is a capability looked up once in the running Blender, never a version number
compared in the code that uses it; a module that needs one imports it from here. Tested on
the latest bpy of 4.2 and 4.5 and on 5.0 (``make test-compat``, ``make test``).
"""

from __future__ import annotations

import blf

#: ``blf`` can draw text into an ``imbuf`` image buffer (``blf.bind_imbuf`` and
#: ``blf.draw_buffer``, Blender 4.3 and newer), which needs no GPU. Blender 4.2 can't, so a
#: chart's text there is filled from the glyph outlines of a text object
#: (:mod:`batten.glyph_outlines`).
BLF_DRAWS_INTO_IMBUF: bool = hasattr(blf, "bind_imbuf")
