"""Editing a form and rebuilding regenerates its C code: touch
forms/elasticity.py, rebuild the library, and the generated elasticity.c must
be newer than before (FFCx ran again)."""
import os
import subprocess
import time

from common import check

source = os.environ["PUSHOUT_SOURCE_DIR"]
build = os.environ["PUSHOUT_BUILD_DIR"]
form = os.path.join(source, "forms", "elasticity.py")
generated = os.path.join(build, "elasticity.c")

check(os.path.exists(generated), "generated elasticity.c exists in the build tree")
before = os.path.getmtime(generated)
time.sleep(1.1)
os.utime(form)  # same content, newer time: what an edit looks like to make
p = subprocess.run(["cmake", "--build", build, "--target", "pushout_core"],
                   capture_output=True, text=True)
check(p.returncode == 0, "rebuild succeeds")
check("FFCx: forms/elasticity.py" in p.stdout, "the rebuild ran FFCx on the form")
check(os.path.getmtime(generated) > before, "elasticity.c was regenerated")
