"""Studies that outgrow one machine: integration error, spectrum statistics, discrepancy
statistics and rendered error, split into chunks that run here, on a Dask cluster or on any
``concurrent.futures`` executor (a process pool, say), and merge to the same bits.

A study is a fixed list of chunks, decided by its description alone (never by the cluster).
The library describes every kind (``samplab::study`` and ``samplab_render::study`` in
Rust): its checks, its chunks, the computation of one chunk and the merge in chunk order
into the JSON and CSV the CLI writes; this module schedules the chunks here or on Dask,
keeps checkpoints and plots. Adding a kind is a constructor here.

Every number of a chunk is a function of the study and the chunk alone (realization k is
seeded by ``seed.derive(k)``), and partial results are merged in chunk order whatever order
the workers finish in, so ``study.run()``, ``study.run(client)`` on any cluster or executor,
any resumed run, and the CLI give the same bytes.

A checkpoint directory keeps each finished chunk in its own file, whole or absent, checked
when read back (``samplab::study::Checkpoint``): a file that fails any check is refused with
an error naming it, never used.
"""

from __future__ import annotations

import concurrent.futures
import hashlib
import inspect
import json
import sys
import time
import uuid
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np

from . import _samplab
from ._samplab import Error

__all__ = ["Study", "StudyResult"]

FORMAT = 1


def _canonical(value: Any) -> str:
    return json.dumps(value, sort_keys=True, separators=(",", ":"))


def _plain(value: Any) -> Any:
    """numpy scalars and arrays, and ranges, as JSON (the library reads each argument by its
    type)."""
    if isinstance(value, (np.generic, np.ndarray)):
        return value.tolist()
    if isinstance(value, range):
        return list(value)
    raise Error(f"{value!r}: not a number, a name or a list of them")


def _constructor(kind: str) -> Any:
    """``Study.<kind>(...)``, its parameters, defaults and documentation those the library
    declares for the kind (``samplab_render::study::KINDS``), which also reads the values."""
    info = next(k for k in _samplab.study_kinds() if k["kind"] == kind)
    params, (chunk_name, chunk_default), rest = info["parameters"], info["per_chunk"], info["rest"]
    P = inspect.Parameter
    signature = [P("cls", P.POSITIONAL_ONLY)]
    signature += [P(p["name"], P.POSITIONAL_OR_KEYWORD if p["positional"] else P.KEYWORD_ONLY, default=P.empty if p["default"] is None else json.loads(p["default"])) for p in params]
    signature += [P(chunk_name, P.KEYWORD_ONLY, default=chunk_default)] + ([P(rest, P.VAR_KEYWORD)] if rest else [])

    def make(cls: Any, *args: Any, **kwargs: Any) -> "Study":
        arguments = inspect.Signature(signature).bind(cls, *args, **kwargs).arguments
        del arguments["cls"]
        # the other keywords side by side with the parameters, as STUDY.json gives them
        arguments.update(arguments.pop(rest, {}) if rest else {})
        function = _function(arguments)
        described, chunks, feeds = _samplab.study_plan(json.dumps({"kind": kind, **arguments}, default=_plain))
        params = json.loads(described)
        del params["kind"]
        return cls(kind, params, [list(c) for c in chunks], feeds, function)

    make.__name__ = make.__qualname__ = kind
    make.__doc__ = _numpydoc(info)
    make.__signature__ = inspect.Signature(signature)  # type: ignore[attr-defined]
    return classmethod(make)


#: The Python types of the library's parameter kinds (``samplab_render::study``).
_TYPES = {
    "counts": "int or sequence of int",
    "names": "str or sequence of str",
    "name": "str",
    "name?": "str, optional",
    "float": "float",
    "float?": "float, optional",
    "count": "int",
    "count?": "int, optional",
    "seed": "int, optional",
    "bool": "bool",
}


def _numpydoc(info: Dict[str, Any]) -> str:
    """The library's documentation of a study kind, with a numpy-style Parameters section
    made from its declared parameters (their types and defaults)."""
    lines = [info["doc"].replace("`", "``"), "", "Parameters", "----------"]
    for p in info["parameters"]:
        value = None if p["default"] is None else json.loads(p["default"])
        default = "" if value is None else f", default {value!r}"
        # an integration study's integrand may be a function (``_function`` takes it out)
        of = "str or callable" if p["name"] == "integrand" else _TYPES.get(p["of"], p["of"])
        lines.append(f"{p['name']} : {of}{default}")
    name, default = info["per_chunk"]
    lines += [f"{name} : int, default {default}", "    Units per chunk: aim for chunks of a second or more."]
    if info["rest"]:
        lines += [f"**{info['rest']}", "    Settings passed through to the library, by name."]
    lines += ["", "Returns", "-------", "Study", "    The study's chunks, computed by ``run``."]
    return "\n".join(lines)


def _function(arguments: Dict[str, Any]) -> Any:
    """An integration study's own integrand, taken out of ``arguments`` (which keep its
    name; one function, so one instance unless asked), or None."""
    f, declared = arguments.get("integrand"), [arguments.get("d"), arguments.get("exact")]
    if callable(f) == (declared[0] is None) or (not callable(f) and declared[1] is not None):
        raise Error("a callable integrand needs d= (its dimension; exact= its integral, else computed); a family takes neither")
    if not callable(f):
        return None
    if declared[1] is None:
        from . import reference

        arguments["exact"] = reference(f, declared[0])
    arguments["integrand"] = getattr(f, "__name__", type(f).__name__)
    arguments.setdefault("instances", 1)
    return f


def _identity(f: Any) -> str:
    """What a checkpoint of a study of ``f`` is tied to: its code, constants, defaults and
    captured values (by repr), so that editing the function invalidates its chunks."""
    code, cells = getattr(f, "__code__", None), getattr(f, "__closure__", None) or ()
    parts = repr(f) if code is None else (f.__module__, f.__qualname__, code.co_code, code.co_consts, code.co_names, f.__defaults__, [c.cell_contents for c in cells])
    return hashlib.sha256(repr(parts).encode()).hexdigest()


@dataclass
class Study:
    """A study: what to compute (``kind`` and ``params``) and its chunks. Build one with
    ``Study.integrate``, ``Study.spectrum``, ``Study.discrepancy`` or ``Study.render``."""

    kind: str
    params: Dict[str, Any]
    chunks: List[Any] = field(default_factory=list)
    #: whether chunk 0's result is given to every other chunk (a render study's reference)
    first_feeds_the_rest: bool = False
    #: an integration study's own integrand (a vectorized callable; Dask workers receive it
    #: pickled), or None
    function: Any = None

    integrate = _constructor("integrate")
    spectrum = _constructor("spectrum")
    discrepancy = _constructor("discrepancy")
    render = _constructor("render")

    # ----- identity -----------------------------------------------------------------------

    @property
    def fingerprint(self) -> str:
        """SHA-256 of what the study computes and how it is chunked (and of the package
        version): chunks of one study are never mistaken for another's."""
        from . import __version__

        function = {} if self.function is None else {"function": _identity(self.function)}
        text = _canonical({"format": FORMAT, "version": __version__, "kind": self.kind, "params": self.params, "chunks": self.chunks, **function})
        return hashlib.sha256(text.encode()).hexdigest()

    # ----- running ------------------------------------------------------------------------

    def run(
        self,
        client: Any = None,
        *,
        checkpoint: Optional[str] = None,
        progress: Optional[bool] = None,
        retries: int = 3,
    ) -> "StudyResult":
        """Compute the missing chunks (here, one after the other, each in parallel on the
        Rust core; on the Dask ``client``'s workers; or on ``client`` a
        ``concurrent.futures.Executor``, such as a ``ProcessPoolExecutor``), keep each finished chunk in ``checkpoint`` if given, and merge.
        ``progress``: a progress bar with the time left on stderr (default: when stderr is a
        terminal or in Jupyter). ``retries``: how many times Dask retries a chunk whose task
        failed (chunks of a lost worker are recomputed by the scheduler anyway; an executor
        does not retry). A process pool should start its workers by ``spawn`` or
        ``forkserver``: a fork of a process whose thread pool has started can hang."""
        dask = callable(getattr(client, "scatter", None)) and callable(getattr(client, "submit", None))
        if client is not None and not dask and not isinstance(client, concurrent.futures.Executor):
            raise Error(
                f"client: {client!r} is neither a Dask client nor a concurrent.futures.Executor "
                "(give one, or nothing to run here)"
            )
        start = time.monotonic()
        store = None
        if checkpoint:
            manifest = _canonical({"fingerprint": self.fingerprint, "kind": self.kind, "params": self.params, "chunks": len(self.chunks)})
            store = _samplab.Checkpoint(checkpoint, self.fingerprint, manifest)
        results: Dict[int, bytes] = dict(store.load(len(self.chunks))) if store else {}
        reused = len(results)
        todo = [i for i in range(len(self.chunks)) if i not in results]
        bar = _Bar(len(self.chunks), reused, progress)
        computed = 0

        def done(i: int, data: bytes) -> None:
            nonlocal computed
            results[i] = data
            computed += 1
            if store:
                store.save(i, data)
            bar.update(1)

        try:
            if client is None:
                self._run_here(todo, results, done)
            elif dask:
                self._run_dask(client, todo, results, done, retries)
            else:
                self._run_executor(client, todo, results, done)
        finally:
            bar.close()
        data, text, table = _merge(self.kind, self.params, [results[i] for i in range(len(self.chunks))])
        return StudyResult(self.kind, self.params, data, computed, reused, time.monotonic() - start, text, table)

    def _run_here(self, todo: List[int], results: Dict[int, bytes], done: Any) -> None:
        dependency = self._dependency(results, lambda i: _compute(self.kind, self.params, self.chunks[i]), done)
        for i in todo:
            if i in results:
                continue
            done(i, _compute(self.kind, self.params, self.chunks[i], dependency, self.function))

    def _dependency(self, results: Dict[int, bytes], compute: Any, done: Any) -> Optional[bytes]:
        """Chunk 0's result where it feeds the others, computed first when missing."""
        if not self.first_feeds_the_rest:
            return None
        if 0 not in results:
            done(0, compute(0))
        return results[0]

    def _run_dask(self, client: Any, todo: List[int], results: Dict[int, bytes], done: Any, retries: int) -> None:
        from distributed import as_completed

        # a key per run: a finished run's results may linger on the scheduler, and a new run
        # must compute (or a benchmark would time a cache)
        fp = f"{self.fingerprint[:12]}-{uuid.uuid4().hex[:8]}"

        def submit(i: int, dependency: Any = None) -> Any:
            return client.submit(_compute, self.kind, self.params, self.chunks[i], dependency, self.function, key=f"samplab-{fp}-{i}", retries=retries)

        dependency = self._dependency(results, lambda i: submit(i).result(), done)
        if dependency is not None:
            dependency = client.scatter(dependency, broadcast=True)
        futures = {submit(i, dependency): i for i in todo if i not in results}
        for future in as_completed(list(futures)):
            done(futures[future], future.result())


    def _run_executor(self, executor: Any, todo: List[int], results: Dict[int, bytes], done: Any) -> None:
        def submit(i: int, dependency: Optional[bytes] = None) -> Any:
            return executor.submit(_compute, self.kind, self.params, self.chunks[i], dependency, self.function)

        dependency = self._dependency(results, lambda i: submit(i).result(), done)
        futures = {submit(i, dependency): i for i in todo if i not in results}
        try:
            for future in concurrent.futures.as_completed(futures):
                done(futures[future], future.result())
        finally:
            # a failed or stopped run leaves no chunk computing behind it
            for future in futures:
                future.cancel()


def _compute(kind: str, params: Dict[str, Any], chunk: Any, dependency: Optional[bytes] = None, function: Any = None) -> bytes:
    """One chunk's partial result, as bytes (what workers run and checkpoints keep)."""
    return bytes(_samplab.study_chunk(_canonical({"kind": kind, **params}), list(chunk), dependency, function))


def _merge(kind: str, params: Dict[str, Any], parts: List[bytes]) -> tuple:
    """Every chunk's result, in chunk order, into the study's result: (data, JSON, CSV)."""
    text, table, statistics = _samplab.study_merge(_canonical({"kind": kind, **params}), parts)
    return (json.loads(text) if statistics is None else statistics), text, table


@dataclass
class StudyResult:
    """A study's result: ``data`` (dicts and arrays, the CLI's JSON structure), how many
    chunks this run ``computed`` and ``reused`` from the checkpoint, and its wall time."""

    kind: str
    params: Dict[str, Any]
    data: Dict[str, Any]
    computed: int
    reused: int
    seconds: float
    text: str = field(repr=False, default="")
    table: str = field(repr=False, default="")

    def to_json(self, path: Optional[str] = None) -> str:
        """The result as the CLI writes it: ``samplab integrate --json``, ``samplab
        discrepancy --json``, the ``statistics`` of ``spectrum.json``; per-seed errors and
        their summary for renders."""
        if path:
            _samplab.write_file(path, self.text.encode())
        return self.text

    def to_csv(self, path: Optional[str] = None) -> str:
        """One row per result line: integration rows, per-metric summaries, per-seed
        errors, or ``radial.csv`` of the spectra (numbers as the CLI prints them)."""
        if path:
            _samplab.write_file(path, self.table.encode())
        return self.table

    def plot(self, ax: Any = None) -> Any:
        """A matplotlib plot like the report's: relative variance against N (log-log),
        radial spectra, discrepancy histograms or error per seed. Returns the axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(7, 4.5))
        if self.kind == "integrate":
            fits = {f["sampler"]: f["exponent"] for f in self.data["fits"]}
            for s in dict.fromkeys(r["sampler"] for r in self.data["rows"]):
                rows = [r for r in self.data["rows"] if r["sampler"] == s]
                label = s + (f" (slope {fits[s]:.2f})" if s in fits else "")
                ax.loglog([r["n"] for r in rows], [r["relative_variance"] for r in rows], marker="o", label=label)
            ax.set(xlabel="N", ylabel="relative variance", title=self.params["integrand"])
        elif self.kind == "spectrum":
            for name in ("periodogram", "expected", "variance"):
                radial = np.asarray(self.data[f"{name}_radial"])
                ax.semilogy(np.arange(1, len(radial) + 1), radial, label=name)
            ax.set(xlabel="radial frequency", ylabel="statistic", title=self.params["sampler"])
        elif self.kind == "discrepancy":
            for r in self.data["metrics"]:
                ax.hist(r["values"], bins=30, alpha=0.6, label=r["metric"])
            ax.set(xlabel="discrepancy", ylabel="sets", title=self.params["sampler"])
        else:
            key = "rmse" if "rmse" in self.data["errors"][0] else next(iter(self.data["errors"][0]))
            ax.plot(self.data["seeds"], [e[key] for e in self.data["errors"]], marker="o", label=key)
            ax.set(xlabel="seed", ylabel=key, title=self.params["scene"])
        ax.legend()
        return ax


class _Bar:
    """A progress bar with the time left, on stderr: chunks done of the total."""

    def __init__(self, total: int, done: int, show: Optional[bool]):
        if show is None:
            show = sys.stderr.isatty() or "ipykernel" in sys.modules
        self.show, self.total, self.done, self.start_done = show, total, done, done
        self.start = time.monotonic()
        self._draw()

    def update(self, k: int) -> None:
        self.done += k
        self._draw()

    def _draw(self) -> None:
        if not self.show:
            return
        elapsed = time.monotonic() - self.start
        fresh = self.done - self.start_done
        left = elapsed / fresh * (self.total - self.done) if fresh else float("nan")
        width = 30
        filled = width * self.done // max(self.total, 1)
        eta = "?" if left != left else f"{left:.0f} s"
        sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} chunks, {elapsed:.0f} s, {eta} left ")
        sys.stderr.flush()

    def close(self) -> None:
        if self.show:
            sys.stderr.write("\n")
            sys.stderr.flush()
