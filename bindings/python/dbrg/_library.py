"""Finds and loads the dbrg shared library once, checking that its version matches this package; and
libdbrg_io (the project's writers and vertex normals, include/dbrg/dbrg_io.h) when a mesh is written.

Search order: the file named by the environment variable DBRG_LIBRARY (DBRG_IO_LIBRARY for libdbrg_io;
nothing else is tried when it is set), a copy next to this package, then the system loader
(LD_LIBRARY_PATH, ld.so.cache, ...).
"""

import ctypes
import ctypes.util
import os
import sys
import threading

from . import _capi, _io


class LibraryError(ImportError):
    """The dbrg shared library could not be found or loaded, or its version does not fit this package."""


_lock = threading.Lock()
_library = None
_library_path = None
_io_library = None


def _file_names(base="dbrg"):
    major = _capi.DBRG_VERSION_MAJOR
    if sys.platform == "win32":
        return ["%s.dll" % base, "lib%s.dll" % base, "%s-%d.dll" % (base, major)]
    if sys.platform == "darwin":
        return ["lib%s.%d.dylib" % (base, major), "lib%s.dylib" % base]
    return ["lib%s.so.%d" % (base, major), "lib%s.so" % base]


def _candidates(variable="DBRG_LIBRARY", base="dbrg"):
    """Yields (what to pass to CDLL, whether it is an explicit path)."""
    explicit = os.environ.get(variable)
    if explicit:
        yield explicit, True
        return
    here = os.path.dirname(os.path.abspath(__file__))
    for name in _file_names(base):
        path = os.path.join(here, name)
        if os.path.exists(path):
            yield path, True
    # Bare names: the system loader searches its own path.
    for name in _file_names(base):
        yield name, False
    found = ctypes.util.find_library(base)
    if found:
        yield found, False


def _compatible(found):
    """The same major and minor version. The stable ABI only grows within a major version (the C and
    CMake consumers accept a newer minor library), but this package also calls EXPERIMENTAL functions
    (the tetrahedralization, the tiles), which may change in any minor version (docs/api.md)."""
    major, minor = found // 10000, found // 100 % 100
    return major == _capi.DBRG_VERSION_MAJOR and minor == _capi.DBRG_VERSION_MINOR


def _open():
    tried = []
    for target, explicit in _candidates():
        try:
            library = ctypes.CDLL(target)
        except OSError as error:
            if explicit:
                origin = "named by DBRG_LIBRARY" if target == os.environ.get("DBRG_LIBRARY") else "next to the package"
                raise LibraryError("cannot load the dbrg shared library %r %s: %s" % (target, origin, error)) from None
            tried.append(target)
            continue
        try:
            _capi.declare(library)
        except AttributeError as error:
            raise LibraryError(
                "%s is not a usable dbrg library (%s); this package needs dbrg %s"
                % (target, error, _capi.DBRG_VERSION_STRING)
            ) from None
        found = library.dbrg_version_number()
        if not _compatible(found):
            raise LibraryError(
                "%s is dbrg %s, but this Python package (dbrg %s) needs the library version %d.%d.x; "
                "point DBRG_LIBRARY at a matching libdbrg"
                % (target, library.dbrg_version_string().decode(), _capi.DBRG_VERSION_STRING,
                   _capi.DBRG_VERSION_MAJOR, _capi.DBRG_VERSION_MINOR)
            )
        return library, target
    raise LibraryError(
        "cannot find the dbrg shared library (tried %s). Build it (meson setup build && ninja -C build) and "
        "either set DBRG_LIBRARY=/path/to/build/src/libdbrg.so, copy the library next to this package (%s), "
        "or install it (meson install) where the system loader looks"
        % (", ".join(tried) or "nothing", os.path.dirname(os.path.abspath(__file__)))
    )


def library():
    """Returns the loaded ctypes.CDLL, loading it on first use. ctypes.CDLL releases the GIL for the
    length of every foreign call and takes it back for Python callbacks."""
    global _library, _library_path
    if _library is None:
        with _lock:
            if _library is None:
                loaded, path = _open()
                _library_path = path
                _library = loaded
    return _library


def library_path():
    """What the library was loaded from (a path, or a name resolved by the system loader)."""
    library()
    return _library_path


def io_library():
    """Returns libdbrg_io as a ctypes.CDLL with its functions declared, loading it on first use. It is
    built from the same tree as libdbrg, so it has no version check of its own."""
    global _io_library
    if _io_library is None:
        with _lock:
            if _io_library is None:
                _io_library = _open_io()
    return _io_library


def _open_io():
    tried = []
    for target, explicit in _candidates("DBRG_IO_LIBRARY", "dbrg_io"):
        try:
            library = ctypes.CDLL(target)
        except OSError as error:
            if explicit:
                raise LibraryError("cannot load the dbrg I/O library %r: %s" % (target, error)) from None
            tried.append(target)
            continue
        try:
            _io.declare(library)
        except AttributeError as error:
            raise LibraryError("%s is not a usable libdbrg_io (%s)" % (target, error)) from None
        return library
    raise LibraryError(
        "cannot find libdbrg_io, which writes mesh files (tried %s). Install the package with `pip install .` "
        "from the repository, or set DBRG_IO_LIBRARY=/path/to/build/src/io/libdbrg_io.so" % ", ".join(tried))
