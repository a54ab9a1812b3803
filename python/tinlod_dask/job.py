"""What a Dask worker runs: one ``tinlod tiles --part`` job.

The driver pickles this module by value (cloudpickle), so workers need Dask and the tinlod binary,
not this package.
"""
import shutil
import signal
import subprocess
import time


class JobFailed(RuntimeError):
    """A job's tinlod run failed; the message is the tool's own error line."""


def run_part(command):
    """Runs ``command`` (a ``tinlod tiles ... --part SPEC`` argument list); returns its seconds.

    Raises JobFailed with tinlod's last stderr line (its ``tinlod: error: ...``) when it fails, so
    that Dask retries the job and the driver reports that line.
    """
    start = time.monotonic()
    # Killed with the worker (setpriv's parent-death signal), as on a machine that went down: a
    # job the scheduler runs again elsewhere is not also still writing here.
    if shutil.which("setpriv"):
        command = ["setpriv", "--pdeathsig", "KILL", *command]
    run = subprocess.run(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True, errors="replace", check=False)
    if run.returncode != 0:
        lines = [line for line in run.stderr.splitlines() if line.strip()]
        if lines:
            raise JobFailed(lines[-1].strip())
        if run.returncode < 0:
            raise JobFailed(f"tinlod killed by {signal.Signals(-run.returncode).name}")
        raise JobFailed(f"tinlod exited with status {run.returncode}")
    return time.monotonic() - start
