"""What every benchmark records about the machine it ran on."""

from __future__ import annotations

import os
import platform


def cpu_name() -> str:
    """The CPU model from /proc/cpuinfo (the architecture where there is none)."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or "?"


def describe() -> str:
    """CPU, cores, memory, Python and clingo versions, load average now."""
    import clingo

    mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    load1, load5, load15 = os.getloadavg()
    return (
        f"{cpu_name()}, nproc {os.cpu_count()}, {mem:.0f} GiB RAM, Python {platform.python_version()},"
        f" clingo {clingo.__version__}, load average {load1:.2f} / {load5:.2f} / {load15:.2f}"
    )
