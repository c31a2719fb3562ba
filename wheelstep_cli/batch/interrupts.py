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
            return
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
    inherit the block (a Dask cluster's event loop and every worker process it starts,
    restarts included, keep it; a process pool's workers lift it once set up to end quietly),
    so a Ctrl-C reaches this process only. One that arrives meanwhile waits and is delivered
    as the block ends. Where threads cannot block signals (Windows) the block runs as is."""
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
    timers: list[threading.Timer] = []

    def raise_again(unraisable):
        if unraisable.exc_type is not None and issubclass(unraisable.exc_type, KeyboardInterrupt):
            # from another thread, once the callback is left: raised here and now, it would
            # land in this hook, as unraisable as where it came from
            timers.append(threading.Timer(AGAIN_SECONDS, _thread.interrupt_main))
            timers[-1].daemon = True
            timers[-1].start()
        else:
            before(unraisable)

    sys.unraisablehook = raise_again
    try:
        yield
    finally:
        sys.unraisablehook = before
        for timer in timers:                  # the block is over: not into whatever follows
            timer.cancel()


#: Seconds after a lost Ctrl-C that it is raised again: far longer than a garbage-collector
#: callback or a finalizer runs, far shorter than a person notices.
AGAIN_SECONDS = 0.05


def caused_by_interrupt(err: BaseException) -> bool:
    """Whether ``err`` is a Ctrl-C or an error raised on account of one: wrapped by a library
    (a class body's ``__set_name__`` while a module loads turns it into a RuntimeError) or
    met while cleaning up after it (the person asked to stop; that is what to say). Context
    a ``raise ... from None`` suppressed is not followed."""
    seen: set[int] = set()
    while err is not None and id(err) not in seen:
        if isinstance(err, KeyboardInterrupt):
            return True
        seen.add(id(err))
        err = err.__cause__ or (None if err.__suppress_context__ else err.__context__)
    return False


def exit_now(code: int) -> None:
    """End the process with ``code`` at once (what it printed flushed first), leaving out
    Python's exit handlers and the joining of threads."""
    import os
    import sys

    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):         # a closed pipe: nothing more can be said
            pass
    os._exit(code)


#: Seconds the threads of a stopped run have to end before the process ends without them.
STOPPED_THREADS_SECONDS = 2.0


def exit_unless_threads_end(code: int, seconds: float = STOPPED_THREADS_SECONDS) -> None:
    """End the process with ``code`` at once (:func:`exit_now`) unless every thread Python's
    shutdown would wait for ends within ``seconds``; else return, for the normal shutdown
    (which lets the standard library release what its worker pools held)."""
    import time

    deadline = time.monotonic() + seconds
    for thread in threading.enumerate():
        if thread is not threading.current_thread() and not thread.daemon:
            thread.join(max(0.0, deadline - time.monotonic()))
            if thread.is_alive():
                exit_now(code)
