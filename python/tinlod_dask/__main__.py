"""python3 -m tinlod_dask tiles DEM... -o DIR (--scheduler tcp://HOST:PORT | --local N)

Runs `tinlod tiles` over a Dask cluster (docs/scaling.md): the pyramid is cut into jobs
(plan.py), each a ``tinlod tiles --part SPEC --threads 1`` on a worker, writing into a staging
folder inside DIR; layer.json is written last (``--layer-only``) and the levels moved in, replacing
those of an earlier run, as the single-process build does. DEMs, DIR and the tinlod binary must be
at the same paths on every worker (a shared filesystem).
"""
import argparse
import json
import logging
import os
import shutil
import subprocess
import sys
import tempfile
import time
import uuid

from . import job, plan

PROG = "tinlod_dask"


class Failure(Exception):
    """Ends the run with one line and an exit status."""

    def __init__(self, line, status=1):
        super().__init__(line)
        self.status = status


def tool_error(run):
    """The last line tinlod wrote to stderr (its ``tinlod: error: ...``)."""
    lines = [line for line in run.stderr.splitlines() if line.strip()]
    return lines[-1] if lines else f"tinlod exited with status {run.returncode}"


def parse(argv):
    parser = argparse.ArgumentParser(prog=f"python3 -m {PROG}")
    commands = parser.add_subparsers(dest="command", required=True)
    tiles = commands.add_parser(
        "tiles", help="tinlod tiles over a Dask cluster: the same tile set, byte for byte")
    tiles.add_argument("dem", nargs="+", metavar="DEM")
    tiles.add_argument("-o", "--output", required=True, metavar="DIR",
                       help="the tile set's folder, on storage every worker sees")
    tiles.add_argument("--min-zoom", type=int, metavar="Z")
    tiles.add_argument("--max-zoom", type=int, metavar="Z")
    tiles.add_argument("--normals", action="store_true")
    tiles.add_argument("--fill-height", metavar="H")
    tiles.add_argument("--memory-mb", metavar="M",
                       help="memory each job may hold, MiB (tinlod tiles --memory-mb; default "
                       "tinlod's, half of the machine's memory per job: give the worker "
                       "machine's memory over its jobs at once)")
    where = tiles.add_mutually_exclusive_group(required=True)
    where.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                       help="a running Dask scheduler")
    where.add_argument("--local", type=int, metavar="N",
                       help="a local cluster of N single-threaded worker processes")
    tiles.add_argument("--tinlod", default=shutil.which("tinlod"), metavar="PATH",
                       help="the tinlod binary, at this path on every worker "
                       "(default: tinlod on PATH)")
    tiles.add_argument("--cut-zoom", type=int, metavar="Z",
                       help="the level the jobs' subtrees start from (default: plan.choose_cut)")
    tiles.add_argument("--retries", type=int, default=2, metavar="N",
                       help="times a job whose tinlod or worker died is run again (default 2); "
                       "a job tinlod refuses with its own error line is not")
    args = parser.parse_args(argv)
    if args.local is not None and args.local < 1:
        parser.error("--local: at least 1 worker")
    if not args.tinlod or not os.access(args.tinlod, os.X_OK):
        parser.error("--tinlod: no tinlod binary (give its path)")
    return args


def tile_options(args, max_zoom):
    """The options of `tinlod tiles` every run of the build shares (tinlod's default --max-zoom
    when ``max_zoom`` is None)."""
    opts = [] if max_zoom is None else ["--max-zoom", str(max_zoom)]
    if args.min_zoom is not None:
        opts += ["--min-zoom", str(args.min_zoom)]
    if args.normals:
        opts.append("--normals")
    if args.fill_height is not None:
        opts += ["--fill-height", args.fill_height]
    if args.memory_mb is not None:
        opts += ["--memory-mb", args.memory_mb]
    return opts


def run_tool(command):
    """Runs tinlod here; a failure ends the run with its error line and status."""
    run = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                         errors="replace", check=False)
    if run.returncode != 0:
        raise Failure(tool_error(run), 2 if run.returncode == 2 else 1)
    return run.stdout


def connect(args, scratch):
    """A client of the scheduler, or of a local cluster (its workers' scratch space in
    ``scratch``); the cluster it started, if any; and the worker threads."""
    from distributed import Client, LocalCluster
    if args.local is not None:
        # The workers' scratch space in a folder of this run (the default one, shared by every
        # local cluster, holds the locks of killed ones).
        cluster = LocalCluster(n_workers=args.local, threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.ERROR,
                               local_directory=scratch)
        return Client(cluster), cluster, args.local
    try:
        client = Client(args.scheduler, timeout="20s")
    except OSError as e:
        raise Failure(f"--scheduler: {args.scheduler}: {e}") from e
    try:
        client.wait_for_workers(1, timeout=60)
    except TimeoutError as e:
        client.close()
        raise Failure(f"--scheduler: {args.scheduler}: no worker in 60 s") from e
    return client, None, sum(client.nthreads().values())


def run_jobs(client, tinlod, dems, stage, opts, specs, retries):
    """Submits the jobs and waits for them, showing progress; returns the tiles and the jobs'
    seconds summed. Raises Failure when one fails for good."""
    import cloudpickle
    from distributed import as_completed
    # Workers need not import this package: the job's code travels with it.
    cloudpickle.register_pickle_by_value(job)
    token = uuid.uuid4().hex[:8]
    commands = [[tinlod, "--threads", "1", "tiles", *dems, "-o", stage, *opts, "--part", spec]
                for spec, _ in specs]
    # In the order given, the levels above the cut first: that job is the longest (coarse tiles
    # measure the error at every post they cover), so it starts at once.
    futures = [client.submit(job.run_part, command, key=f"tinlod-part-{spec}-{token}",
                             retries=retries, priority=len(specs) - k)
               for k, (command, (spec, _)) in enumerate(zip(commands, specs))]
    spec_of = {f.key: spec for f, (spec, _) in zip(futures, specs)}
    tiles_of = {f.key: tiles for f, (_, tiles) in zip(futures, specs)}
    total = sum(tiles for _, tiles in specs)
    done_jobs = done_tiles = 0
    job_seconds = 0.0
    tty = sys.stderr.isatty()
    try:
        for future in as_completed(futures):
            if future.status != "finished":
                # "error": the job's last try died (JobFailed, or Dask's KilledWorker after its
                # workers died); otherwise the scheduler cancelled or lost it.
                error = future.exception() if future.status == "error" else future.status
                raise Failure(f"part {spec_of[future.key]}: {error}")
            seconds, refused = future.result()
            if refused:
                raise Failure(f"part {spec_of[future.key]}: {refused}")
            done_jobs += 1
            job_seconds += seconds
            done_tiles += tiles_of[future.key]
            line = f"{PROG}: {done_jobs}/{len(futures)} jobs, {done_tiles}/{total} tiles"
            print("\r" + line if tty else line, end="" if tty else "\n", file=sys.stderr,
                  flush=True)
        if tty:
            print(file=sys.stderr)
    except BaseException:
        client.cancel(futures)
        raise
    return total, job_seconds


def commit(stage, output, levels):
    """Moves the staged levels and layer.json into DIR, replacing the levels of an earlier run."""
    # Hidden files in the stage are the temporaries of jobs killed while writing a tile.
    for folder, _, files in os.walk(stage):
        for name in files:
            if name.startswith("."):
                os.remove(os.path.join(folder, name))
    for z in levels:
        shutil.rmtree(os.path.join(output, str(z)), ignore_errors=True)
        if os.path.isdir(os.path.join(stage, str(z))):
            os.rename(os.path.join(stage, str(z)), os.path.join(output, str(z)))
    os.replace(os.path.join(stage, "layer.json"), os.path.join(output, "layer.json"))


def tiles(args):
    tinlod = os.path.abspath(args.tinlod)
    dems = [os.path.abspath(d) for d in args.dem]
    output = os.path.abspath(args.output)
    # The plan: the levels and their tiles, as tinlod computes them (its default --max-zoom too).
    pyramid = json.loads(run_tool([tinlod, "tiles", *dems, "-o", output, "--plan",
                                   *tile_options(args, args.max_zoom)]))
    opts = tile_options(args, pyramid["max_zoom"])
    if args.cut_zoom is not None and not \
            pyramid["min_zoom"] <= args.cut_zoom <= pyramid["max_zoom"]:
        raise Failure(f"--cut-zoom: a level from {pyramid['min_zoom']} to "
                      f"{pyramid['max_zoom']}", 2)
    scratch = tempfile.TemporaryDirectory(prefix="tinlod-dask-")
    client, cluster, workers = connect(args, scratch.name)
    try:
        cut = args.cut_zoom if args.cut_zoom is not None else plan.choose_cut(pyramid, workers)
        specs = plan.jobs(pyramid, cut)
        print(f"{PROG}: levels {pyramid['min_zoom']} to {pyramid['max_zoom']} cut at level "
              f"{cut}: {len(specs)} jobs on {workers} worker threads", file=sys.stderr)
        created = not os.path.exists(output)
        os.makedirs(output, exist_ok=True)
        stage = tempfile.mkdtemp(prefix=".tinlod-dask-", dir=output)
        try:
            os.chmod(stage, 0o755)
            start = time.monotonic()
            total, job_seconds = run_jobs(client, tinlod, dems, stage, opts, specs,
                                          args.retries)
            seconds = time.monotonic() - start
            run_tool([tinlod, "tiles", *dems, "-o", stage, *opts, "--layer-only"])
            commit(stage, output, range(pyramid["min_zoom"], pyramid["max_zoom"] + 1))
        except BaseException:
            # A failed run leaves DIR as it was (a folder it made is removed).
            shutil.rmtree(stage, ignore_errors=True)
            if created:
                shutil.rmtree(output, ignore_errors=True)
            raise
        shutil.rmtree(stage, ignore_errors=True)
    finally:
        client.close()
        if cluster:
            cluster.close()
        scratch.cleanup()
    print(f"{output}: {total} tiles on levels {pyramid['min_zoom']} to {pyramid['max_zoom']}, "
          f"jobs done in {seconds:.1f} s ({total / seconds:.1f} tiles/s; the jobs ran "
          f"{job_seconds:.1f} s in all)", file=sys.stderr)


def main(argv=None):
    args = parse(argv)
    try:
        tiles(args)
    except Failure as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return e.status
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
