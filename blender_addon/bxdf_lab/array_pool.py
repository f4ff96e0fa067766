"""numpy arrays of the last export, handed out again to the next one.

Blender's malloc (jemalloc) hands freed pages back to the kernel within a fraction of a second,
so every export's mesh arrays were fresh memory, faulted in 4 KB at a time: 2000-3000 page
faults for the 242k triangles of a harness scene, 20-28 ms of its export on a VM where a fault
costs ~9 us. An array of the pool is handed out only when nothing but the pool refers to it (the
export's dict and its views are gone), so an array still in use is never written over. The pool
keeps only what the last two exports used, and at most MAX_BYTES. Exports may run at once (a
material preview renders in a job thread while F12 renders in another): an array is claimed
under a lock, so two of them never get the same one.
"""

import sys
import threading

import numpy as np

MAX_BYTES = 64 << 20

# sys.getrefcount of an array only the pool's list refers to, seen from a loop over that list:
# the list, the loop variable and getrefcount's own argument.
_FREE_REFCOUNT = 3


class ArrayPool:
    def __init__(self, max_bytes=MAX_BYTES):
        self.max_bytes = max_bytes
        self._arrays = {}  # (dtype, n) -> [array, ...]
        self._last_use = {}  # id(array) -> the export that last took it
        self._bytes = 0
        self._export = 0
        self._lock = threading.Lock()

    def begin_export(self):
        """Starts an export: arrays neither this nor the last export took are let go."""
        with self._lock:
            self._begin_export()

    def _begin_export(self):
        self._export += 1
        for key, arrays in list(self._arrays.items()):
            kept = [a for a in arrays if self._last_use.get(id(a), 0) >= self._export - 1]
            for a in arrays:
                if self._last_use.get(id(a), 0) < self._export - 1:
                    self._last_use.pop(id(a), None)
                    self._bytes -= a.nbytes
            if kept:
                self._arrays[key] = kept
            else:
                del self._arrays[key]

    def empty(self, n, dtype):
        """A 1-D array of n elements of dtype, contents undefined (as np.empty)."""
        with self._lock:
            # The caller holds the array before the lock is let go: no other export can see it
            # free in between.
            return self._claim(n, np.dtype(dtype))

    def _claim(self, n, dtype):
        key = (dtype.str, n)
        arrays = self._arrays.get(key)
        if arrays:
            for a in arrays:
                if sys.getrefcount(a) == _FREE_REFCOUNT:
                    self._last_use[id(a)] = self._export
                    return a
        a = np.empty(n, dtype=dtype)
        if n > 0 and self._bytes + a.nbytes <= self.max_bytes:
            self._arrays.setdefault(key, []).append(a)
            self._last_use[id(a)] = self._export
            self._bytes += a.nbytes
        return a

    def zeros(self, n, dtype):
        a = self.empty(n, dtype)
        a.fill(0)
        return a

    @property
    def nbytes(self):
        return self._bytes


# The export's pool (export.py takes its mesh arrays from it).
mesh_arrays = ArrayPool()
