#!/usr/bin/env python3
"""The native .lf.h5 as a Python user reads it: h5py (Debian's python3-h5py), decoded as
docs/formats.md says, agrees with what lfcam wrote, for float32, 8-bit sRGB and 16-bit linear
samples. Skips (exit 77) when no interpreter at hand has h5py.

    read_native_file.py LFCAM
"""
import os
import subprocess
import sys
import tempfile

try:
    import h5py
    import numpy as np
except ImportError:
    # CMake may have found another Python than Debian's, which is where python3-h5py installs.
    if sys.executable != "/usr/bin/python3" and os.access("/usr/bin/python3", os.X_OK) and \
            subprocess.run(["/usr/bin/python3", "-c", "import h5py"], capture_output=True).returncode == 0:
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    print("SKIPPED: h5py is missing (Debian: apt-get install python3-h5py)")
    sys.exit(77)


def lfcam(*args):
    subprocess.run([sys.argv[1], *args], check=True, stdout=subprocess.DEVNULL)


def read(path):
    """The snippet of docs/formats.md: linear float32 samples, whatever the encoding."""
    with h5py.File(path, "r") as f:
        d = f["lightfield"]
        lf = d[...]
        encoding = d.attrs.get("encoding", b"float").decode()
        if encoding == "srgb8":
            c = lf / 255.0
            lf = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4).astype(np.float32)
        elif encoding == "linear":
            lf = (lf * d.attrs["scale"]).astype(np.float32)
        return d.dtype, encoding, f.attrs["axes"].decode(), lf


def main():
    with tempfile.TemporaryDirectory() as work:
        floats = os.path.join(work, "float.lf.h5")
        lfcam("synth", "--views", "3", "--size", "16", "-o", floats)
        lfcam("convert", floats, "-o", os.path.join(work, "hci"))  # 8-bit sRGB PNGs
        lfcam("convert", os.path.join(work, "hci"), "-o", os.path.join(work, "srgb8.lf.h5"))
        lfcam("convert", floats, "-o", os.path.join(work, "lenslet.tif"), "--16bit")  # 16-bit linear
        lfcam("convert", os.path.join(work, "lenslet.tif"), "-o", os.path.join(work, "linear16.lf.h5"))

        dtype, encoding, axes, reference = read(floats)
        assert (str(dtype), encoding, axes) == ("float32", "float", "v,u,c,t,s"), (dtype, encoding, axes)
        assert reference.shape == (3, 3, 3, 16, 16), reference.shape
        failures = []
        for name, want_dtype, want_encoding, tolerance in (("srgb8", "uint8", "srgb8", 0.01),
                                                          ("linear16", "uint16", "linear", 1e-4)):
            dtype, encoding, _, values = read(os.path.join(work, name + ".lf.h5"))
            worst = float(np.abs(values - np.clip(reference, 0, 1)).max())
            print(f"{name}: {dtype}, encoding {encoding}, largest difference from the float32 file {worst:.2g}")
            if (str(dtype), encoding) != (want_dtype, want_encoding) or worst > tolerance:
                failures.append(name)
        if failures:
            sys.exit("h5py does not read back what lfcam wrote: " + ", ".join(failures))
    print("h5py reads every encoding of the native file")


if __name__ == "__main__":
    main()
