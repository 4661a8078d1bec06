"""ctypes declarations mirroring include/dbrg/dbrg_io.h (libdbrg_io: the project's mesh writers and
vertex normals). Declares only; dbrg/_library.py loads the library."""

from ctypes import POINTER, c_char_p, c_double, c_float, c_int, c_size_t, c_uint32

DBRG_IO_STATUS = {
    0: "DBRG_IO_OK",
    1: "DBRG_IO_ERR_INVALID_ARGUMENT",
    2: "DBRG_IO_ERR_FILE",
    3: "DBRG_IO_ERR_OUT_OF_MEMORY",
}

FUNCTIONS = {
    "dbrg_io_vertex_normals": (c_int, [POINTER(c_double), c_uint32, POINTER(c_uint32), c_uint32, POINTER(c_float)]),
    "dbrg_io_write_mesh": (c_int, [c_char_p, POINTER(c_double), c_uint32, POINTER(c_uint32), c_uint32,
                                   POINTER(c_float), c_char_p, c_size_t]),
}


def declare(library):
    """Sets restype/argtypes of every function; raises AttributeError naming the first one missing."""
    for name, (restype, argtypes) in FUNCTIONS.items():
        function = getattr(library, name)
        function.restype = restype
        function.argtypes = argtypes
    return library
