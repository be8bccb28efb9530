"""The mesh is generated from the scene once and reused when the same mesh
parameters come again; a changed parameter makes a new mesh."""
import shutil
import os
import subprocess

from common import OUT_ROOT, PUSHOUT, check, curve, out_dir, run, summary

scene = """
[mesh]
elements_per_quarter = 4
elements_through_thickness = 2
[loading]
steps = 2
"""
cache = os.path.join(OUT_ROOT, "mesh-cache-test")
shutil.rmtree(cache, ignore_errors=True)
os.environ["PUSHOUT_CACHE_DIR"] = cache
a, b, c = out_dir("cache_a"), out_dir("cache_b"), out_dir("cache_c")
first_line = lambda p: p.stdout.splitlines()[0]  # noqa: E731  the size guard's
pa = run(scene, a, quiet=False)
pb = run(scene, b, quiet=False)
run(scene, c, sets=["mesh.steel_layers=2"])
check(not summary(a)["mesh_reused"], "first run generates the mesh")
check(summary(b)["mesh_reused"], "second run reuses it")
# The first progress line says which, before either begins (it said
# "meshing" for a cached mesh too).
check(first_line(pa).startswith("pushout: meshing "), f"the first run says it meshes: {first_line(pa)!r}")
check(first_line(pb).startswith("pushout: the cached mesh, "),
      f"the second says the mesh comes from the cache: {first_line(pb)!r}")
check(not summary(c)["mesh_reused"], "another steel_layers makes a new mesh")
strip = lambda rows: [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]  # noqa: E731
check(strip(curve(a)) == strip(curve(b)), "same curve from the cached mesh")
check(summary(c)["dofs"] != summary(a)["dofs"], "the new mesh differs")

# The cache is bounded ($PUSHOUT_CACHE_MAX_MB): past the bound the least
# recently used meshes go; a reused mesh counts as used. Each coarse mesh
# here is 35-55 kB: 0.12 MB holds two or three.
shutil.rmtree(cache, ignore_errors=True)
meshes = lambda: sorted(f for f in os.listdir(cache) if f.endswith(".mesh"))  # noqa: E731
os.environ["PUSHOUT_CACHE_MAX_MB"] = "0.12"
layers = {n: ["mesh.steel_layers=" + str(n)] for n in (1, 2, 3, 4, 5)}
run(scene, out_dir("cache_l1"), sets=layers[1])
first = meshes()
run(scene, out_dir("cache_l2"), sets=layers[2])
run(scene, out_dir("cache_l1_again"), sets=layers[1])  # renews the first
check(summary(os.path.join(os.path.dirname(a), "cache_l1_again"))["mesh_reused"],
      "a cached mesh is reused under a bound")
for n in (3, 4, 5):
    run(scene, out_dir(f"cache_l{n}"), sets=layers[n])
size_mb = sum(os.path.getsize(os.path.join(cache, f)) for f in meshes()) / 2 ** 20
check(size_mb <= 0.12, f"the cache holds {size_mb:.3f} MB <= 0.12 MB ({len(meshes())} meshes)")
check(len(meshes()) >= 2, "it still holds the newest meshes")
run(scene, out_dir("cache_l5_again"), sets=layers[5])
check(summary(os.path.join(os.path.dirname(a), "cache_l5_again"))["mesh_reused"], "the newest stays")
run(scene, out_dir("cache_l2_again"), sets=layers[2])
check(not summary(os.path.join(os.path.dirname(a), "cache_l2_again"))["mesh_reused"],
      "the least recently used went first")

# A damaged cache file (cut short, or not one of ours) is meshed again.
for name, damage in (("cut", lambda data: data[: len(data) // 2]), ("foreign", lambda data: b"$MeshFormat" + data)):
    for f in meshes():
        path = os.path.join(cache, f)
        with open(path, "rb") as fh:
            data = fh.read()
        with open(path, "wb") as fh:
            fh.write(damage(data))
    out = out_dir(f"cache_damaged_{name}")
    run(scene, out, sets=layers[5])
    check(not summary(out)["mesh_reused"] and strip(curve(out)) == strip(curve(os.path.join(
        os.path.dirname(a), "cache_l5"))), f"a {name} cache file is meshed again, the same curve")

# PUSHOUT_CACHE_MAX_MB = 0: no cache at all.
shutil.rmtree(cache, ignore_errors=True)
os.environ["PUSHOUT_CACHE_MAX_MB"] = "0"
run(scene, out_dir("cache_off_1"))
run(scene, out_dir("cache_off_2"))
check(not summary(os.path.join(os.path.dirname(a), "cache_off_2"))["mesh_reused"]
      and not (os.path.isdir(cache) and meshes()), "PUSHOUT_CACHE_MAX_MB=0 stores and reuses nothing")
os.environ["PUSHOUT_CACHE_MAX_MB"] = "lots"
p = run(scene, out_dir("cache_bad"), check=False)
# The user's input, as a bad option is: exit 2 (README's exit codes), and
# named as the environment's, not the scene's.
check(p.returncode == 2 and p.stderr.startswith("pushout: error: PUSHOUT_CACHE_MAX_MB"),
      f"a bad bound is a clear error, exit 2: {p.returncode}, {p.stderr.strip()!r}")
# So it is for a sweep and a fit, before any case (each case failed with
# "mesh generation failed", exit 1, and the sweep with exit 3).
scene_file = os.path.join(os.path.dirname(a), "cache_bad.toml")
data_file = os.path.join(os.path.dirname(a), "cache_bad_data.csv")
with open(data_file, "w") as f:
    f.write("delta_mm,tau_MPa\n0.001,0.1\n0.002,0.2\n0.003,0.3\n")
for command in (["sweep", scene_file, "--vary", "loading.steps=1,2"],
                ["fit", scene_file, "--data", data_file, "--free", "interface.0.mu"]):
    p = subprocess.run([PUSHOUT] + command + ["--out", out_dir(f"cache_bad_{command[0]}"), "--quiet"],
                       capture_output=True, text=True, timeout=120)
    check(p.returncode == 2 and "PUSHOUT_CACHE_MAX_MB" in p.stderr,
          f"{command[0]}: a bad bound is exit 2 before any case: {p.returncode}, {p.stderr.strip()!r}")
