"""tinlod's terrain tile build spread over a Dask cluster.

``python3 -m tinlod_dask tiles DEM... -o DIR (--scheduler tcp://HOST:PORT | --local N)`` cuts the
pyramid `tinlod tiles` writes into independent jobs (``tinlod tiles --part``), runs them on the
cluster's workers, and writes layer.json at the end: the single-process build's tile set, byte for
byte (docs/scaling.md). Dask is Debian's ``python3-distributed``, in ``/usr/bin/python3``.
"""
