"""``apart batch`` on a Ray cluster: one task per assembly, lines streamed back.

>>> import apart.ray                                        # doctest: +SKIP
>>> for line in apart.ray.run("assemblies/", command="partition", timeout=300):
...     print(line["assembly"], line["status"])

:func:`run` connects to the cluster Ray finds (``ray.init()``: a running cluster from
``RAY_ADDRESS`` or ``address="auto"``, otherwise a local one it starts); pass
``address="ray://head:10001"`` to point it at another. Every worker must be able to
``import apart`` (install the package on every node, or give ``runtime_env``). Each
task makes the line :func:`apart.batch.answer_line` makes, with the fields of
``apart batch``'s JSON lines; a task that fails (a crashed worker, a lost node) gives a
line with status ``failed`` and the error, never an exception.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Dict, Iterable, Iterator, List, Optional, Tuple, Union

from .batch import answer_line, assemblies_under, key_of

PathLike = Union[str, os.PathLike]


def _targets(paths: Union[PathLike, Iterable[PathLike]]) -> List[Tuple[Path, str]]:
    """(assembly, key) pairs: the assemblies under a folder, keyed relative to it, or the
    given assemblies, keyed by their paths."""
    if isinstance(paths, (str, os.PathLike)):
        root = Path(paths)
        return [(a, key_of(root, a)) for a in assemblies_under(root)]
    return [(Path(p), str(p)) for p in paths]


def run(paths: Union[PathLike, Iterable[PathLike]], command: str = "partition", *,
        address: Optional[str] = None, timeout: Optional[float] = 300.0,
        num_cpus_per_task: float = 1, skip: Iterable[str] = (),
        **load_options: Any) -> Iterator[Dict[str, Any]]:
    """Runs ``command`` on every assembly of ``paths`` (a folder, searched as
    ``apart batch`` searches it, or a list of assemblies), one Ray task each, and yields
    each line as its task finishes. ``timeout`` bounds each assembly (its partial answer,
    status ``timeout``); ``skip`` holds keys already answered (a resumed run);
    ``load_options`` are :func:`apart.load`'s. Starts or joins a cluster with
    ``ray.init(address=address)`` unless Ray is already initialised."""
    import ray  # an optional dependency: only this module needs it

    if not ray.is_initialized():
        ray.init(address=address, ignore_reinit_error=True, log_to_driver=False)
    task = ray.remote(num_cpus=num_cpus_per_task, max_retries=0)(answer_line)
    done_before = set(skip)
    pending: Dict[Any, str] = {}
    for path, key in _targets(paths):
        if key in done_before:
            continue
        ref = task.remote(str(path), command, key, timeout, **load_options)
        pending[ref] = key
    while pending:
        ready, _ = ray.wait(list(pending), num_returns=1)
        for ref in ready:
            key = pending.pop(ref)
            try:
                yield ray.get(ref)
            except Exception as e:  # a task's failure is recorded, not raised
                yield {"assembly": key, "command": command, "status": "failed",
                       "error": f"{type(e).__name__}: {e}"}
