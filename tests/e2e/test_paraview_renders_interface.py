"""The paper's Fig. 8 maps: ParaView (pvbatch, under a virtual X server)
renders the interface tractions of a push-out from interface.xdmf, the way
scripts/studies.py does. A missing ParaView is a failure with one clear line
(scripts/setup.sh installs it), never a skip or a traceback; the picture
must have content (each map coloured over a range of its field, and its
colours in the picture), not be blank. A tube off
the slice's centre with a crack plane (the corroded demo's specimen) is
unrolled about its own axis, over its whole circumference, without the
crack plane's joints (the axis was once taken at the slice's centre, and
the plane's joints stretched s to 240 mm)."""
import math
import os
import re
import sys

from common import SOURCE, check, out_dir, run, summary

sys.path.insert(0, os.path.join(SOURCE, "scripts"))
import studies  # noqa: E402

out = out_dir("render_interface")
run("[mesh]\nelements_per_quarter = 8\nelements_through_thickness = 4\n"
    "[loading]\ntemperature_change = -5.0\npush_displacement = 0.01\nsteps = 3\n"
    "[output]\nxdmf = true\nplot = false\n", out)
png = os.path.join(out, "maps.png")
try:
    said = studies.render_interface(out, png, "render test")
except studies.RenderError as e:
    check(False, str(e))

import matplotlib.image  # noqa: E402
import numpy  # noqa: E402

# Each map is coloured over its field's range, and the tractions vary over
# the interface (through the thickness): a map of one value is blank.
ranges = re.findall(r"coloured (\S+): (\S+) to (\S+)", said)
check(len(ranges) >= 2 and all(float(hi) - float(lo) > 1e-3 * max(abs(float(lo)), abs(float(hi)))
                               for _, lo, hi in ranges),
      f"every map coloured over a range of its field: {ranges}")
# The maps' colours, not only the colour bars' and the text's: the share of
# saturated pixels (a map of one value is one grey: the bars alone gave
# 1.7 %, these maps 9.3 %).
image = matplotlib.image.imread(png)[:, :, :3]
saturated = float(numpy.mean(image.max(axis=2) - image.min(axis=2) > 0.2))
check(os.path.getsize(png) > 20000, f"maps.png written ({os.path.getsize(png)} bytes)")
check(saturated > 0.05, f"maps.png has coloured maps: {saturated:.1%} of its pixels saturated")

out = out_dir("render_interface_off_centre")
run(os.path.join(SOURCE, "demo", "pushout_corroded.toml"), out,
    sets=["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2", "corrosion.steps=2",
          "corrosion.penetration=0.004", "loading.steps=1", "loading.push_displacement=0.002",
          "output.xdmf=true", "output.plot=false"])
try:
    said = studies.render_interface(out, os.path.join(out, "maps.png"), "off-centre test")
except studies.RenderError as e:
    check(False, str(e))
m = re.search(r"unrolled: s (\S+) to (\S+) mm, z (\S+) to (\S+) mm, (\d+) of (\d+) cells", said)
check(m is not None, f"render_interface.py says what it drew: {said.strip()!r}")
s0, s1, z0, z1 = (float(m.group(i)) for i in range(1, 5))
kept, total = int(m.group(5)), int(m.group(6))
R = 10.0  # mm: the demo's tube, 20 mm across
# The nodes lie on the circle to the mesher's round-off; 1e-4 mm is far below an element.
# The seam (225 deg) lies on a node line of a centred tube's mesh only; off
# the centre the cells across it are kept whole, so the map starts within an
# element of 0 (h = pi R / 2 / 4).
check(abs(s1 - s0 - 2 * math.pi * R) < 1e-4 and -1e-4 < s0 < math.pi * R / 8,
      f"the whole circumference about the tube's own axis: s from {s0} to {s1} mm "
      f"({s1 - s0:.5f} against {2 * math.pi * R:.5f}), starting within an element of 0")
check(abs(z0) < 1e-4 and abs(z1 - 20.0) < 1e-4, f"the whole thickness: z from {z0} to {z1} mm")
check(summary(out)["symmetry"] == "full" and kept == 4 * 4 * 2 and total > kept,
      f"the tube's 4 x 4 x 2 cells kept, the crack plane's left out: {kept} of {total}")
