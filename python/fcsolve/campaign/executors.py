"""Where the runs execute: a local pool (default) or a Dask distributed cluster.

An executor takes tasks (tasks.Task) and yields their CSV rows as they
finish, in any order. Each run is a separate solver process either way, so
the local pool is a pool of threads that each wait on one process.
"""
import concurrent.futures
import dataclasses
import os

from . import tasks as _tasks


class LocalExecutor:
    """Runs `jobs` solver processes at a time on this machine."""

    def __init__(self, jobs=None):
        self.jobs = max(1, int(jobs or os.cpu_count() or 1))

    def describe(self):
        return f"local, {self.jobs} job{'s' if self.jobs > 1 else ''}"

    def run(self, task_list):
        _tasks.allow_runs()
        pool = concurrent.futures.ThreadPoolExecutor(max_workers=self.jobs)
        try:
            futures = [pool.submit(_tasks.run_task, t) for t in task_list]
            for fut in concurrent.futures.as_completed(futures):
                yield fut.result()
        finally:  # Ctrl-C or an error: stop queued runs, kill running ones
            pool.shutdown(wait=False, cancel_futures=True)
            _tasks.kill_all()
            pool.shutdown(wait=True)
            _tasks.allow_runs()

    def close(self):
        pass


class DaskExecutor:
    """Sends the runs to a Dask distributed scheduler.

    The workers must see the same paths as this machine: the fcsolve binary
    (or peer runner), the problem files, the output folder and this package
    (shared file system). They need numpy, scipy and h5py, not fcsolve: the
    task function travels by value (bootstrap.py) and imports the campaign
    from its folder there.
    """

    def __init__(self, address, client=None):
        try:
            import cloudpickle
            import distributed
        except ImportError as e:
            raise RuntimeError("--dask needs Dask distributed (Debian: apt-get install "
                               "python3-dask python3-distributed)") from e
        from . import bootstrap

        cloudpickle.register_pickle_by_value(bootstrap)
        self._bootstrap = bootstrap
        self._distributed = distributed
        self.address = address
        self.client = client or distributed.Client(address, timeout=30)
        self._own_client = client is None

    def describe(self):
        workers = self.client.scheduler_info().get("workers", {})
        threads = sum(w.get("nthreads", 0) for w in workers.values())
        return f"dask {self.address}, {len(workers)} workers, {threads} threads"

    def run(self, task_list):
        campaign_dir = os.path.dirname(os.path.abspath(__file__))
        futures = [self.client.submit(self._bootstrap.run_task_dict, campaign_dir,
                                      dataclasses.asdict(t), pure=False)
                   for t in task_list]
        try:
            for fut in self._distributed.as_completed(futures):
                yield fut.result()
        finally:
            self.client.cancel(futures)

    def close(self):
        if self._own_client:
            self.client.close()


def make_executor(jobs=None, dask=None):
    return DaskExecutor(dask) if dask else LocalExecutor(jobs)
