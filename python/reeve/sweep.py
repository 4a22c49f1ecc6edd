"""reeve.sweep: one simulation per parameter set, spread over Dask workers.

Parameter studies (the bench's speed/accuracy trade, a gear ratio against
load, a user's own grid) are embarrassingly parallel: each set loads its
own scene, changes it, steps it and measures it, with nothing shared. Dask's
distributed scheduler (Debian: python3-distributed) runs them on a
LocalCluster of this machine by default, or on any cluster whose scheduler
address is given.
"""


def _one(scene, parameters, measure):
    # Runs on a worker: everything it needs arrives pickled.
    from . import load

    return measure(load(scene(parameters) if callable(scene) else scene), parameters)


def sweep(scene, parameters, measure, client=None, workers=None):
    """Runs measure(reeve.load(scene), p) for each p in `parameters`, in parallel, and returns the results in order.

    scene: what reeve.load() takes (a path, JSON text or a dict), or a
    function p -> one of those (to vary what a scene file fixes, such as a
    mass); each run loads it afresh on its worker, so runs share no state. parameters: a
    list of parameter sets (anything picklable: dicts, tuples, numbers).
    measure: a function (scene, p) -> result that sets the scene up for p
    (settings, state, drive targets), steps it and returns what it measured
    (picklable); define it at module level so that workers can import it.
    client: a dask.distributed.Client, or a scheduler address such as
    "tcp://10.0.0.5:8786"; None starts a LocalCluster of `workers` worker
    processes (default: one per core) with one thread each, and closes it
    afterwards.

    The results equal the serial [measure(reeve.load(scene), p) for p in
    parameters] bit for bit on the same build and machine (Reeve is
    deterministic). An exception in a run is raised here.
    """
    from dask.distributed import Client, LocalCluster

    parameters = list(parameters)
    own = None
    if client is None:
        own = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=":0")  # a free port: sweeps may run side by side
        client = Client(own)
    elif isinstance(client, str):
        client = Client(client)
        own = client
    try:
        futures = client.map(_one, [scene] * len(parameters), parameters, [measure] * len(parameters), pure=False)
        return client.gather(futures)
    finally:
        if own is not None:
            if isinstance(own, Client):
                own.close()
            else:
                client.close()
                own.close()
