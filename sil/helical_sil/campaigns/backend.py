"""Where a campaign's runs execute: this machine's processes (`local`, the
default) or a Ray cluster (`ray`: an optional extra, `pip install
'helical-sil[ray]'`; with `--address` an existing cluster, without it a
local Ray started for the campaign and stopped after it).

Every run is a pure function of its inputs (the scenario file fixes the seed,
the board library is the same code), so the backends give bit-identical
results; only the order of completion differs, and the results come back in
the order of the inputs either way.
"""

from __future__ import annotations

from typing import Any, Callable, Sequence, TypeVar

T = TypeVar("T")
R = TypeVar("R")

BACKENDS = ("local", "ray")


class BackendError(RuntimeError):
    """The backend cannot run (Ray not installed, the cluster not reachable)."""


def _ray() -> Any:
    try:
        import ray
    except ImportError:
        raise BackendError("--backend ray needs Ray: pip install 'helical-sil[ray]' "
                           "(or sil/requirements-ray.lock)") from None
    return ray


def _reachable(address: str, timeout_s: float = 5.0) -> None:
    """A cluster address is a host:port that answers: checked first, since
    Ray itself retries an unreachable cluster for minutes."""
    import socket
    hostport = address.split("://", 1)[-1]
    host, _, port = hostport.rpartition(":")
    if not host or not port.isdigit():
        raise BackendError(f"--address {address!r}: expected host:port or ray://host:port")
    try:
        with socket.create_connection((host, int(port)), timeout=timeout_s):
            pass
    except OSError as e:
        raise BackendError(f"Ray did not start ({address}): cannot reach {hostport}: "
                           f"{e.strerror or e}") from None


def map_ordered(fn: Callable[[T], R], items: Sequence[T], *, jobs: int = 1,
                backend: str = "local", address: str | None = None,
                progress: Callable[[int, R], None] | None = None) -> list[R]:
    """fn over items, results in the items' order. progress(k, result) is
    called as each one completes (k: how many have). jobs: processes of the
    local pool, or CPUs of a local Ray (ignored with an address)."""
    if backend not in BACKENDS:
        raise BackendError(f"unknown backend {backend!r} (known: {', '.join(BACKENDS)})")
    if jobs < 1:
        raise BackendError("jobs must be at least 1")
    n = len(items)
    out: list[Any] = [None] * n
    if backend == "local":
        if jobs == 1 or n <= 1:
            for k, x in enumerate(items):
                out[k] = fn(x)
                if progress is not None:
                    progress(k + 1, out[k])
            return out
        from concurrent.futures import ProcessPoolExecutor, as_completed
        with ProcessPoolExecutor(max_workers=jobs) as ex:
            futs = {ex.submit(fn, x): k for k, x in enumerate(items)}
            for done, f in enumerate(as_completed(futs), 1):
                out[futs[f]] = f.result()
                if progress is not None:
                    progress(done, out[futs[f]])
        return out
    ray = _ray()
    started = not ray.is_initialized()
    if started:
        if address:
            _reachable(address)
        try:
            if address:
                ray.init(address=address, log_to_driver=False)
            else:
                ray.init(num_cpus=jobs, include_dashboard=False, log_to_driver=False)
        except Exception as e:  # a cluster that is not there, a port in use
            raise BackendError(f"Ray did not start ({address or 'local'}): {e}") from None
    try:
        remote = ray.remote(fn)
        refs = [remote.remote(x) for x in items]
        index = {r: k for k, r in enumerate(refs)}
        pending = list(refs)
        done = 0
        while pending:
            ready, pending = ray.wait(pending, num_returns=1)
            for r in ready:
                k = index[r]
                out[k] = ray.get(r)
                done += 1
                if progress is not None:
                    progress(done, out[k])
        return out
    finally:
        if started:
            ray.shutdown()
