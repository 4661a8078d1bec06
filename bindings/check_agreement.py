#!/usr/bin/env python3
"""Checks that the public header, the built library and both bindings declare the same C API:

  - the DBRG_API functions of dbrg.h, the dbrg_ symbols `nm -D` finds in the shared library, the
    FUNCTIONS table of the Python binding (bindings/python/dbrg/_capi.py) and the `pub fn dbrg_...`
    declarations of the Rust sys module (bindings/rust/src/sys.rs) are the same set, and each binding
    gives every function the header's number of parameters with the same kinds (integer widths,
    double, pointer) and the same kind of result;
  - the fields of every struct (dbrg_params, dbrg_stats, dbrg_points, dbrg_allocator) have the same
    names, order and kinds;
  - every enum constant and every DBRG_ #define has the same value, and the package versions
    (Cargo.toml, the Python package) are the header's.

--io does the same for the I/O library's interface: dbrg_io.h (DBRG_IO_API functions), libdbrg_io, the
Python declarations in bindings/python/dbrg/_io.py and the Rust ones in bindings/rust/src/io_sys.rs.

Prints every disagreement and exits 1 when there is one.

    check_agreement.py HEADER LIBRARY PYTHON_CAPI RUST_SYS CARGO_TOML [--io IO_HEADER IO_LIBRARY IO_PYTHON IO_RUST] [--nm NM]
    check_agreement.py --self-test ...the same arguments...

--self-test applies a series of single drifts (a renamed field, a reordered field, a missing function,
a changed enum value, ...) to copies of the files and fails unless the check catches every one.
Needs only the Python standard library (the Python binding's declarations use ctypes alone).
"""

import argparse
import importlib.util
import os
import re
import shutil
import subprocess
import sys
import tempfile

# ---------------------------------------------------------------------------------------------------
# Kinds: what must agree about a type across C, ctypes and Rust.
# ---------------------------------------------------------------------------------------------------

C_KINDS = {"uint32_t": "u32", "uint64_t": "u64", "size_t": "usize", "double": "f64", "int": "int32",
           "void": "void"}
RUST_KINDS = {"u32": "u32", "c_uint": "u32", "u64": "u64", "usize": "usize", "f64": "f64", "c_double": "f64",
              "c_int": "int32", "i32": "int32"}


def strip_c_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def c_kind(type_text, enums):
    type_text = type_text.replace("const", " ").strip()
    if "*" in type_text or type_text.endswith("_fn"):
        return "pointer"
    type_text = " ".join(type_text.split())
    if type_text in enums:
        return "int32"  # every dbrg enum has the size of an int
    return C_KINDS.get(type_text, "unknown C type %r" % type_text)


# ---------------------------------------------------------------------------------------------------
# The header
# ---------------------------------------------------------------------------------------------------

def split_top_level(text, separator):
    parts, depth, current = [], 0, ""
    for i, ch in enumerate(text):
        if ch in "(<[{":
            depth += 1
        elif ch in ")]}" or (ch == ">" and text[i - 1 : i] != "-"):  # the > of Rust's -> closes nothing
            depth -= 1
        if ch == separator and depth == 0:
            parts.append(current)
            current = ""
        else:
            current += ch
    if current.strip():
        parts.append(current)
    return [p.strip() for p in parts if p.strip()]


def c_declaration(text, enums):
    """'const dbrg_points* points' -> ('points', 'pointer'); 'void* (*allocate)(void* user, ...)' -> ('allocate', 'pointer')."""
    pointer = re.search(r"\(\s*\*\s*(\w+)\s*\)\s*\(", text)
    if pointer:
        return pointer.group(1), "pointer"
    match = re.match(r"(.*?)(\w+)\s*$", text, flags=re.S)
    return match.group(2), c_kind(match.group(1), enums)


def parse_header(path):
    raw = open(path).read()
    text = strip_c_comments(raw)
    header = {"enums": {}, "structs": {}, "functions": {}, "defines": {}}
    for name, body in re.findall(r"typedef\s+enum\s+(\w+)\s*\{(.*?)\}\s*\w+\s*;", text, flags=re.S):
        constants = {}
        for item in split_top_level(body, ","):
            key, value = (s.strip() for s in item.split("="))
            constants[key] = int(value, 0)
        header["enums"][name] = constants
    # Callback typedefs are passed like enums: one named scalar (a function pointer) per field.
    enums = set(header["enums"]) | set(re.findall(r"typedef\s+\w+\s*\(\s*\*\s*(\w+)\s*\)", text))
    for name, body in re.findall(r"typedef\s+struct\s+(\w+)\s*\{(.*?)\}\s*\w+\s*;", text, flags=re.S):
        header["structs"][name] = [c_declaration(field, enums) for field in split_top_level(body, ";")]
    code = "\n".join(line for line in text.splitlines() if not line.lstrip().startswith("#"))
    for result, name, params in re.findall(r"DBRG(?:_IO)?_API\s+(.*?)\b(dbrg_\w+)\s*\((.*?)\)\s*;", code, flags=re.S):
        params = [] if params.strip() == "void" else [c_declaration(p, enums)[1] for p in split_top_level(params, ",")]
        header["functions"][name] = (c_kind(result, enums), params)
    defines = {}
    for name, value in re.findall(r"^\s*#define\s+(DBRG_\w+)[ \t]+([^\n]+)$", raw, flags=re.M):
        value = value.strip()
        if name.endswith("_API") or value.startswith("__"):
            continue
        defines[name] = value
    for name, value in defines.items():
        header["defines"][name] = evaluate_c(value, defines)
    return header


def evaluate_c(expression, defines):
    if expression.startswith('"'):
        return expression.strip('"')
    while re.search(r"\bDBRG_\w+", expression):
        expression = re.sub(r"\b(DBRG_\w+)\b", lambda m: "(%s)" % defines[m.group(1)], expression)
    expression = expression.replace("(size_t)", "").replace("UINT32_MAX", "0xFFFFFFFF")
    expression = re.sub(r"\b(0[xX][0-9a-fA-F]+|\d+)[uUlL]+\b", r"\1", expression)
    if not re.fullmatch(r"[0-9a-fA-FxX()+\-*/ ]+", expression):
        raise ValueError("cannot evaluate #define value %r" % expression)
    return eval(expression, {"__builtins__": {}})


# ---------------------------------------------------------------------------------------------------
# The Python binding
# ---------------------------------------------------------------------------------------------------

def python_kind(ctype):
    import ctypes
    if ctype is None:
        return "void"
    if isinstance(ctype, type) and issubclass(ctype, (ctypes._Pointer, ctypes._CFuncPtr)) \
            or ctype in (ctypes.c_char_p, ctypes.c_void_p, ctypes.c_wchar_p):
        return "pointer"
    for kind, candidates in (("u32", (ctypes.c_uint32,)), ("u64", (ctypes.c_uint64,)), ("usize", (ctypes.c_size_t,)),
                             ("f64", (ctypes.c_double,)), ("int32", (ctypes.c_int,))):
        if ctype in candidates:
            return kind
    return "unknown ctypes type %r" % ctype


def parse_python(path):
    spec = importlib.util.spec_from_file_location("dbrg_capi_under_check", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    structs = {}
    for name in dir(module):
        value = getattr(module, name)
        if name.startswith("dbrg_") and isinstance(value, type) and hasattr(value, "_fields_"):
            if value._fields_:
                structs[name] = [(field, python_kind(ctype)) for field, ctype in value._fields_]
    functions = {name: (python_kind(result), [python_kind(a) for a in args])
                 for name, (result, args) in module.FUNCTIONS.items()}
    defines = {name: getattr(module, name) for name in dir(module) if re.fullmatch(r"DBRG_[A-Z0-9_]+", name)}
    return {"enums": module.ENUMS, "structs": structs, "functions": functions, "defines": defines}


# ---------------------------------------------------------------------------------------------------
# The Rust binding
# ---------------------------------------------------------------------------------------------------

def rust_kind(type_text, aliases):
    type_text = " ".join(type_text.split())
    if type_text.startswith(("*const", "*mut", "Option<", "&")) or re.fullmatch(r"dbrg_\w+_fn", type_text):
        return "pointer"
    if type_text in aliases:
        return "int32"
    return RUST_KINDS.get(type_text, "unknown Rust type %r" % type_text)


def evaluate_rust(expression, values):
    expression = expression.strip()
    if expression.startswith('"'):
        return expression.strip('"')
    expression = re.sub(r"\b(DBRG_\w+)\b", lambda m: "(%r)" % values[m.group(1)], expression)
    expression = expression.replace("u32::MAX", "0xFFFFFFFF")
    expression = re.sub(r"(?<=[0-9a-fA-F])_(?=[0-9a-fA-F])", "", expression)
    if not re.fullmatch(r"[0-9a-fA-FxX()+\-*/ ]+", expression):
        raise ValueError("cannot evaluate Rust constant %r" % expression)
    return eval(expression, {"__builtins__": {}})


def parse_rust(path):
    text = re.sub(r"//[^\n]*", "", open(path).read())
    aliases = set(re.findall(r"pub type (dbrg_\w+) = c_u?int;", text))
    enums, defines = {}, {}
    for name, type_name, value in re.findall(r"pub const (DBRG_\w+): ([\w&']+) = (.+?);", text):
        if type_name in aliases:
            enums.setdefault(type_name, {})[name] = evaluate_rust(value, defines)
        else:
            defines[name] = evaluate_rust(value, defines)
    structs = {}
    for name, body in re.findall(r"pub struct (dbrg_\w+)\s*\{(.*?)\n\}", text, flags=re.S):
        fields = []
        for field in split_top_level(body, ","):
            match = re.match(r"pub (?:r#)?(\w+)\s*:\s*(.+)$", field, flags=re.S)
            if match:
                fields.append((match.group(1), rust_kind(match.group(2), aliases)))
        if fields:
            structs[name] = fields
    functions = {}
    block = re.search(r'extern "C"\s*\{(.*)\n\}', text, flags=re.S).group(1)
    for name, params, result in re.findall(r"pub fn (dbrg_\w+)\s*\((.*?)\)\s*(?:->\s*([^;]+))?;", block, flags=re.S):
        kinds = [rust_kind(p.split(":", 1)[1], aliases) for p in split_top_level(params, ",")]
        functions[name] = (rust_kind(result, aliases) if result else "void", kinds)
    return {"enums": enums, "structs": structs, "functions": functions, "defines": defines}


# ---------------------------------------------------------------------------------------------------
# Comparison
# ---------------------------------------------------------------------------------------------------

def exported_functions(library, nm):
    run = subprocess.run([nm, "-D", "--defined-only", library], capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit("cannot list the symbols of %s: %s" % (library, run.stderr.strip()))
    output = run.stdout
    return {parts[2] for parts in (line.split() for line in output.splitlines())
            if len(parts) == 3 and parts[1] in "TW" and parts[2].startswith("dbrg_")}


def same_kind_in_ctypes(kind):
    """ctypes.c_size_t is ctypes.c_uint64 (or c_uint32) itself: the Python binding cannot tell them apart."""
    import ctypes
    if kind == "usize":
        return "u%d" % (8 * ctypes.sizeof(ctypes.c_size_t))
    return kind


def normalized(declarations, normalize):
    """Applies `normalize` to every kind in the functions and structs of a parsed declaration set."""
    result = dict(declarations)
    result["functions"] = {name: (normalize(r), [normalize(p) for p in params])
                           for name, (r, params) in declarations["functions"].items()}
    result["structs"] = {name: [(f, normalize(k)) for f, k in fields] for name, fields in declarations["structs"].items()}
    return result


def first_difference(ours, theirs):
    """Where two field lists part: 'field 20 is hole_triangles_delaunay (u32) in the header, hole_triangles_added (u32) here'."""
    for index, (mine, other) in enumerate(zip(ours, theirs)):
        if mine != other:
            return "field %d is %s (%s) in the header, %s (%s) here" % (index, mine[0], mine[1], other[0], other[1])
    if len(ours) > len(theirs):
        return "the header has %d more fields at the end: %s" % (len(ours) - len(theirs), [f for f, _ in ours[len(theirs):]])
    return "it has %d fields more than the header at the end: %s" % (len(theirs) - len(ours), [f for f, _ in theirs[len(ours):]])


def compare(header, binding, label, normalize=None):
    if normalize:
        header, binding = normalized(header, normalize), normalized(binding, normalize)
    problems = []
    missing = sorted(set(header["functions"]) - set(binding["functions"]))
    extra = sorted(set(binding["functions"]) - set(header["functions"]))
    if missing:
        problems.append("%s lacks functions the header declares: %s" % (label, ", ".join(missing)))
    if extra:
        problems.append("%s declares functions the header does not: %s" % (label, ", ".join(extra)))
    for name, signature in header["functions"].items():
        if name in binding["functions"] and binding["functions"][name] != signature:
            problems.append("%s: %s is (result, parameters) %s in the header but %s here"
                            % (label, name, signature, binding["functions"][name]))
    for name, fields in header["structs"].items():
        if name not in binding["structs"]:
            problems.append("%s has no struct %s" % (label, name))
        elif binding["structs"][name] != fields:
            problems.append("%s: struct %s differs from the header: %s"
                            % (label, name, first_difference(fields, binding["structs"][name])))
    for name in sorted(set(binding["structs"]) - set(header["structs"])):
        problems.append("%s declares struct %s, which the header has not" % (label, name))
    for name, constants in header["enums"].items():
        theirs = binding["enums"].get(name)
        if theirs is None:
            problems.append("%s has no enum %s" % (label, name))
        elif theirs != constants:
            differing = sorted(set(constants.items()) ^ set(theirs.items()))
            problems.append("%s: enum %s differs from the header in (name, value) %s" % (label, name, differing))
    for name in sorted(set(binding["enums"]) - set(header["enums"])):
        problems.append("%s declares enum %s, which the header has not" % (label, name))
    for name, value in header["defines"].items():
        if name not in binding["defines"]:
            problems.append("%s lacks #define %s (= %r)" % (label, name, value))
        elif binding["defines"][name] != value:
            problems.append("%s: %s is %r in the header but %r here" % (label, name, value, binding["defines"][name]))
    return problems


def check(header_path, library, python_capi, rust_sys, cargo_toml, nm, quiet=False):
    """cargo_toml: None for a header without the package version (dbrg_io.h)."""
    header = parse_header(header_path)
    problems = []
    # dbrg_io.h has opaque types only: a struct a binding declares is still compared with none.
    if not header["functions"] or not header["enums"]:
        problems.append("found nothing to compare in %s (did its layout change?)" % header_path)
    exported = exported_functions(library, nm)
    for name in sorted(set(header["functions"]) - exported):
        problems.append("the library does not export %s, which the header declares" % name)
    for name in sorted(exported - set(header["functions"])):
        problems.append("the library exports %s, which the header does not declare" % name)
    problems += compare(header, parse_python(python_capi), "the Python binding", same_kind_in_ctypes)
    problems += compare(header, parse_rust(rust_sys), "the Rust binding")
    if cargo_toml:
        cargo_version = re.search(r'^version\s*=\s*"([^"]+)"', open(cargo_toml).read(), flags=re.M)
        if not cargo_version or cargo_version.group(1) != header["defines"]["DBRG_VERSION_STRING"]:
            problems.append("Cargo.toml's version %s is not the header's %s"
                            % (cargo_version and cargo_version.group(1), header["defines"]["DBRG_VERSION_STRING"]))
    if not quiet:
        print("compared %d functions, %d structs (%d fields), %d enums, %d defines across %s, %s, "
              "the Python binding and the Rust binding" % (
                  len(header["functions"]), len(header["structs"]),
                  sum(len(f) for f in header["structs"].values()), len(header["enums"]), len(header["defines"]),
                  os.path.basename(header_path), os.path.basename(library)))
    return problems


# ---------------------------------------------------------------------------------------------------
# Self-test: each single drift must be caught.
# ---------------------------------------------------------------------------------------------------

DRIFTS = [
    # (file, what to replace, replacement, description)
    ("rust", "    pub boundary_factor: f64,\n    pub boundary_mean:", "    pub boundary_mean_: f64,\n    pub boundary_mean:",
     "a renamed field in Rust's dbrg_params"),
    ("rust", "    pub seconds_sort: f64,\n    pub seconds_delaunay: f64,", "    pub seconds_delaunay: f64,\n    pub seconds_sort: f64,",
     "two fields of Rust's dbrg_stats swapped"),
    ("rust", "    pub holes_found: u32,", "    pub holes_found: u64,", "a field of Rust's dbrg_stats widened"),
    ("rust", "    pub fn dbrg_mesh_point_count(mesh: *const dbrg_mesh) -> u32;\n", "", "a function missing from Rust"),
    ("rust", "pub fn dbrg_mesh_boundary_loop(mesh: *const dbrg_mesh, loop_: u32, out_count: *mut u32)",
     "pub fn dbrg_mesh_boundary_loop(mesh: *const dbrg_mesh, loop_: u32)", "a parameter missing from a Rust function"),
    ("rust", "pub const DBRG_ERR_CANCELLED: dbrg_status = 8;", "pub const DBRG_ERR_CANCELLED: dbrg_status = 9;",
     "a status value changed in Rust"),
    ("rust", "pub const DBRG_NO_NEIGHBOR: u32 = u32::MAX;", "pub const DBRG_NO_NEIGHBOR: u32 = 0;", "a #define changed in Rust"),
    ("python", '        ("peak_bytes", c_size_t),\n', "", "a field missing from Python's dbrg_stats"),
    ("python", '        ("fill_holes", c_uint32),\n        ("max_hole_edges", c_uint32),',
     '        ("max_hole_edges", c_uint32),\n        ("fill_holes", c_uint32),', "two fields of Python's dbrg_params swapped"),
    ("python", '        ("count", c_size_t),', '        ("count", c_uint32),', "a field of Python's dbrg_points narrowed"),
    ("python", '    "dbrg_tetrahedralization_unique_point_count": (c_uint32, [tets_p]),\n', "", "a function missing from Python"),
    ("python", '    "dbrg_mesh_stats": (c_enum, [mesh_p, POINTER(dbrg_stats)]),', '    "dbrg_mesh_stats": (c_enum, [mesh_p]),',
     "a parameter missing from a Python function"),
    ("python", '        "DBRG_STAGE_OUTPUT": 5,', '        "DBRG_STAGE_OUTPUT": 6,', "a stage value changed in Python"),
    ("python", "DBRG_VERSION_MINOR = 5", "DBRG_VERSION_MINOR = 6", "the version changed in Python"),
    ("header", "    uint32_t pinch_faces_removed;", "    uint32_t pinch_faces_removed;\n    uint32_t new_counter;",
     "a field added to the header's dbrg_stats"),
    ("header", "DBRG_API uint32_t dbrg_mesh_point_count(const dbrg_mesh* mesh);",
     "DBRG_API uint32_t dbrg_mesh_point_count(const dbrg_mesh* mesh);\nDBRG_API uint32_t dbrg_mesh_new_thing(const dbrg_mesh* mesh);",
     "a function added to the header only (the library does not export it)"),
    ("header", "    DBRG_STAGE_OUTPUT = 5", "    DBRG_STAGE_OUTPUT = 5,\n    DBRG_STAGE_NEW = 6", "an enum constant added to the header"),
    ("cargo", 'version = "', 'version = "9', "Cargo.toml's version"),
    ("io_rust", "pub const DBRG_IO_ERR_FILE: dbrg_io_status = 2;", "pub const DBRG_IO_ERR_FILE: dbrg_io_status = 3;",
     "an I/O status value changed in Rust"),
    ("io_rust", "    pub fn dbrg_io_points_count(points: *const dbrg_io_points) -> u32;\n", "",
     "an I/O function missing from Rust"),
    ("io_rust", "        normals: *const f32,\n        message: *mut c_char,", "        message: *mut c_char,",
     "a parameter missing from a Rust I/O function"),
    ("io_python", '        "DBRG_IO_UINT16": 3,', '        "DBRG_IO_UINT16": 4,', "a value type changed in Python"),
    ("io_python", '    "dbrg_io_points_attribute_type": (c_int, [c_void_p, c_uint32]),',
     '    "dbrg_io_points_attribute_type": (c_int, [c_void_p]),', "a parameter missing from a Python I/O function"),
    ("io_header", "    DBRG_IO_FLOAT64 = 7", "    DBRG_IO_FLOAT64 = 7,\n    DBRG_IO_FLOAT16 = 8",
     "a value type added to dbrg_io.h"),
    ("io_header", "DBRG_IO_API void dbrg_io_points_destroy(dbrg_io_points* points);",
     "DBRG_IO_API void dbrg_io_points_destroy(dbrg_io_points* points);\nDBRG_IO_API void dbrg_io_new_thing(void);",
     "a function added to dbrg_io.h only (libdbrg_io does not export it)"),
]


def self_test(paths, io_paths, nm):
    header, library, python_capi, rust_sys, cargo_toml = paths
    failures = []
    with tempfile.TemporaryDirectory(prefix="dbrg-agreement-") as scratch:
        originals = {"header": header, "python": python_capi, "rust": rust_sys, "cargo": cargo_toml}
        if io_paths:
            originals.update(zip(["io_header", "io_python", "io_rust"], [io_paths[0]] + io_paths[2:]))
        copies = {key: os.path.join(scratch, key + "_" + os.path.basename(path)) for key, path in originals.items()}

        def reset():
            for key, path in originals.items():
                shutil.copy(path, copies[key])

        def run():
            problems = check(copies["header"], library, copies["python"], copies["rust"], copies["cargo"], nm, quiet=True)
            if io_paths:
                problems += check(copies["io_header"], io_paths[1], copies["io_python"], copies["io_rust"], None, nm,
                                  quiet=True)
            return problems

        reset()
        baseline = run()
        if baseline:
            failures.append("the unchanged files already disagree: %s" % baseline)
        drifts = [drift for drift in DRIFTS if drift[0] in originals]
        for key, old, new, description in drifts:
            reset()
            text = open(copies[key]).read()
            if old not in text:
                failures.append("cannot apply drift %r: its text is not in %s" % (description, originals[key]))
                continue
            open(copies[key], "w").write(text.replace(old, new, 1))
            try:
                problems = run()
            except Exception as error:  # a parse failure counts as caught, but say so
                problems = ["the check failed with %r" % error]
            if problems:
                print("caught: %s\n    -> %s" % (description, problems[0].splitlines()[0]))
            else:
                failures.append("not caught: %s" % description)
    for failure in failures:
        print("SELF-TEST FAILURE:", failure)
    print("self-test: %d drifts, %d caught" % (len(drifts), len(drifts) - sum(f.startswith("not caught") for f in failures)))
    return 1 if failures else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--self-test", action="store_true")
    parser.add_argument("--nm", default="nm")
    parser.add_argument("header")
    parser.add_argument("library")
    parser.add_argument("python_capi")
    parser.add_argument("rust_sys")
    parser.add_argument("cargo_toml")
    parser.add_argument("--io", nargs=4, metavar=("IO_HEADER", "IO_LIBRARY", "IO_PYTHON", "IO_RUST"))
    args = parser.parse_args()
    paths = (args.header, args.library, args.python_capi, args.rust_sys, args.cargo_toml)
    if args.self_test:
        return self_test(paths, args.io, args.nm)
    problems = check(*paths, nm=args.nm)
    if args.io:
        problems += check(*args.io, None, nm=args.nm)
    for problem in problems:
        print("DISAGREEMENT:", problem)
    if not problems:
        print("the header, the library and both bindings agree")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
