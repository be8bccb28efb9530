"""The mesh is generated from the scene once and reused when the same mesh
parameters come again; a changed parameter makes a new mesh."""
import shutil
import os

from common import check, curve, out_dir, run, summary

scene = """
[mesh]
elements_per_quarter = 4
elements_through_thickness = 2
[loading]
steps = 2
"""
cache = os.path.join(os.environ.get("PUSHOUT_TEST_OUT", "/tmp"), "mesh-cache-test")
shutil.rmtree(cache, ignore_errors=True)
os.environ["PUSHOUT_CACHE_DIR"] = cache
a, b, c = out_dir("cache_a"), out_dir("cache_b"), out_dir("cache_c")
run(scene, a)
run(scene, b)
run(scene, c, sets=["mesh.steel_layers=2"])
check(not summary(a)["mesh_reused"], "first run generates the mesh")
check(summary(b)["mesh_reused"], "second run reuses it")
check(not summary(c)["mesh_reused"], "another steel_layers makes a new mesh")
strip = lambda rows: [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]  # noqa: E731
check(strip(curve(a)) == strip(curve(b)), "same curve from the cached mesh")
check(summary(c)["dofs"] != summary(a)["dofs"], "the new mesh differs")
