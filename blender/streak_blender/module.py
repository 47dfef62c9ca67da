"""Finding the streak Python module: already importable, in the add-on's own lib/ folder (the
zip scripts/blender_addon.sh makes), or in the folder the add-on's preferences name."""

import ctypes
import importlib
import os
import sys

_LIB = os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib")


def _from_folder(folder):
    # The module links libstreak.so by its soname; loading the library first, globally, lets
    # the loader find it in a folder that is on no search path.
    for name in sorted(os.listdir(folder)):
        if name.startswith("libstreak.so"):
            ctypes.CDLL(os.path.join(folder, name), mode=ctypes.RTLD_GLOBAL)
    if folder not in sys.path:
        sys.path.insert(0, folder)
    return importlib.import_module("streak")


def load(folder=""):
    """The streak module, or ImportError saying where it was looked for."""
    if "streak" in sys.modules:
        return sys.modules["streak"]
    tried = []
    for candidate in (folder, _LIB):
        if candidate and os.path.isdir(candidate):
            try:
                return _from_folder(candidate)
            except ImportError as e:
                tried.append(f"{candidate}: {e}")
    try:
        return importlib.import_module("streak")
    except ImportError as e:
        tried.append(f"sys.path: {e}")
    raise ImportError("the streak Python module was not found (" + "; ".join(tried) +
                      "): install the zip scripts/blender_addon.sh makes, or name a build's python/ folder in the add-on's preferences")
