"""Every scene in demo/ runs to the end (push-out scenes on a coarse mesh
with few steps, to keep the suite fast) and writes its outputs."""
import glob
import os

from common import SOURCE, check, curve, out_dir, run, summary

scenes = sorted(glob.glob(os.path.join(SOURCE, "demo", "*.toml")))
check(len(scenes) >= 8, f"{len(scenes)} demo scenes")
for scene in scenes:
    name = os.path.basename(scene)[:-5]
    out = out_dir("demo_" + name)
    sets = ["output.plot=false"]
    if name.startswith("pushout"):
        sets += ["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2", "loading.steps=5"]
    run(scene, out, sets=sets)
    s = summary(out)
    check(s["converged"] and len(curve(out)) == s["steps"] + 1, f"{name}: converged, {s['steps']} steps")
