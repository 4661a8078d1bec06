"""ctypes declarations mirroring include/dbrg/dbrg_io.h (libdbrg_io: the project's readers, mesh writers
and vertex normals). Declares only; dbrg/_library.py loads the library."""

from ctypes import POINTER, c_char_p, c_double, c_float, c_int, c_size_t, c_uint32, c_void_p

# The header's enums by name, as bindings/check_agreement.py compares them.
ENUMS = {
    "dbrg_io_status": {
        "DBRG_IO_OK": 0,
        "DBRG_IO_ERR_INVALID_ARGUMENT": 1,
        "DBRG_IO_ERR_FILE": 2,
        "DBRG_IO_ERR_OUT_OF_MEMORY": 3,
    },
    "dbrg_io_value_type": {
        "DBRG_IO_INT8": 0,
        "DBRG_IO_UINT8": 1,
        "DBRG_IO_INT16": 2,
        "DBRG_IO_UINT16": 3,
        "DBRG_IO_INT32": 4,
        "DBRG_IO_UINT32": 5,
        "DBRG_IO_FLOAT32": 6,
        "DBRG_IO_FLOAT64": 7,
    },
}

# Status names by value.
DBRG_IO_STATUS = {value: name for name, value in ENUMS["dbrg_io_status"].items()}

# The numpy type of each dbrg_io_value_type value: "int8", "uint8", ... "float64".
VALUE_TYPES = {value: name[len("DBRG_IO_"):].lower() for name, value in ENUMS["dbrg_io_value_type"].items()}

FUNCTIONS = {
    "dbrg_io_vertex_normals": (c_int, [POINTER(c_double), c_uint32, POINTER(c_uint32), c_uint32, POINTER(c_float)]),
    "dbrg_io_write_mesh": (c_int, [c_char_p, POINTER(c_double), c_uint32, POINTER(c_uint32), c_uint32,
                                   POINTER(c_float), c_char_p, c_size_t]),
    "dbrg_io_read_points": (c_int, [c_char_p, POINTER(c_void_p), c_char_p, c_size_t]),
    "dbrg_io_points_destroy": (None, [c_void_p]),
    "dbrg_io_points_count": (c_uint32, [c_void_p]),
    "dbrg_io_points_positions": (c_void_p, [c_void_p]),
    "dbrg_io_points_normals": (c_void_p, [c_void_p]),
    "dbrg_io_points_attribute_count": (c_uint32, [c_void_p]),
    "dbrg_io_points_attribute_name": (c_char_p, [c_void_p, c_uint32]),
    "dbrg_io_points_attribute_type": (c_int, [c_void_p, c_uint32]),
    "dbrg_io_points_attribute_values": (c_void_p, [c_void_p, c_uint32]),
}


def declare(library):
    """Sets restype/argtypes of every function; raises AttributeError naming the first one missing."""
    for name, (restype, argtypes) in FUNCTIONS.items():
        function = getattr(library, name)
        function.restype = restype
        function.argtypes = argtypes
    return library
