"""What a Dask worker runs: one ``tinlod tiles --part`` job.

The driver pickles this module by value (cloudpickle), so workers need Dask and the tinlod binary,
not this package.
"""
import shutil
import signal
import subprocess
import time


class JobFailed(RuntimeError):
    """A job's tinlod run died; the message says how."""


def run_part(command):
    """Runs ``command`` (a ``tinlod tiles ... --part SPEC`` argument list).

    Returns ``(seconds, None)``, or ``(None, line)`` when tinlod refused the job with its own
    ``tinlod: error: ...`` line (exit status 1 or 2): the same job fails the same way anywhere, so
    it is returned rather than raised, and Dask does not retry it. A tinlod killed by a signal (the
    kernel's OOM killer, a machine going down) raises JobFailed: Dask runs that job again.
    """
    start = time.monotonic()
    # Killed with the worker (setpriv's parent-death signal), as on a machine that went down: a
    # job the scheduler runs again elsewhere is not also still writing here.
    if shutil.which("setpriv"):
        command = ["setpriv", "--pdeathsig", "KILL", *command]
    run = subprocess.run(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True, errors="replace", check=False)
    if run.returncode in (1, 2):
        lines = [line for line in run.stderr.splitlines() if line.strip()]
        return None, lines[-1].strip() if lines else f"tinlod exited with status {run.returncode}"
    if run.returncode < 0:
        raise JobFailed(f"tinlod killed by {signal.Signals(-run.returncode).name}")
    if run.returncode != 0:
        raise JobFailed(f"tinlod exited with status {run.returncode}")
    return time.monotonic() - start, None
