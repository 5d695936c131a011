"""Freed memory kept for reuse (``strand.solver.keep_freed_memory``): a large block freed and
allocated again faults its pages in once, not at every allocation as glibc's defaults do."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import pytest

#: allocates, writes and frees 64 MiB ten times; prints the minor page faults after the first
SCRIPT = textwrap.dedent(
    """
    import resource, sys
    import numpy as np
    from strand.solver.memory import keep_freed_memory
    print(keep_freed_memory() if sys.argv[1] == "keep" else False)
    def faults():
        return resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    a = np.empty(8 << 20); a[:] = 1.0; del a
    before = faults()
    for _ in range(10):
        a = np.empty(8 << 20); a[:] = 1.0; del a
    print(faults() - before)
    """
)


def _faults(mode: str) -> tuple[bool, int]:
    env = {k: v for k, v in os.environ.items() if k != "STRAND_KEEP_FREED_MEMORY"}
    done = subprocess.run(
        [sys.executable, "-c", SCRIPT, mode], capture_output=True, text=True, check=True, env=env
    )
    applied, faults = done.stdout.split()
    return applied == "True", int(faults)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's mallopt")
def test_a_freed_block_is_reused_without_faulting_its_pages_in_again():
    applied, kept = _faults("keep")
    _, default = _faults("default")
    assert applied
    # glibc maps each 64 MiB block afresh: at least a fault per allocation (measured 5440 for
    # the ten, in 2 MiB pages where the kernel gives huge pages); kept, none (measured 0)
    assert default >= 10 and 20 * kept < default
