"""Ctrl-C (SIGINT) around work that must not be cut in half.

A Ctrl-C at a terminal goes to every process of the foreground group: the command and the
worker processes it started. The command answers it (cancels, merges what is done, stops its
cluster in order); its workers must not also die of it half way, printing tracebacks of
their own. So workers are started with SIGINT blocked (:func:`interrupts_kept_from_children`),
and the few steps that must finish once begun hold it (:func:`interrupts_deferred`).
"""

from __future__ import annotations

import signal
import threading
from contextlib import contextmanager


@contextmanager
def interrupts_deferred():
    """Hold a SIGINT that arrives inside the block and hand it on when the block ends to the
    handler it would have gone to (Python's raises KeyboardInterrupt, also when the block
    itself failed: the person asked to stop); a second SIGINT inside the block goes through at
    once, so that a block that hangs can still be stopped. In the main thread only; elsewhere
    the block runs as is."""
    # a handler set from C (getsignal None) could not be put back: left as it is
    if threading.current_thread() is not threading.main_thread() or signal.getsignal(signal.SIGINT) is None:
        yield
        return
    caught: list[int] = []

    def hold(signum, frame):
        if caught:                            # the second: at once, and not again at the end
            caught.clear()
            _deliver(previous)
        caught.append(signum)

    previous = signal.signal(signal.SIGINT, hold)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if caught:
            _deliver(previous)


def _deliver(handler) -> None:
    """Hand a SIGINT to ``handler`` as the signal machinery would."""
    if callable(handler):                     # Python's own raises KeyboardInterrupt
        handler(signal.SIGINT, None)
    elif handler == signal.SIG_DFL:
        signal.raise_signal(signal.SIGINT)


@contextmanager
def interrupts_kept_from_children():
    """Block SIGINT in this thread for the block. Threads and processes started inside it
    inherit the blocked signal for their whole life (a process pool's workers, a Dask
    cluster's event loop and every worker process it starts, restarts included), so a Ctrl-C
    reaches this process only. One that arrives meanwhile waits and is delivered as the block
    ends. Where threads cannot block signals (Windows) the block runs as is."""
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    from multiprocessing import resource_tracker

    # started now, not by the first worker: starting it unblocks SIGINT in the starting
    # thread (the standard library's own guard for it), which would undo the block below
    resource_tracker.ensure_running()
    before = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, before)


@contextmanager
def interrupts_not_lost():
    """For the block, a Ctrl-C that lands where Python cannot raise it (in a garbage-collector
    callback or a finalizer, which print 'Exception ignored in ...' and go on) is not printed
    and lost but raised again in the main thread a moment later (:data:`AGAIN_SECONDS`)."""
    import _thread
    import sys

    before = sys.unraisablehook

    def raise_again(unraisable):
        if unraisable.exc_type is not None and issubclass(unraisable.exc_type, KeyboardInterrupt):
            # from another thread, once the callback is left: raised here and now, it would
            # land in this hook, as unraisable as where it came from
            timer = threading.Timer(AGAIN_SECONDS, _thread.interrupt_main)
            timer.daemon = True
            timer.start()
        else:
            before(unraisable)

    sys.unraisablehook = raise_again
    try:
        yield
    finally:
        sys.unraisablehook = before


#: Seconds after a lost Ctrl-C that it is raised again: far longer than a garbage-collector
#: callback or a finalizer runs, far shorter than a person notices.
AGAIN_SECONDS = 0.05


def caused_by_interrupt(err: BaseException) -> bool:
    """Whether ``err`` is a Ctrl-C that a library wrapped in an error of its own (a class
    body's ``__set_name__`` while a module loads turns it into a RuntimeError)."""
    seen: set[int] = set()
    while err is not None and id(err) not in seen:
        if isinstance(err, KeyboardInterrupt):
            return True
        seen.add(id(err))
        err = err.__cause__ or err.__context__
    return False
