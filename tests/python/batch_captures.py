"""Small captures for the batch tests, and what two runs of one batch must share."""
import os
import subprocess

# Every kind of step, on captures small enough that eight take a few seconds.
STEPS = ["refocus:0.5", "stack:-1:1:3", "edof", "depth", "page"]


def write_captures(folder, count, size=40, views=5):
    """`lfcam synth` light fields (textured planes at known depths), one seed each."""
    os.makedirs(folder, exist_ok=True)
    paths = [os.path.join(folder, f"capture_{seed:02d}.lf.h5") for seed in range(count)]
    for seed, path in enumerate(paths):
        subprocess.run([os.environ["LFCAM_EXECUTABLE"], "synth", "-o", path, "--views", str(views), "--size", str(size),
                        "--seed", str(seed)], check=True, capture_output=True)
    return paths


def files_below(folder, skip=("batch-report.json", )):
    """{relative path: bytes} of every file under folder, hidden ones included (the done-markers)."""
    found = {}
    for root, _, names in os.walk(folder):
        for name in names:
            path = os.path.join(root, name)
            relative = os.path.relpath(path, folder)
            if relative not in skip:
                with open(path, "rb") as f:
                    found[relative] = f.read()
    return found


def without_times(report):
    """The report with its timings and output folder taken out: what two runs of one batch share."""
    return {**report, "output": None, "captures": [{**c, "seconds": None} for c in report["captures"]]}
