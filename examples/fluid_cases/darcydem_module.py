"""The darcydem Python module that the examples' scripts drive: the one
built next to the program they are given (build/python beside
build/darcydem), so that a script and the program are the same build."""
import os
import sys


def load_module(darcydem_exe):
    """Imports darcydem from python/ next to `darcydem_exe`, or exits
    saying how to build it."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(darcydem_exe)), "python"))
    try:
        import darcydem
    except ImportError as e:
        sys.exit(f"the darcydem Python module is not next to {darcydem_exe} ({e}); build it with "
                 "scripts/build.sh (DARCYDEM_BUILD_PYTHON=ON, the default)")
    return darcydem
