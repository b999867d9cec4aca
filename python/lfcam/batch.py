"""lfcam.batch: one pipeline applied to every capture, on this machine or on a Dask cluster.

    report = lfcam.batch.run(["captures/*.lf.h5"], "out", ["refocus:0.5", "depth"])
    report = lfcam.batch.run("captures", "out", "edof,page", client="tcp://scheduler:8786")

The contract of `lfcam batch` (docs/batch.md): each capture writes under OUTDIR/<name>/, every file
atomically; a rerun skips complete captures and redoes half-done ones; a bad capture does not stop
the others; the report goes to OUTDIR/batch-report.json (or `report`). Each capture runs the
library's own batch code (the C++ runBatchCapture), so the outputs are the same bytes on one
machine and on a cluster.

With `client` (a distributed.Client, or a scheduler's address), each capture is one Dask task on
the cluster's workers. Every worker must import this package (the same build on a shared path, or
installed) and see the inputs, the white image and OUTDIR under the same absolute paths as the
caller. A worker lost mid-capture has its task rerun on another; the rerun redoes the capture whole.

`python3 -m lfcam.batch` is the command line's `lfcam batch --dask ADDRESS` (the command hands over
to it) and takes the same flags.
"""
import argparse
import json
import os
import sys
import time
import uuid

from . import _lfcam
from ._lfcam import Error, UsageError

__all__ = ["BatchError", "run", "main"]

# Seconds to reach a scheduler before giving up (an unreachable one is an error, not a hang).
CONNECT_TIMEOUT = 3


class BatchError(Error):
    """Some captures failed; the others were done. `report` is the whole report (a dict, also written
    to its file), its failed captures with their one-line messages."""

    def __init__(self, message, report):
        super().__init__(message)
        self.report = report


def run(inputs, output, steps, white=None, jobs=None, report=None, client=None, progress=None, whites=None,
        any_camera=False):
    """Applies `steps` to every capture of `inputs` and returns the report (a dict, as batch-report.json).

    inputs: a path or a list of them: light-field files or folders, raws (with `white`), folders of
        inputs, or globs (expanded here; one matching nothing is a UsageError).
    output: OUTDIR; each capture writes under OUTDIR/<input's name>/.
    steps: a list, or a comma-separated string, of refocus:SLOPE, stack:FROM:TO:N, edof, depth, page,
        photo:NAME?FIELD=TEXT&... (any photograph: lfcam.photo_fields()), volume:SETTINGS (a microscope
        volume.tif; SETTINGS as lfcam volume --optics takes them; the PSF computed once into OUTDIR).
    white: the inputs are raw lenslet images of this white image, decoded on the way.
    whites: ... or of the white a white-image database (lfcam whites index) chooses for each capture's
        camera, zoom and focus; any_camera: among every camera's whites.
    jobs: captures at once on this machine (default: half the cores, 1 to 4); not used with `client`.
    report: the report's file (default: OUTDIR/batch-report.json).
    client: a distributed.Client or a scheduler address ("tcp://HOST:8786"): one Dask task per capture.
    progress: called as progress(finished, total) as captures finish.

    Raises lfcam.UsageError for a bad request (before any work), lfcam.Error when the scheduler cannot
    be reached, and lfcam.batch.BatchError (an lfcam.Error carrying .report) when any capture failed,
    after all the others were done and the report was written: the command line's exit status 1.
    """
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    if isinstance(steps, str):
        steps = _lfcam._split_batch_steps(steps)
    plan = _lfcam._batch_plan([os.fspath(i) for i in inputs], os.fspath(output), list(steps),
                              os.fspath(white) if white else "", os.fspath(report) if report else "",
                              os.fspath(whites) if whites else "", bool(any_camera))
    if client is None:
        total = len(plan.captures)
        by_fraction = progress and (lambda fraction: progress(round(fraction * total), total))
        text, failure = _lfcam._batch_run_local(plan, jobs or 0, by_fraction)
    else:
        text, failure = _run_on_dask(plan, client, progress)
    result = json.loads(text)
    if failure:
        raise BatchError(failure, result)
    return result


def capture_task(input, name, steps, white, output, base="", whites="", any_camera=False):
    """One capture on a Dask worker: the C++ runBatchCapture, the single-machine batch's own code.
    base: the caller's working folder, where the steps' relative paths (volume:SETTINGS) start."""
    return _lfcam._batch_capture(input, name, steps, white, output, base, whites, any_camera)


def _connect(address):
    try:
        from distributed import Client
    except ImportError as e:
        raise Error(f"batch: a Dask scheduler needs the Python package distributed (Debian: python3-distributed): {e}")
    try:
        return Client(address, timeout=CONNECT_TIMEOUT)
    except ValueError as e:
        raise UsageError(f"batch: --dask {address}: {e}") from None
    except (OSError, TimeoutError) as e:
        raise Error(f"batch: cannot reach the Dask scheduler at {address}: {e}") from None


def _run_on_dask(plan, client, progress):
    owned = isinstance(client, str)
    if owned:
        client = _connect(client)
    try:
        # What the captures share (a volume step's PSF) is made here once, so the workers only read it.
        _lfcam._batch_prepare(plan)
        # Workers need not share the caller's working folder: they get absolute paths. The report
        # keeps the paths as given, as on one machine.
        absolute = os.path.abspath
        white = absolute(plan.white) if plan.white else ""
        whites = absolute(plan.whites) if plan.whites else ""
        run_id = uuid.uuid4().hex[:8]
        futures = [
            client.submit(capture_task, absolute(input), name, plan.steps, white, absolute(plan.output), os.getcwd(),
                          whites, plan.any_camera, key=f"lfcam-batch-{run_id}-{index}-{name}", pure=False, retries=2)
            for index, (input, name) in enumerate(plan.captures)
        ]
        try:
            outcomes = _gather(client, futures, plan, progress)
        except BaseException:  # Ctrl-C: the cluster stops working for this batch too
            client.cancel(futures)
            raise
        return _lfcam._batch_finish(plan, outcomes)
    finally:
        if owned:
            client.close()


def _gather(client, futures, plan, progress):
    from distributed import as_completed
    outcomes = [None] * len(futures)
    index_of = {future.key: index for index, future in enumerate(futures)}
    for finished, future in enumerate(as_completed(futures), 1):
        index = index_of[future.key]
        try:
            outcomes[index] = future.result()
        except Exception as e:  # a capture's own failure is an outcome: this is the cluster's (workers lost
            # more times than Dask allows, lfcam missing on a worker)
            input = plan.captures[index][0]
            outcomes[index] = {"status": "failed", "outputs": [], "seconds": 0.0,
                               "error": f"{input}: the Dask task failed: {type(e).__name__}: {e}".replace("\n", " ")}
        if progress:
            progress(finished, len(futures))
    return outcomes


class _ProgressLine:
    """`batch of N: K done, M:SS left` on stderr, on a terminal, after a second (as the C++ bar)."""

    def __init__(self):
        self.start, self.shown = time.monotonic(), False

    def __call__(self, finished, total):
        elapsed = time.monotonic() - self.start
        if not sys.stderr.isatty() or (not self.shown and elapsed < 1):
            return
        left = elapsed * (total - finished) / finished
        sys.stderr.write(f"\rbatch of {total}: {finished} done, {int(left) // 60}:{int(left) % 60:02d} left ")
        sys.stderr.flush()
        self.shown = True

    def close(self):
        if self.shown:
            sys.stderr.write("\r" + " " * 60 + "\r")


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line and exit 2, as the command line
        sys.stderr.write(f"lfcam: batch: {message}\n")
        sys.exit(2)


def main(argv=None):
    """`lfcam batch` from Python: prints as the command line does and returns its exit status."""
    parser = _Parser(prog="python3 -m lfcam.batch", description=__doc__.split("\n")[0])
    parser.add_argument("inputs", nargs="+", metavar="INPUT")
    parser.add_argument("-o", "--output", required=True)
    parser.add_argument("--steps", required=True, help="comma-separated steps")
    parser.add_argument("--white", default="")
    parser.add_argument("--whites", default="")
    parser.add_argument("--any-camera", action="store_true")
    parser.add_argument("--jobs", type=int, default=0)
    parser.add_argument("--report", default="")
    parser.add_argument("--dask", default=None, help="scheduler address, tcp://HOST:8786")
    args = parser.parse_args(argv)
    bar = _ProgressLine()
    try:
        report = run(args.inputs, args.output, args.steps, white=args.white, jobs=args.jobs, report=args.report,
                     client=args.dask, progress=bar, whites=args.whites, any_camera=args.any_camera)
        failure = None
    except BatchError as e:
        report, failure = e.report, str(e)
    except UsageError as e:
        print(f"lfcam: {e}", file=sys.stderr)
        return 2
    except Error as e:
        print(f"lfcam: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("lfcam: batch: interrupted; the same command resumes it", file=sys.stderr)
        return 130
    finally:
        bar.close()
    for capture in report["captures"]:
        if capture["status"] == "failed":
            print(f"lfcam: batch: failed: {capture['error']}", file=sys.stderr)
    print(f"batch: {report['done']} done, {report['skipped']} skipped (complete already), {report['failed']} failed; "
          f"report {args.report or os.path.join(args.output, 'batch-report.json')}")
    if failure:
        print(f"lfcam: {failure}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    # As lfcam.batch, not __main__, so that Dask sends workers capture_task by name.
    from lfcam.batch import main as package_main
    sys.exit(package_main())
