#!/usr/bin/env python3
"""Writes the seed corpora fuzz/corpus/<harness>/seed_* (small hand-picked inputs the fuzzers start from).

The point encoding mirrors fuzz/point_producer.h, the control bytes fuzz_reconstruct.cpp and
fuzz_predicates.cpp. Inputs that once found a bug live beside the seeds under other names (crash_*,
slow_*); this script never touches them. Run it again after changing an encoding, and commit the result.
"""
import math
import os
import struct

CORPUS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
GRID_SIZES = [2, 3, 4, 5, 7, 16, 64, 256]
SPECIAL, RAW = 255, 254
NAN, INF, HUGE, TINY = 0, 2, 6, 12  # indices into SPECIAL_VALUES in point_producer.cpp


def points(coordinates, grid=256, float32=False, padding=0, offset=0, exponent=0, escapes=False):
    """Encodes points given as grid steps (integers) or ('special', index) / ('raw', float) escapes."""
    out = bytearray([(1 if float32 else 0) | padding << 1 | offset << 5,
                     GRID_SIZES.index(grid) | (8 if escapes else 0),
                     (exponent + 64) % 128])
    for point in coordinates:
        for value in point:
            if isinstance(value, tuple):
                kind, what = value
                out += bytes([SPECIAL, what]) if kind == "special" else bytes([RAW]) + struct.pack(">d", what)
            else:
                assert -(grid // 2) <= value < grid - grid // 2
                out.append(value + grid // 2)
    return bytes(out)


def scaled(shape, count, steps=100):
    """`count` points of a unit-sized parametric shape rounded to integer grid steps."""
    return [tuple(int(round(steps * c)) for c in shape(i, count)) for i in range(count)]


def sphere(i, n):
    z = 1 - (2 * i + 1) / n
    r, angle = math.sqrt(1 - z * z), i * math.pi * (3 - math.sqrt(5))
    return r * math.cos(angle), r * math.sin(angle), z


def torus(i, n):
    u, v = 2 * math.pi * (i * 0.618034 % 1), 2 * math.pi * i / n
    return (0.8 + 0.3 * math.cos(u)) * math.cos(v), (0.8 + 0.3 * math.cos(u)) * math.sin(v), 0.3 * math.sin(u)


def hemisphere(i, n):
    x, y, z = sphere(i, 2 * n)
    return x, y, abs(z)


LATTICE = [(x, y, z) for x in range(-2, 3) for y in range(-2, 3) for z in range(-2, 3)]
SHELL = [(x, y, z) for x in range(-3, 3) for y in range(-3, 3) for z in range(-3, 3) if {-3, 2} & {x, y, z}]
CUBE = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
OCTAHEDRON = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
TETRAHEDRON = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
# Every integer point at distance 5 from the origin: a large cospherical set.
SPHERE_25 = [(x, y, z) for x in range(-5, 6) for y in range(-5, 6) for z in range(-5, 6) if x * x + y * y + z * z == 25]

POINT_SETS = {
    "tetrahedron": points(TETRAHEDRON, grid=4),
    "cube_and_centre": points(CUBE + [(0, 0, 0)], grid=3),
    "octahedron": points(OCTAHEDRON, grid=3, exponent=-20),
    "lattice_5x5x5": points(LATTICE, grid=5),
    "lattice_shell": points(SHELL, grid=7, exponent=30),
    "cospherical_r5": points(SPHERE_25, grid=16),
    "sphere_300": points(scaled(sphere, 300), grid=256),
    "torus_400": points(scaled(torus, 400), grid=256, float32=True, padding=3, offset=1),
    "hemisphere_200": points(scaled(hemisphere, 200), grid=256, padding=7, offset=5),
    "coplanar": points([(x, y, 0) for x in range(-2, 3) for y in range(-2, 3)], grid=5),
    "collinear": points([(x, x, -x) for x in range(-3, 4)] * 2, grid=7),
    "duplicates": points(TETRAHEDRON[:3] * 4, grid=4),
    "nan": points(CUBE[:4] + [(0, ("special", NAN), 0)] + CUBE[4:], grid=3, escapes=True),
    "huge_and_tiny": points(CUBE + [(("special", HUGE), 0, 0), (0, ("special", TINY), 0), (("raw", 1e-310), 0, 1)],
                            grid=3, escapes=True),
    "float32_odd_stride": points(scaled(sphere, 60, steps=60), grid=256, float32=True, padding=5, offset=3, exponent=-40),
    "empty": points([]),
}

# fuzz_reconstruct: control byte (bits 0-1 params: 0 NULL, 1 defaults, 2 produced; bits 2-3 fault: 1 fail
# one allocation, 2 fail from one on, 3 cancel; bits 4-5 variant: 1 reversed, 2 relaid, 3 rescaled; bit 6
# mangle), [mangle kind], fault step (4 bytes), [mangle amount (4)], [variant choice (1)], [params (10)], points.
def reconstruct(points_bytes, params_mode=1, fault=0, variant=0, mangle=None, step=0, amount=0, choice=0, params=b""):
    control = params_mode | fault << 2 | variant << 4 | (0x40 if mangle is not None else 0)
    out = bytearray([control])
    if mangle is not None:
        out.append(mangle)
    out += struct.pack(">I", step)
    if mangle is not None:
        out += struct.pack(">I", amount)
    if variant:
        out.append(choice)
    if params_mode >= 2:
        assert len(params) == 10
        out += params
    return bytes(out) + points_bytes


# produce_params bytes: table flag (1) + angle, boundary factor, mean, fill, hole edges, components, backend,
# threads, struct size; each a table index (see fuzz_reconstruct.cpp).
VALID_PARAMS = bytes([0, 128, 1, 0, 1, 0, 0, 0, 0, 0])
GLOBAL_MEAN_NO_FILL = bytes([1, 0, 0, 1, 0, 1, 1, 0, 1, 0])
BAD_ANGLE = bytes([1, 6, 0, 0, 1, 0, 0, 0, 0, 0])
TETGEN = bytes([0, 200, 3, 0, 1, 3, 2, 1, 0, 0])
BAD_STRUCT_SIZE = bytes([0, 100, 0, 0, 1, 0, 0, 0, 0, 3])

RECONSTRUCT = {name: reconstruct(data) for name, data in POINT_SETS.items()}
RECONSTRUCT.update({
    "sphere_no_params": reconstruct(POINT_SETS["sphere_300"], params_mode=0),
    "sphere_produced_params": reconstruct(POINT_SETS["sphere_300"], params_mode=2, params=VALID_PARAMS),
    "torus_global_mean": reconstruct(POINT_SETS["torus_400"], params_mode=2, params=GLOBAL_MEAN_NO_FILL),
    "bad_sliver_angle": reconstruct(POINT_SETS["cube_and_centre"], params_mode=2, params=BAD_ANGLE),
    "tetgen_backend": reconstruct(POINT_SETS["octahedron"], params_mode=2, params=TETGEN),
    "bad_struct_size": reconstruct(POINT_SETS["octahedron"], params_mode=2, params=BAD_STRUCT_SIZE),
    "fail_allocation_7": reconstruct(POINT_SETS["lattice_5x5x5"], fault=1, step=6),
    "fail_allocations_from_30": reconstruct(POINT_SETS["sphere_300"], fault=2, step=29),
    "cancel_at_5": reconstruct(POINT_SETS["hemisphere_200"], fault=3, step=4),
    "short_stride": reconstruct(POINT_SETS["tetrahedron"], mangle=0, amount=1),
    "bad_type": reconstruct(POINT_SETS["tetrahedron"], mangle=1, amount=5),
    "null_data": reconstruct(POINT_SETS["tetrahedron"], mangle=2),
    "lying_count": reconstruct(POINT_SETS["tetrahedron"], mangle=3, amount=12345),
    "overflowing_stride": reconstruct(POINT_SETS["cube_and_centre"], mangle=4),
    "reversed_cospherical": reconstruct(POINT_SETS["cospherical_r5"], variant=1),
    "reversed_shell": reconstruct(POINT_SETS["lattice_shell"], variant=1),
    "relaid_torus": reconstruct(POINT_SETS["torus_400"], variant=2, choice=0x35),
    "rescaled_sphere": reconstruct(POINT_SETS["sphere_300"], variant=3, choice=200),
})

# fuzz_predicates: mode (0 wide integers, 1 small integers, 2 near-coplanar, 3 near-cospherical, 4 raw
# doubles, 5 wide cospherical), permutation, then the mode's numbers; short inputs are padded with zeros by
# the reader.
def predicates(mode, permutation, body):
    return bytes([mode, permutation]) + body


def pseudo_random_bytes(seed, count):
    state, out = seed, bytearray()
    for _ in range(count):
        state = (state * 6364136223846793005 + 1442695040888963407) % 2**64
        out.append(state >> 56)
    return bytes(out)


PREDICATES = {f"mode{mode}_{k}": predicates(mode, 17 * k + mode, pseudo_random_bytes(31 * mode + k, 160))
              for mode in range(6) for k in range(3)}
PREDICATES["all_zero"] = bytes(64)

PLY_ASCII = b"""ply
format ascii 1.0
comment a tetrahedron with a quad-free face list
element vertex 4
property float x
property float y
property float z
property uchar red
element face 4
property list uchar int vertex_indices
end_header
0 0 0 255
1 0 0 0
0 1 0 0
0 0 1 0
3 0 2 1
3 0 1 3
3 0 3 2
3 1 2 3
"""


def ply_binary(endian):
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    header = (f"ply\nformat {fmt} 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
              "element face 2\nproperty list uchar uint vertex_indices\nend_header\n").encode()
    body = b"".join(struct.pack(endian + "3d", *p) for p in TETRAHEDRON)
    body += struct.pack(endian + "B3I", 3, 0, 2, 1) + struct.pack(endian + "B4I", 4, 0, 1, 3, 2)
    return header + body


PLY_STRIPS = b"""ply
format ascii 1.0
element vertex 5
property double x
property double y
property double z
element tristrips 1
property list int int vertex_indices
end_header
0 0 0
1 0 0
0 1 0
1 1 0
2 1 0
6 0 1 2 3 -1 4
"""

# Text that turns into binary data (an ELF file's first bytes): refused at its first line holding a zero byte.
BINARY_TAIL = b"\x7fELF\x02\x01\x01" + bytes(9) + b"\xff\xfe\nmore\n"

# A PLY header whose element repeats a property name after many others (once a quadratic search).
PLY_REPEATED_PROPERTY = (b"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                         b"element junk 0\n" + b"".join(b"property uchar p%d\n" % i for i in range(300)) +
                         b"property uchar p150\nend_header\n")


def las(minor, fmt, points, count=None, legacy=None, record_length=None, offset_to_points=None, vlr=b"", padding=0):
    """A LAS file (ASPRS LAS 1.4 R15 layout): header, `vlr` bytes, then records of X Y Z intensity, the
    format's other fields zero and colour (points are (x, y, z, intensity, red, green, blue) integers)."""
    header_size = 227 if minor <= 2 else 235 if minor == 3 else 375
    extended = fmt >= 6
    colour = fmt in (2, 3, 5, 7, 8, 10)

    def record(p):
        out = struct.pack("<3iH", *p[:4]) + bytes(8 if extended else 6)
        out += struct.pack("<d", 1.5) if fmt in (1, 3, 4, 5) else b""
        out += struct.pack("<3H", *p[4:7]) if colour else b""
        out += bytes(2) if fmt in (8, 10) else b""
        out += bytes(29) if fmt in (4, 5, 9, 10) else b""
        return out + bytes(padding)

    records = b"".join(record(p) for p in points)
    count = len(points) if count is None else count
    legacy = (0 if minor >= 4 and extended else count) if legacy is None else legacy
    length = len(record((0,) * 7)) if record_length is None else record_length
    start = header_size + len(vlr) if offset_to_points is None else offset_to_points
    out = b"LASF" + bytes(4 + 16) + bytes([1, minor]) + b"s" * 32 + b"g" * 32 + struct.pack("<HH", 1, 2024)
    out += struct.pack("<HIIBHI", header_size, start, 1 if vlr else 0, fmt, length, legacy) + bytes(20)
    out += struct.pack("<3d", 0.01, 0.01, 0.001) + struct.pack("<3d", 1000.0, -2000.0, 0.0) + bytes(48)
    out += bytes(8) if minor >= 3 else b""
    out += bytes(12) + struct.pack("<Q", count) + bytes(120) if minor >= 4 else b""
    assert len(out) == header_size
    return out + vlr + records


LAS_POINTS = [(0, 0, 0, 0, 0, 0, 0), (100, -200, 3000, 65535, 65535, 0, 256), (2**31 - 1, -2**31, 7, 17, 1, 2, 3),
              (-5, 5, -5, 300, 40000, 50000, 60000)]
LAS_SEEDS = {f"v1{minor}_format{fmt}": las(minor, fmt, LAS_POINTS) for minor in (2, 3, 4)
             for fmt in range(11 if minor == 4 else 6)}
LAS_SEEDS.update({
    "vlr_and_extra_bytes": las(4, 7, LAS_POINTS, vlr=b"v" * 154, padding=3),
    "legacy_count_differs": las(4, 1, LAS_POINTS, legacy=3),
    "lying_count": las(4, 6, LAS_POINTS, count=4294967294),
    "short_record_length": las(2, 2, LAS_POINTS, record_length=25),
    "offset_past_end": las(3, 0, LAS_POINTS, offset_to_points=4000000000),
    "truncated": las(2, 3, LAS_POINTS)[:-5],
    "laz": las(2, 0x83, []),
})


# Vertex properties of every type, carried to the mesh with their names and types.
PLY_PROPERTIES = (b"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty char c\nproperty float y\n"
                  b"property float z\nproperty uchar red\nproperty short s\nproperty ushort intensity\nproperty int i\n"
                  b"property uint u\nproperty float confidence\nproperty double quality\nend_header\n"
                  b"0 -128 0 0 255 -32768 65535 -2147483648 4294967295 0.5 1e-300\n1 127 1 1 0 32767 0 2147483647 0 inf -0\n")

READERS = {
    "fuzz_read_ply": {"ascii": PLY_ASCII, "little_endian": ply_binary("<"), "big_endian": ply_binary(">"),
                      "strips": PLY_STRIPS, "truncated": ply_binary("<")[:-7],
                      "lying_count": PLY_ASCII.replace(b"element vertex 4", b"element vertex 4000000000"),
                      "zero_bytes": bytes(1024), "header_then_zero_bytes": b"ply\nformat ascii 1.0\n" + bytes(256),
                      "ascii_turns_binary": PLY_ASCII[:PLY_ASCII.index(b"1 0 0 0")] + BINARY_TAIL,
                      "repeated_property": PLY_REPEATED_PROPERTY,
                      "vertex_properties": PLY_PROPERTIES, "vertex_property_out_of_range": PLY_PROPERTIES.replace(b" 65535 ", b" 65536 ")},
    "fuzz_read_obj": {"tetrahedron": b"# comment\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1/1 4/1 3/1\nf 2//1 3//1 4//1\n",
                      "negative_indices": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0 1.0\nvt 0 0\nvn 0 0 1\nf -4 -3 -1 -2\ng part\nusemtl m\n",
                      "bad_index": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n",
                      "points_only": b"v 1e300 -0 5e-324\nv nan inf -inf\nv 0.1 0.2 0.3\n",
                      "turns_binary": b"# comment\nv 0 0 0\nv 1 0 0\n" + BINARY_TAIL},
    "fuzz_read_off": {"tetrahedron": b"OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
                      "quad_and_comments": b"OFF # header\n# a square\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
                      "colour": b"COFF\n3 1 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n",
                      "lying_counts": b"OFF\n99999999 99999999 0\n0 0 0\n",
                      "zero_bytes": bytes(512), "turns_binary": b"OFF\n3 1 0\n0 0 0\n" + BINARY_TAIL},
    "fuzz_read_xyz": {"points": b"0 0 0\n1 0 0\n0 1 0\n0 0 1\n",
                      "pts_with_count": b"3\n0,0,0\n1,0,0,255,255,255\n0 1 0 # comment\n// another\n",
                      "special_values": b"nan inf -inf\n1e308 -1e-320 -0\n",
                      "bad_line": b"0 0 0\n1 2\n",
                      "zero_bytes": bytes(512), "turns_binary": b"0 0 0\n1 0 0\n" + BINARY_TAIL},
    "fuzz_read_stl": {"ascii": b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                               b"facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n",
                      "binary": bytes(80) + struct.pack("<I", 2) + b"".join(
                          struct.pack("<12fH", 0, 0, 1, *a, *b, *c, 0)
                          for a, b, c in [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((1, 0, 0), (1, 1, 0), (0, 1, 0))]),
                      "lying_count": bytes(80) + struct.pack("<I", 1000000),
                      "ascii_turns_binary": b"solid t\nfacet normal 0 0 1\nouter loop\n" + BINARY_TAIL},
    "fuzz_read_las": LAS_SEEDS,
}

# fuzz_roundtrip: triangle count (4 bytes, modulo 301), three 4-byte corners per triangle, then points.
ROUNDTRIP = {"empty": b"", "one_triangle": struct.pack(">4I", 1, 0, 1, 2) + POINT_SETS["tetrahedron"]}
ROUNDTRIP.update({f"random_{k}": pseudo_random_bytes(1000 + k, 400) for k in range(4)})
ROUNDTRIP["specials"] = struct.pack(">I", 4) + pseudo_random_bytes(7, 48) + POINT_SETS["huge_and_tiny"] + POINT_SETS["nan"][3:]


def write(harness, seeds):
    directory = os.path.join(CORPUS, harness)
    os.makedirs(directory, exist_ok=True)
    for name in os.listdir(directory):
        if name.startswith("seed_"):
            os.remove(os.path.join(directory, name))
    for name, data in seeds.items():
        with open(os.path.join(directory, "seed_" + name), "wb") as f:
            f.write(data)


write("fuzz_reconstruct", RECONSTRUCT)
write("fuzz_delaunay", POINT_SETS)
write("fuzz_predicates", PREDICATES)
for harness, seeds in READERS.items():
    write(harness, seeds)
write("fuzz_roundtrip", ROUNDTRIP)
