# Ends a pvpython script without finalising ParaView, its output kept.
import os
import sys


def exit_keeping_output(code=0):
    """os._exit(code) after flushing Python's streams and C stdio's buffers. pvpython 5.11 (GLX)
    may raise an X error while finalising after a render, so scripts leave without finalising;
    pvpython 6.1 writes Python's output through C stdio buffers that sys.stdout.flush() leaves
    alone and os._exit() would drop."""
    sys.stdout.flush()
    sys.stderr.flush()
    try:
        import ctypes

        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):
        pass
    os._exit(code)
