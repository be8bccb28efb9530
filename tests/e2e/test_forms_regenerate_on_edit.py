"""Editing a form and rebuilding regenerates its C code: touch
forms/elasticity.py, rebuild the forms (pushout_forms, which the library
depends on), and the generated elasticity.c must be newer than before (FFCx
ran again). The library's sources that include the form's header are not
recompiled here (a minute of the suite); the next build does that, as after
any edit."""
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
p = subprocess.run(["cmake", "--build", build, "--target", "pushout_forms"],
                   capture_output=True, text=True)
check(p.returncode == 0, "rebuild succeeds")
check("FFCx: forms/elasticity.py" in p.stdout, "the rebuild ran FFCx on the form")
check(os.path.getmtime(generated) > before, "elasticity.c was regenerated")
