"""Ctrl-C as a request to stop a run at its last converged step."""

from __future__ import annotations

import signal
import threading
from collections.abc import Callable
from types import FrameType
from typing import Any, TextIO

__all__ = ["Interrupt"]


class Interrupt:
    """Ctrl-C as a request to stop: while active (``with Interrupt() as stop:``), a first Ctrl-C
    sets ``requested``: the Newton solve under way stops at its next residual evaluation and the
    load stepper raises ``RunInterrupted`` at the last converged step, so that a run can write
    its summary. A second Ctrl-C interrupts at once (``KeyboardInterrupt``). Outside the main
    thread, where Python cannot handle signals, it does nothing."""

    def __init__(self, stream: TextIO | None = None):
        self.requested = False
        self.stream = stream
        #: the SIGINT handler before ours, put back on exit
        self._previous: Callable[[int, FrameType | None], Any] | int | None = None

    def _handle(self, signum, frame):
        if self.requested:
            raise KeyboardInterrupt
        self.requested = True
        if self.stream is not None:
            print(
                "\nstrand: interrupted; stopping at the last converged step (Ctrl-C again to "
                "stop at once)",
                file=self.stream,
                flush=True,
            )

    def __enter__(self) -> Interrupt:
        if threading.current_thread() is threading.main_thread():
            self._previous = signal.signal(signal.SIGINT, self._handle)
        return self

    def __exit__(self, *exc) -> None:
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)
            self._previous = None
