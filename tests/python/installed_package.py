#!/usr/bin/env python3
"""The installed package as a user meets it: Debian's python3, started from an empty folder with an
empty environment (no PYTHONPATH, no LD_LIBRARY_PATH), imports lfcam from SITE, round-trips a
light field through a file, and loads the camera-raw module through the extension's run path.
Skips (exit 77) when nothing is installed in SITE (scripts/build.sh installs it there).

    installed_package.py SITE    (PREFIX/lib/python3.X/dist-packages)
"""
import os
import subprocess
import sys
import tempfile

USER = """
import numpy as np
import lfcam
print(lfcam.__file__)
lf = lfcam.LightField(np.arange(2 * 3 * 1 * 4 * 5, dtype=np.float32).reshape(2, 3, 1, 4, 5))
lfcam.write("a.lf.h5", lf)
assert (lfcam.read("a.lf.h5").samples == lf.samples).all()
open("white.dng", "wb").write(b"not a camera raw")
try:
    lfcam.calibrate("white.dng")
except lfcam.Error as e:
    print(e)
"""

site = os.path.realpath(sys.argv[1])
package = os.path.join(site, "lfcam")
if not os.path.isfile(os.path.join(package, "__init__.py")):
    print(f"SKIPPED: lfcam is not installed in {site} (scripts/build.sh installs it: "
          "cmake --install build --component python --prefix /usr/local)")
    sys.exit(77)

with tempfile.TemporaryDirectory() as folder:
    run = subprocess.run(["/usr/bin/python3", "-c", USER], cwd=folder, env={}, capture_output=True, text=True)
if run.returncode != 0:
    sys.exit(f"FAILED: /usr/bin/python3 could not use the installed lfcam:\n{run.stderr}")
imported, raw_error = run.stdout.splitlines()
if os.path.dirname(os.path.realpath(imported)) != package:
    sys.exit(f"FAILED: /usr/bin/python3 imported {imported}, not the package installed in {package}")
if "cannot be loaded" in raw_error:
    sys.exit(f"FAILED: the installed extension does not find lfcam's modules: {raw_error}")
print(f"imported {imported}; a camera raw reached LibRaw: {raw_error}")
