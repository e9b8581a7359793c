"""Typed numba compilation decorators shared by every kernel module (private).

Under ``mypy --strict`` a function decorated with ``numba.njit`` directly is
typed only as far as the installed numba's annotations go (older releases
have none: "Untyped decorator makes function untyped"). These decorators are
``njit`` with navkit's options, cast to keep the decorated function's
signature whatever numba is installed; kernel modules use them instead of
``numba.njit``:

* :data:`njit_cached`: ``njit(cache=True)``;
* :data:`njit_inline`: ``njit(cache=True, inline="always")``, inlined into its
  callers at numba IR level;
* :data:`njit_no_refcount`: :data:`njit_cached` without numba's reference
  counting, for kernels that allocate nothing;
* :data:`njit_helper`: :data:`njit_no_refcount` without a Python wrapper, for
  helpers called only from other kernels;
* :data:`njit_force_inline`: a helper compiled once and inlined by LLVM;
* :data:`njit_released` / :data:`njit_cached_released`: :data:`njit_no_refcount`
  and :data:`njit_cached` for the long kernels, which release the GIL while
  they run (:data:`RELEASES_GIL`);
* :func:`typed_njit`: any other options (``typed_njit(cache=True, fastmath=...)``).

None of them builds a cfunc wrapper (``no_cfunc_wrapper=True``): navkit never
passes a kernel as a first-class function value, and every wrapper is compiled
and optimised with its kernel on first use.

A kernel without a Python wrapper (``no_cpython_wrapper=True``: the helpers,
called only from other kernels) is compiled into a lean code library
(:func:`helper_compiler`): numba links a helper's LLVM IR into every kernel
calling it and optimises and translates it to machine code there, so the
helper's own module-level optimisation and machine code were never used
(issue 17: about a tenth of a grid planner's first use; see the function).

numba is imported on first use, not with navkit (issue 17: importing numba
costs about 0.3 s, most of ``import navkit.planning``). A module-level
function decorated before then becomes a :class:`LazyKernel`, a stand-in that
remembers the function and its options. The first call of any stand-in (or
any attribute it does not have, or :func:`load_numba`) imports numba, makes
every waiting function a numba dispatcher and puts the dispatchers in place
of the stand-ins in every loaded module's namespace, so that kernels see each
other as dispatchers when numba types them and Python calls them without the
stand-in's extra call. Functions decorated after that (and closures, which
are made at run time) get a dispatcher straight away. Names a kernel module
needs from numba itself are bound in its namespace at the same moment by
:func:`bind_numba_names`. Loading numba also installs
:mod:`navkit._shared.compile_gc`, which pauses Python's garbage collector
while numba compiles a navkit kernel (about a tenth of the compile time) and
switches on :mod:`navkit._shared.compile_shortcuts` meanwhile (cheaper numba
internals: error-message markup, compile-flag comparisons; tenths of a second).
numba's probe for a BLAS, which imports all of SciPy's linear algebra as numba
initialises its compiler, waits until numba reads its answer
(:func:`_blas_probe_deferred`: a quarter of numba's loading, review 51).

Where numba finds no writable folder for its on-disk cache (a read-only
installation whose ``__pycache__`` and user cache folder cannot be written,
and no ``NUMBA_CACHE_DIR``), numba refuses to make a ``cache=True`` dispatcher
at all ("cannot cache function ..."). navkit then makes its kernels without
the cache, so they work but compile again in every process, and warns once
(:class:`KernelCacheWarning`) naming ``NUMBA_CACHE_DIR``; :func:`cache_problem`
says why.
"""

from __future__ import annotations

import _thread
import importlib
import os
import sys
import threading
import warnings
import weakref
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from types import FrameType
from typing import Any, TypeVar, cast

from navkit._shared.locks import ForkSafeLock
from navkit.errors import KernelCacheWarning

_F = TypeVar("_F", bound=Callable[..., Any])

# Made anew in a forked child (review 37): held by another thread when the
# process forked (a kernel module decorating its kernels, binding numba's
# names), the child's copy stayed held by a thread it does not have, and its
# next kernel module import or decorated function waited for ever.
_LOCK = ForkSafeLock(reentrant=True)
#: numba.njit once numba is loaded.
_NJIT: Any = None
#: Stand-ins made before numba was loaded, and their dispatchers once it is.
_WAITING: list[LazyKernel] = []
#: (namespace, numba module, {name: attribute}) bound by :func:`load_numba`.
_BINDINGS: list[tuple[dict[str, Any], str, dict[str, str], dict[str, Any]]] = []
#: Why numba cannot cache navkit's kernels in this process (empty: it can, so far).
_CACHE_PROBLEM: list[str] = []


def _user_stacklevel() -> int:
    """The ``stacklevel`` at which ``warnings.warn``, called by our caller, names the user.

    That is the first frame outside navkit and numba (a navkit kernel may be
    made while numba compiles a user's kernel that calls it): users filter
    warnings by module and read their location. ``warnings`` steps over
    importlib's bootstrap frames without counting them (a kernel made while a
    navkit module is imported), so they are not counted here either. Python
    3.12's ``skip_file_prefixes`` would do this, but navkit supports older
    Pythons; the walk runs once per process.
    """

    def ours(frame: FrameType) -> bool:
        # By module name, not file: a file's path may be spelt another way (symlinks).
        module = frame.f_globals.get("__name__")
        # importlib's public functions (import_module) are counted by warnings
        # but are not the user's line either: walk through them.
        return isinstance(module, str) and module.partition(".")[0] in (
            "navkit",
            "numba",
            "importlib",
        )

    def internal(frame: FrameType) -> bool:
        # What warnings takes for import machinery: never counted in a stacklevel.
        filename = frame.f_code.co_filename
        return "importlib" in filename and "_bootstrap" in filename

    frame = sys._getframe(1)  # warn's caller: stacklevel 1
    level = 1
    while ours(frame):
        outer = frame.f_back
        while outer is not None and internal(outer):
            outer = outer.f_back
        if outer is None:  # navkit all the way down: its outermost frame
            break
        frame, level = outer, level + 1
    return level


def _make_dispatcher(njit: Any, options: dict[str, Any], py_func: Callable[..., Any]) -> Any:
    """``njit(**options)(py_func)``, without numba's cache where it has nowhere to write it.

    A helper (``no_cpython_wrapper``) is compiled by :func:`helper_compiler`.
    """
    if options.get("no_cpython_wrapper") and "pipeline_class" not in options:
        compiler = helper_compiler()
        if compiler is not None:
            options = {**options, "pipeline_class": compiler}
    try:
        return _count_compiles_in_c(njit(**options)(py_func))
    except RuntimeError as exc:
        # numba's words when no cache locator has a writable folder for the file.
        if not options.get("cache") or "cannot cache function" not in str(exc):
            raise
    if not _CACHE_PROBLEM:
        source = getattr(getattr(py_func, "__code__", None), "co_filename", py_func.__module__)
        if os.path.exists(source):
            why = "its __pycache__ and the user cache folder are read-only"
            fix = "Set NUMBA_CACHE_DIR to a writable folder"
        elif getattr(sys, "frozen", False):
            # A frozen application without its source files: numba then ignores
            # NUMBA_CACHE_DIR and caches in the user cache folder alone.
            why = "the source file is not there, so numba uses only the user cache folder"
            fix = f"Make {numba_user_cache_folder()} writable"
        else:  # numba caches only functions whose source file it finds
            why = "the source file is not there: numba caches only functions it can find"
            fix = "Install navkit with its .py files"
        problem = (
            f"numba cannot cache navkit's compiled kernels: no writable cache folder for "
            f"{source} ({why}), so every process compiles them again on first use (seconds). "
            f"{fix} (see navkit's docs/compilation.md)"
        )
        _CACHE_PROBLEM.append(problem)
        warnings.warn(problem, KernelCacheWarning, stacklevel=_user_stacklevel())
    return _count_compiles_in_c(njit(**{**options, "cache": False})(py_func))


#: Every :class:`_CompileDepth` made, weakly (see :func:`_free_lost_compile_depths`).
_DEPTHS: weakref.WeakSet[_CompileDepth] = weakref.WeakSet()


class _CompileDepth:
    """A dispatcher's count of its compiles under way, which a Ctrl-C cannot leave up.

    numba counts them in a ``CompilingCounter`` (``with dispatcher._compiling_counter:``
    around every compile and cache load), whose ``__exit__`` is Python code:
    CPython runs a pending signal handler as a Python function is entered, so a
    Ctrl-C arriving there raised ``KeyboardInterrupt`` before the count went
    down, and the dispatcher counted as compiling for the rest of the process.
    numba then took every later call to it from a kernel being compiled for
    recursion: each compile of a kernel calling that helper failed for good
    (review 38: A*'s first call interrupted there, every later one raised
    "NotImplementedError: call to CPUDispatcher(<function rec_sift_up>):
    unsupported recursion"). Here the count is a re-entrant C lock's: ``with``
    looks both methods up (this class's properties, Python, before anything is
    counted) and calls them, the lock's own C ``__enter__`` and ``__exit__``, with
    no Python code in between in which a signal's handler could run. numba holds
    its compiler lock around every compile, so one thread at a time counts, and
    the count is true for the thread reading it (numba's type inference, in the
    compiling thread). In a forked child, the counts of the threads the fork
    left behind are freed (:func:`_free_lost_compile_depths`).
    """

    __slots__ = ("__weakref__", "_lock")

    def __init__(self) -> None:
        # C: its __enter__ and __exit__ run no Python. Any: _is_owned is untyped.
        self._lock: Any = _thread.RLock()
        _DEPTHS.add(self)

    __enter__: Any
    __exit__: Any

    def __bool__(self) -> bool:
        return bool(self._lock._is_owned())

    @property
    def counter(self) -> int:
        """numba's name: how deep this thread's compiles of the dispatcher are (0 or more)."""
        text = repr(self._lock)
        if not self:
            return 0
        count = text.partition("count=")[2].split(" ", 1)[0]
        return int(count) if count.isdigit() else 1


class _LockMethod:
    """:class:`_CompileDepth`'s ``__enter__`` or ``__exit__``: its C lock's own, bound.

    ``with`` looks it up on the class and binds it (this ``__get__``, Python code
    run before the block, where an interrupt changes nothing), then calls the C
    method. Looked up on the class itself (``contextlib.ExitStack.enter_context``),
    it is a function of the instance, as a method would be.
    """

    __slots__ = ("name",)

    def __init__(self, name: str) -> None:
        self.name = name

    def __get__(self, depth: Any, owner: Any = None) -> Any:
        if depth is None:
            name = self.name
            return lambda depth, *args: getattr(depth._lock, name)(*args)
        return getattr(depth._lock, self.name)


_CompileDepth.__enter__ = _LockMethod("__enter__")
_CompileDepth.__exit__ = _LockMethod("__exit__")


def _free_lost_compile_depths() -> None:
    """In a forked child, free the compile counts held by threads the fork left behind.

    A fork waits for numba's compiler lock, under which every count goes up
    and down, except one made from a signal handler run inside navkit's
    locking code, which goes without it (``compile_gc._take_for_fork``): a
    thread compiling a kernel then held the kernel's :class:`_CompileDepth`,
    a C lock, and the child's first call of that kernel waited for it for
    ever (review 39; numba's own counter, an int, let the child compile).
    The forking thread's own counts are kept: it goes on with its compiles.
    So are the counts no thread holds: a ``with`` may have bound one's
    ``__enter__`` already, the fork made by a signal's handler run as it looked
    up ``__exit__`` (Python: ``_LockMethod.__get__``); replaced, the child
    entered the old lock, counted 0 through the compile and raised "cannot
    release un-acquired lock" at its end (review 39).
    """
    for depth in list(_DEPTHS):
        lock = depth._lock
        if lock.acquire(False):  # free, or the forking thread's own (re-entrant)
            lock.release()
        else:  # held by a thread the fork left behind
            depth._lock = _thread.RLock()


if hasattr(os, "register_at_fork"):  # not on Windows, which cannot fork
    os.register_at_fork(after_in_child=_free_lost_compile_depths)


def _count_compiles_in_c(dispatcher: Any) -> Any:
    """``dispatcher`` with a :class:`_CompileDepth` in place of numba's compile counter."""
    if hasattr(dispatcher, "_compiling_counter"):  # numba's, since 0.2x
        dispatcher._compiling_counter = _CompileDepth()
    return dispatcher


#: Whether helpers are compiled by :func:`helper_compiler` (read as each kernel is made).
LEAN_HELPERS = True
#: The helper compiler class, once made ([] before; [None] where numba lacks what it needs).
_HELPER_COMPILER: list[Any] = []


def helper_compiler() -> Any:
    """numba's compiler for a helper kernel, with a code library that makes no machine code.

    numba compiles each kernel into a code library of its own, and a kernel
    calling another links a copy of the callee's LLVM IR into its library,
    where the whole is optimised (LLVM's full module pipeline) and translated
    to machine code once more. For a helper, which has no Python wrapper and
    is called only from other kernels, its own library's module optimisation
    and machine code were thus work no caller used: 10-14 % of the first use
    of A*, jump point search, ``MapPlanner`` and Field D* (3.67 -> 3.19 s CPU,
    medians of 7 alternating runs) and about 6 % of the whole library's
    (``navkit warmup``: 28.0 -> 26.4 s, medians of 5, single runs spread by
    +-3 s on a busy machine). The library
    made here skips both: its IR, optimised function by function as numba
    does before linking, is what callers link, and each caller optimises it
    in its own module (as it already did with the optimised copy).

    The callers' results are unchanged bit for bit (the same operations, no
    fast-math), but their machine code differs slightly from that built with
    numba's own libraries (callers copied a helper's module after LLVM's code
    generation had rewritten it in place). Hot loops ran as fast within the
    noise of alternating benchmark runs (A* with and without corner cutting
    and fresh Field D* plans on the 1024² benchmark maps: ratios to pyastar2d
    and to navkit's A* within 0.97-1.03 of numba's own libraries).

    numba's cache keeps such a helper as LLVM bitcode (its documented
    ``bitcode`` serialisation) instead of object code plus bitcode: a later
    process that compiles a new caller loads and links it as before. Nothing
    writes the helper's environment pointer, which only its own machine code
    would read. Returns None (numba's own compiler is used) if
    :data:`LEAN_HELPERS` is False or the installed numba lacks a method this
    relies on.

    Examples
    --------
    >>> from navkit._shared.jit import helper_compiler
    >>> helper_compiler().__name__
    'HelperCompiler'
    """
    if not LEAN_HELPERS:
        return None
    with _LOCK:
        if not _HELPER_COMPILER:
            _HELPER_COMPILER.append(_make_helper_compiler())
        return _HELPER_COMPILER[0]


def _make_helper_compiler() -> Any:
    """The class :func:`helper_compiler` returns, or None where numba lacks what it needs."""
    from numba.core import codegen, compiler

    # Any: numba is untyped in some supported versions.
    library_class: Any = getattr(codegen, "JITCodeLibrary", None)
    base_compiler: Any = getattr(compiler, "Compiler", None)
    needed = (
        "_finalize_final_module", "_finalize_dynamic_globals", "_verify_declare_only_symbols",
        "_optimize_final_module", "serialize_using_object_code", "serialize_using_bitcode",
        "enable_object_caching",
    )  # fmt: skip
    if (
        library_class is None
        or base_compiler is None
        or not all(hasattr(library_class, name) for name in needed)
        or not hasattr(base_compiler, "compile_extra")
    ):
        return None

    class _NoEnvironment:
        """A helper library's codegen as numba's lowering sees it: no environment to write."""

        def __init__(self, inner: Any) -> None:
            self._inner = inner

        def set_env(self, env_name: str, env: Any) -> None:
            """Nothing: the environment's slot is in the helper's machine code, never made."""

        def __getattr__(self, name: str) -> Any:
            return getattr(self._inner, name)

    class HelperLibrary(library_class):  # type: ignore[misc]  # (a class of Any)
        """A helper's code library: IR for callers to link, no machine code of its own."""

        @property
        def codegen(self) -> Any:
            # numba's lowering writes the kernel's environment pointer into its
            # machine code through this; there is none to write into.
            return _NoEnvironment(self._codegen)

        def _optimize_final_module(self) -> None:
            """Nothing: every caller optimises the linked copy in its own module."""

        def _finalize_final_module(self) -> None:
            # numba's checks, without handing the module to the JIT engine
            # (which would translate it to machine code).
            self._finalize_dynamic_globals()
            if self._dynamic_globals:
                # numba finds these after its module optimisation, which drops
                # the ones only dead code used (an exception's class address):
                # optimised as numba does, the helper is cached where numba's
                # own library would be (numba caches no kernel using one).
                self._dynamic_globals.clear()
                library_class._optimize_final_module(self)
                self._finalize_dynamic_globals()
            self._verify_declare_only_symbols()
            self._finalized = True

        def serialize_using_object_code(self) -> Any:
            # There is no object code: the cache keeps the bitcode, which
            # numba reloads and links as it does object code's bitcode.
            return self.serialize_using_bitcode()

    class HelperCompiler(base_compiler):  # type: ignore[misc]
        """numba's compiler, with a :class:`HelperLibrary` for the kernel's code."""

        def compile_extra(self, func: Any) -> Any:
            state = self.state
            if state.library is None:  # what numba's lowering would otherwise make
                library = HelperLibrary(state.targetctx.codegen(), func.__qualname__)
                library.enable_object_caching()
                state.library = library
            return super().compile_extra(func)

    return HelperCompiler


def numba_user_cache_folder() -> str:
    """numba's user-wide cache folder, where it caches what it cannot beside the sources.

    ``~/.cache/numba`` on Linux (under ``XDG_CACHE_HOME`` if set),
    ``~/Library/Caches/numba`` on macOS, ``%LOCALAPPDATA%\\numba\\Cache`` on
    Windows: what numba's ``_UserWideCacheLocator`` asks its ``appdirs`` for.
    """
    try:
        from numba.misc import appdirs

        dirs: Any = appdirs.AppDirs
        return str(dirs(appname="numba", appauthor=False).user_cache_dir)
    except (ImportError, AttributeError):  # pragma: no cover - numba moved it
        base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
        return os.path.join(base, "numba")


def jit_disabled() -> bool:
    """Whether numba's JIT is disabled (``NUMBA_DISABLE_JIT=1``): kernels run as Python."""
    if "numba.core.config" not in sys.modules:
        from navkit._shared import compile_gc
        from navkit._shared.interrupts import interrupts_deferred

        # This may import numba (``navkit warmup`` asks before loading it): a
        # Ctrl-C cutting that import short would break numba as in load_numba,
        # and a fork meanwhile waits for it (compile_gc.NUMBA_IMPORT).
        with compile_gc.NUMBA_IMPORT, interrupts_deferred():
            importlib.import_module("numba.core.config")
    config: Any = importlib.import_module("numba.core.config")
    return bool(config.DISABLE_JIT)


def cache_warned() -> bool:
    """Whether this process has already warned that numba cannot cache navkit's kernels.

    Unlike :func:`cache_problem`, this does not load numba: a process that has
    made no kernel yet has not warned.
    """
    return bool(_CACHE_PROBLEM)


def cache_problem() -> str | None:
    """Why numba cannot cache navkit's kernels in this process, or None if it can.

    Loads numba (and makes every waiting kernel's dispatcher) first.
    """
    load_numba()
    return _CACHE_PROBLEM[0] if _CACHE_PROBLEM else None


class LazyKernel:
    """A kernel whose numba dispatcher is made when numba is first needed.

    Calls and attribute lookups go to the dispatcher (loading numba on the
    first); navkit's modules hold the dispatcher itself once numba is loaded.

    Parameters
    ----------
    py_func : callable
        The Python function to compile.
    options : dict
        The ``numba.njit`` options.

    Examples
    --------
    >>> from navkit._shared.jit import LazyKernel
    >>> def twice(x):
    ...     return 2 * x
    >>> LazyKernel(twice, {"cache": False})(3)
    6
    """

    def __init__(self, py_func: Callable[..., Any], options: dict[str, Any]) -> None:
        self.py_func = py_func
        self.options = options
        self.dispatcher: Any = None
        self.__wrapped__ = py_func
        self.__name__ = py_func.__name__
        self.__qualname__ = py_func.__qualname__
        self.__module__ = py_func.__module__
        self.__doc__ = py_func.__doc__

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        dispatcher = self.dispatcher
        if dispatcher is None:
            dispatcher = self._load()
        return dispatcher(*args, **kwargs)

    def __getattr__(self, name: str) -> Any:
        # Only attributes the stand-in lacks (a dispatcher's signatures, compile, ...).
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self._load(), name)

    def __repr__(self) -> str:
        return f"<navkit kernel {self.__module__}.{self.__qualname__}>"

    def _load(self) -> Any:
        """This kernel's dispatcher, made (with every waiting one) on first need."""
        if self.dispatcher is None:
            load_numba()
            with _LOCK:  # one dispatcher, whichever threads get here at once
                if self.dispatcher is None:  # made by hand after numba was loaded
                    self.dispatcher = _make_dispatcher(_NJIT, self.options, self.py_func)
        return self.dispatcher


def numba_loaded() -> bool:
    """Whether :func:`load_numba` has run (numba imported, kernels are dispatchers)."""
    return _NJIT is not None


def load_numba() -> None:
    """Import numba and turn every waiting kernel into a numba dispatcher.

    Binds the names registered with :func:`bind_numba_names`, makes the
    dispatchers (nothing is compiled yet) and puts each in place of its
    stand-in in the namespace of every loaded module. Runs once; later calls
    return at once.
    """
    global _NJIT
    if numba_loaded():
        return
    from navkit._shared import compile_gc
    from navkit._shared.interrupts import interrupts_deferred

    # A Ctrl-C cutting numba's import short would leave it half imported, and
    # every later kernel call in the process failing: the interrupt waits. Not
    # while this waits for numba's compiler lock, though, which another thread
    # may hold for as long as its compile takes (a user's kernel): nothing is
    # done yet then, and a Ctrl-C stops the wait as usual. (The pauses of the
    # collector inside the deferrals: one interrupted as it ends would leave
    # the collector off.)
    # Under navkit's import lock, which a fork waits for (compile_gc): a child
    # forked during the import hung at its first kernel call (Python's locks of
    # the modules under way held by a thread it does not have).
    with compile_gc.NUMBA_IMPORT, interrupts_deferred(), compile_gc.paused():
        from numba import njit
        from numba.core.compiler_lock import global_compiler_lock
        from numba.core.registry import cpu_target

        # Before the compiler lock below is taken, so that the main thread's hold of
        # signals in its steps (compile_gc) spans it from its acquire: installed
        # inside it, the hold was begun by a nested acquire, in front of the
        # deferral below, which ended first and took Ctrl-C's hold with it; a Ctrl-C
        # as this function let go of the lock left it held for good (review 41,
        # REVSIG). Idempotent, and under NUMBA_IMPORT: one install however many
        # threads load numba.
        compile_gc.install()

    # numba's compiler lock first, then navkit's, as in a thread whose compile
    # types a stand-in (a user's kernel calling a navkit one): taken the other
    # way round, that thread and this one each waited for the other's lock.
    with global_compiler_lock, _LOCK:
        if numba_loaded():  # another thread loaded it meanwhile
            return
        with interrupts_deferred(), compile_gc.paused():
            # numba initialises its compiler (importing most of its modules) at the
            # first compile or cache load: done here, with the collector paused.
            with _blas_probe_deferred():
                cpu_target.target_context.refresh()
            _hold_refreshes(cpu_target.target_context)
            _make_dispatchers(njit)
            _NJIT = njit


class _BlasProbe:
    """numba's ``numba.np.arraymath._HAVE_BLAS``, found out the first time numba reads it.

    numba reads it only as ``if not _HAVE_BLAS`` (typing ``np.correlate`` and
    ``np.convolve`` of floats, which then call ``np.dot``); the answer is
    numba's own ``_check_blas()``, asked then instead of at numba's import
    (:func:`_blas_probe_deferred`).
    """

    __slots__ = ("_check", "_found")

    def __init__(self, check: Callable[[], object]) -> None:
        self._check = check
        self._found: bool | None = None

    def __bool__(self) -> bool:
        if self._found is None:
            # numba's compiler lock is held by whoever types the call: one probe.
            self._found = bool(self._check())
        return self._found

    def __repr__(self) -> str:
        return "<numba BLAS probe: not asked yet>" if self._found is None else repr(self._found)


@contextmanager
def _blas_probe_deferred() -> Iterator[None]:
    """numba's import of its implementations without SciPy's linear algebra, probed later.

    ``numba.np.arraymath`` (imported by numba's first registry refresh, in
    :func:`load_numba`) asks at its import whether a BLAS is there
    (``_HAVE_BLAS = _check_blas()``), and the probe imports
    ``scipy.linalg.cython_blas``: all of ``scipy.linalg``, whose array-API shim
    reads every attribute of numpy and so imports ``numpy.f2py`` and
    ``numpy.testing`` too. That was 0.15-0.16 s of CPU, about a quarter of numba's
    loading (issue 17), for an answer numba reads only when it types
    ``np.correlate`` or ``np.convolve`` (navkit's kernels never do). Here the
    probe answers that one call without importing (whatever else calls
    ``ensure_blas`` meanwhile gets numba's own), and ``_HAVE_BLAS`` becomes a
    :class:`_BlasProbe` that asks numba's ``_check_blas`` the first time it is
    read: the same answer, SciPy imported then. A numba without
    ``numba.np.linalg.ensure_blas`` probes as it does; one that keeps the answer
    elsewhere than ``_HAVE_BLAS`` is probed at once after the import (SciPy is
    one of navkit's requirements, so the deferred answer, "there is a BLAS", is
    the probe's unless that raises, as numba's own would have). Already
    imported, there is nothing to defer.
    """
    if "numba.np.arraymath" in sys.modules:
        yield
        return
    linalg: Any = importlib.import_module("numba.np.linalg")
    ensure_blas = vars(linalg).get("ensure_blas")
    if not callable(ensure_blas):
        yield
        return
    deferred: list[bool] = []

    def ensure_blas_later() -> None:
        caller = sys._getframe(1)
        if (
            caller.f_code.co_name == "_check_blas"
            and caller.f_globals.get("__name__") == "numba.np.arraymath"
        ):
            deferred.append(True)  # the answer, probed later, goes into _HAVE_BLAS
            return
        ensure_blas()

    linalg.ensure_blas = ensure_blas_later
    try:
        yield
    finally:
        linalg.ensure_blas = ensure_blas
        arraymath = sys.modules.get("numba.np.arraymath")
        space: dict[str, Any] = vars(arraymath) if arraymath is not None else {}
        if space.get("ensure_blas") is ensure_blas_later:  # bound by name at its import
            space["ensure_blas"] = ensure_blas
        if deferred:
            check = space.get("_check_blas")
            if space.get("_HAVE_BLAS") is True and callable(check):
                space["_HAVE_BLAS"] = _BlasProbe(check)
            elif callable(check):  # the answer went elsewhere: numba's own, now
                check()


#: Marks the ``refresh`` wrappers :func:`_hold_refreshes` installs (installed once).
_HELD_MARK = "__navkit_refresh_held__"
#: Per thread, whether a held refresh is under way (the typing context's, refreshed
#: by the target context's own, is not held a second time).
_REFRESHING = threading.local()


def _hold_refreshes(target_context: Any) -> None:
    """Make numba's refreshes of its registries hold a Ctrl-C back until they are done.

    numba refreshes its target and typing registries at every compile and every
    cache load (``BaseContext.refresh``), reading each registry's new entries
    through a generator (``numba.core.utils.stream_list``). A KeyboardInterrupt
    raised inside one ended it for good: every later compile or cache load in
    the process, of any kernel (the user's own too), failed with "generator
    raised StopIteration" (review 38). Raised between a batch's read and its last
    entry's install, it would drop the rest of the batch for good. The
    ``refresh`` of numba's CPU target context and of its typing context (made
    once per process) are wrapped on the instances, once (a second call finds
    the wrapper and returns): the refresh runs inside
    :func:`navkit._shared.interrupts.interrupts_deferred`, so a Ctrl-C arrives as
    it ends, and the typing context's refresh called by the target context's
    is not held again. Outside the main thread the hold does nothing (no signal
    lands there). The contexts' shallow copies (numba's ``subtarget``, one a
    compile) keep the wrapper, which refreshes the original: the same thing, as
    a refresh only adds to the registries and tables the copies share.

    Every compile and cache load in the process goes through it, the user's own
    kernels' too: a Ctrl-C landing in their refresh (a fraction of a millisecond)
    is raised a fraction of a millisecond later, as it ends, still inside the
    compile. About 40 µs a hold on a loaded 2-core machine, one per cache load
    and two per compile (the typing context's refresh, then the target context's).
    """
    from navkit._shared.interrupts import interrupts_deferred

    for context in (target_context, target_context.typing_context):
        refresh = context.refresh
        if getattr(refresh, _HELD_MARK, False):
            continue

        def held(refresh: Callable[[], None] = refresh) -> None:
            if getattr(_REFRESHING, "on", False):  # inside a held refresh already
                refresh()
                return
            _REFRESHING.on = True
            try:
                with interrupts_deferred():
                    refresh()
            finally:
                _REFRESHING.on = False

        setattr(held, _HELD_MARK, True)
        context.refresh = held


def _make_dispatchers(njit: Any) -> None:
    """Bind the registered numba names and put dispatchers in place of the stand-ins."""
    for namespace, module, names, python in _BINDINGS:
        _bind(namespace, module, names, python)
    for kernel in _WAITING:
        kernel.dispatcher = _make_dispatcher(njit, kernel.options, kernel.py_func)
    for module_object in list(sys.modules.values()):
        module_namespace = getattr(module_object, "__dict__", None)
        if not isinstance(module_namespace, dict):
            continue
        for key, value in list(module_namespace.items()):
            if type(value) is LazyKernel and value.dispatcher is not None:
                module_namespace[key] = value.dispatcher
    _WAITING.clear()


def bind_numba_names(
    namespace: dict[str, Any],
    module: str,
    *,
    python: dict[str, Any] | None = None,
    **names: str,
) -> None:
    """Bind attributes of the numba module ``module`` in ``namespace`` when numba loads.

    For what a kernel uses from numba itself (intrinsics, types): a kernel
    module calls this with ``globals()`` instead of importing them, so that
    importing the module does not import numba. ``names`` maps each name to
    bind to the attribute it stands for. Binds them at once if numba is
    already loaded. ``python`` maps names to plain Python equivalents, bound
    instead when numba's JIT is disabled (``NUMBA_DISABLE_JIT=1``: kernels then
    run as Python, and numba intrinsics cannot be called from Python).

    Examples
    --------
    >>> from navkit._shared.jit import bind_numba_names, load_numba
    >>> namespace = {}
    >>> bind_numba_names(namespace, "numba.core", numba_types="types")
    >>> load_numba()
    >>> namespace["numba_types"].float64
    float64
    """
    with _LOCK:
        if _NJIT is None:
            _BINDINGS.append((namespace, module, names, python or {}))
            return
    _bind(namespace, module, names, python or {})


def _bind(
    namespace: dict[str, Any], module: str, names: dict[str, str], python: dict[str, Any]
) -> None:
    config: Any = importlib.import_module("numba.core.config")
    if config.DISABLE_JIT and python:
        namespace.update(python)
        return
    imported = importlib.import_module(module)
    for name, attribute in names.items():
        namespace[name] = getattr(imported, attribute)


def typed_njit(**options: Any) -> Callable[[_F], _F]:
    """``numba.njit(**options)`` typed as a decorator that keeps the function's signature.

    Before numba is loaded a module-level function becomes a
    :class:`LazyKernel`; a closure (made at run time) loads numba and
    becomes a dispatcher at once.
    """

    def decorate(py_func: _F) -> _F:
        with _LOCK:
            if _NJIT is None and "<locals>" not in py_func.__qualname__:
                kernel = LazyKernel(py_func, options)
                _WAITING.append(kernel)
                return cast(_F, kernel)
        load_numba()
        return cast(_F, _make_dispatcher(_NJIT, options, py_func))

    return decorate


#: Options every navkit kernel is compiled with.
CACHED: dict[str, Any] = {"cache": True, "no_cfunc_wrapper": True}

njit_cached: Callable[[_F], _F] = typed_njit(**CACHED)
"""``numba.njit(cache=True)``."""

njit_inline: Callable[[_F], _F] = typed_njit(**CACHED, inline="always")
"""``numba.njit(cache=True, inline="always")``: inlined into the calling kernel."""

# Kernels that allocate nothing are compiled without numba's reference counting
# (the private jit option ``_nrt=False``). With it, every call that passes arrays
# increments and decrements their reference counts atomically, which perf showed
# to take about a third of an A* search's time. Such a function must not create
# arrays; numba refuses to compile it if it does.
NO_REFCOUNT: dict[str, Any] = {**CACHED, "_nrt": False}

njit_no_refcount: Callable[[_F], _F] = typed_njit(**NO_REFCOUNT)
"""``numba.njit(cache=True)`` without reference counting, for allocation-free kernels."""

njit_helper: Callable[[_F], _F] = typed_njit(**NO_REFCOUNT, no_cpython_wrapper=True)
"""As :data:`njit_no_refcount`, for a helper called only from other kernels: no
Python wrapper is compiled (a wrapper of many arguments alone costs tenths of a
second), so Python cannot call it."""

njit_force_inline: Callable[[_F], _F] = typed_njit(
    **NO_REFCOUNT, forceinline=True, no_cpython_wrapper=True
)
"""``njit_no_refcount`` compiled once and inlined by LLVM (``alwaysinline``) into
its callers: as fast as numba's IR-level ``inline="always"``, which copies and
re-types the body at every call site (seconds of first-use compilation for a
body inlined eight times), but typed once. Its arguments must not be literals
at any call site: each literal value compiles it once more. Called only from
kernels: no Python wrapper (A*'s 22-argument relax step: about 0.05 s of its
first use), and compiled as a helper (:func:`helper_compiler`)."""

#: The option of the kernels that release the GIL while they run (``nogil=True``).
#:
#: A kernel holding the GIL stops every other Python thread of the process for
#: its whole run: a 170 ms Field D* plan in a ROS 2 timer callback delayed a
#: 200 Hz IMU callback by 190-590 ms (4-5 ms without the plan; with this
#: option 16-38 ms; benchmarks/test_bench_threads.py: 230-430 ms -> 6-44 ms,
#: against 4-8 ms with no plan, on a busy 2-core machine). The long
#: kernels (the grid searches and distance fields, the Field D* walk, passes
#: over a whole cost grid, ray casting a scan into a map, scan matching, the
#: simulated LiDAR, a fusion batch, a trace's cross-track distances) release it,
#: so other threads run meanwhile and two threads planning on two maps use two
#: cores. The others keep it: releasing and taking it back costs about 40 ns a
#: call (a tenth to a quarter of a ten-point ``world_to_cell`` or one fusion
#: step, issue 17's small calls), and a thread taking it back waits while
#: another thread runs Python (up to ``sys.getswitchinterval()``, 5 ms), which
#: a kernel called thousands of times a second would pay at every call.
#: A kernel with this option must only read memory its caller alone writes:
#: its arguments are per call, per thread, or read-only (the search workspaces
#: of :mod:`navkit.planning.grid._workspace` are per thread).
#:
#: numba's cache does not key a kernel on its options, only on its source
#: file's modification time and size: a kernel given this option must have it
#: written in its own file (its decorator line), so that its cached machine
#: code, compiled with the GIL held, is not loaded again (docs/compilation.md).
RELEASES_GIL: dict[str, Any] = {"nogil": True}

njit_released: Callable[[_F], _F] = typed_njit(**NO_REFCOUNT, **RELEASES_GIL)
"""As :data:`njit_no_refcount`, releasing the GIL while it runs (:data:`RELEASES_GIL`)."""

njit_cached_released: Callable[[_F], _F] = typed_njit(**CACHED, **RELEASES_GIL)
"""As :data:`njit_cached`, releasing the GIL while it runs (:data:`RELEASES_GIL`)."""
