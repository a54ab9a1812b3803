"""The jobs of a tile build: the pyramid `tinlod tiles --plan` describes, cut at one level.

A cut at level C makes one job per tile of level C above a tile written on levels C and below
(``tinlod tiles --part C/X/Y``: that subtree), and one for the levels above C (``--part top:C``).
The levels and their tiles come from tinlod itself; here are only the rectangles' arithmetic.
"""

# A job's window of the DEM, once tinlod reads windows: a tile of the cut level at most this many
# posts across (4097^2 float heights, 64 MB), unless the whole coverage is that small.
MAX_WINDOW_POSTS = 4096
# Jobs per worker thread: enough that the last jobs to finish leave few workers idle and a lost
# worker costs little work, few enough that loading the coverage per job stays a small overhead.
JOBS_PER_WORKER = 4


def _overlap(a0, a1, b0, b1):
    return max(0, min(a1, b1) - max(a0, b0) + 1)


def subtrees(plan, cut):
    """{(x, y): tiles} for the tiles of level ``cut`` above a tile written on levels from ``cut``,
    with the number of tiles each subtree writes."""
    jobs = {}
    for level in plan["levels"]:
        d = level["z"] - cut
        if d < 0:
            continue
        for r in level["available"]:
            for y in range(r["startY"] >> d, (r["endY"] >> d) + 1):
                rows = _overlap(y << d, ((y + 1) << d) - 1, r["startY"], r["endY"])
                for x in range(r["startX"] >> d, (r["endX"] >> d) + 1):
                    cols = _overlap(x << d, ((x + 1) << d) - 1, r["startX"], r["endX"])
                    jobs[(x, y)] = jobs.get((x, y), 0) + rows * cols
    return jobs


def choose_cut(plan, workers):
    """The shallowest level whose subtrees make JOBS_PER_WORKER jobs per worker thread, with
    windows of at most MAX_WINDOW_POSTS posts across; the last level when none does."""
    lattice = plan["lattice"]
    spacing = min(lattice["spacing_deg"])
    small = max(lattice["width"], lattice["height"]) <= MAX_WINDOW_POSTS
    for cut in range(plan["min_zoom"], plan["max_zoom"] + 1):
        across = 180.0 / 2**cut / spacing
        if len(subtrees(plan, cut)) >= JOBS_PER_WORKER * workers and (
                small or across <= MAX_WINDOW_POSTS):
            return cut
    return plan["max_zoom"]


def jobs(plan, cut):
    """[(SPEC, tiles)] of a cut at level ``cut``: the levels above it first (one job, the longest
    on coarse levels), then the subtrees."""
    out = []
    above = sum(level["tiles"] for level in plan["levels"] if level["z"] < cut)
    if cut > plan["min_zoom"]:
        out.append((f"top:{cut}", above))
    for (x, y), tiles in sorted(subtrees(plan, cut).items(), key=lambda j: (j[0][1], j[0][0])):
        out.append((f"{cut}/{x}/{y}", tiles))
    return out
