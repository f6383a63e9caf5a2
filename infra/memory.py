"""How much memory this process may still use, as the estimates before
long work need it (the map's Dyson series, the compiler's gcc and
rumoca)."""

import os
import resource

__all__ = ["available_memory"]


def available_memory():
    """Bytes of memory this process may still use: the least of the
    memory available now (``MemAvailable`` of /proc/meminfo, else the
    physical memory), what is left of its cgroup's limit (a batch job's
    or a container's, v2 or v1) and what is left of its address-space
    limit (``ulimit -v``)."""
    try:
        with open("/proc/meminfo") as stream:
            free = next(int(line.split()[1]) * 1024 for line in stream
                        if line.startswith("MemAvailable:"))
    except (OSError, StopIteration, ValueError):
        free = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    limits = [free, _cgroup_left()]
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft != resource.RLIM_INFINITY:
        limits.append(soft - _status_bytes("VmSize:"))
    return max(0, min(v for v in limits if v is not None))


def _status_bytes(key):
    try:
        with open("/proc/self/status") as stream:
            return next(int(line.split()[1]) * 1024 for line in stream
                        if line.startswith(key))
    except (OSError, StopIteration, ValueError):
        return 0


def _cgroup_left():
    """Limit minus usage of this process's memory cgroup, or None."""
    try:
        with open("/proc/self/cgroup") as stream:
            lines = [line.strip().split(":", 2) for line in stream]
    except OSError:
        return None
    places = []
    for _, controllers, path in lines:
        if controllers == "":                      # v2
            places.append((f"/sys/fs/cgroup{path}", "memory.max",
                           "memory.current"))
        elif "memory" in controllers.split(","):   # v1
            places.append((f"/sys/fs/cgroup/memory{path}",
                           "memory.limit_in_bytes", "memory.usage_in_bytes"))
    for folder, limit, usage in places:
        try:
            with open(os.path.join(folder, limit)) as a, \
                    open(os.path.join(folder, usage)) as b:
                text, used = a.read().strip(), int(b.read())
        except (OSError, ValueError):
            continue
        if text != "max" and int(text) < 2 ** 60:
            return int(text) - used
    return None
