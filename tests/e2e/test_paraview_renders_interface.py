"""The paper's Fig. 8 maps: ParaView (pvbatch, under a virtual X server)
renders the interface tractions of a push-out from interface.xdmf, the way
scripts/studies.py does. A missing ParaView is a failure with one clear line
(scripts/setup.sh installs it), never a skip or a traceback; the picture
must have content (many colours: the colour maps), not be blank."""
import os
import sys

from common import SOURCE, check, out_dir, run

sys.path.insert(0, os.path.join(SOURCE, "scripts"))
import studies  # noqa: E402

out = out_dir("render_interface")
run("[mesh]\nelements_per_quarter = 8\nelements_through_thickness = 4\n"
    "[loading]\ntemperature_change = -5.0\npush_displacement = 0.01\nsteps = 3\n"
    "[output]\nxdmf = true\nplot = false\n", out)
png = os.path.join(out, "maps.png")
try:
    studies.render_interface(out, png, "render test")
except studies.RenderError as e:
    check(False, str(e))

import matplotlib.image  # noqa: E402

image = matplotlib.image.imread(png)
colours = {tuple(p) for row in image[::4] for p in row[::4]}
check(os.path.getsize(png) > 20000, f"maps.png written ({os.path.getsize(png)} bytes)")
check(len(colours) > 50, f"maps.png has content: {len(colours)} colours")
