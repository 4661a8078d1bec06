// Reading and writing point sets and triangle meshes: PLY, OBJ, OFF, XYZ/PTS and STL; reading LAS point clouds.
//
// Errors come back as an IoStatus value whose message names the problem and where it is (a line number
// for text formats, a byte offset for binary ones). Hostile input never crashes, never hangs and never
// makes the reader allocate more than a small multiple of the input's size, whatever its header claims.
// Text formats refuse a zero byte (binary data, not text) and lines longer than 16 MiB; a PLY header may
// take at most 1 MiB. Coordinates are returned exactly as stored, NaN and infinity included: judging them
// is the caller's job, and MeshData::non_finite_at tells it where the first such vertex is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dbrg::io {

// The type of a per-vertex value, as PLY has them (char, uchar, short, ushort, int, uint, float, double),
// in the order of dbrg_io_value_type's values (dbrg_io.h), which io_api.cpp relies on.
enum class ValueType : uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

// Bytes per value of `type`.
size_t value_size(ValueType type);

// A per-vertex value besides position and normal: a colour channel, an intensity, a confidence. Carried
// from the readers that know them (PLY, LAS) to the PLY writer under the same name and type. A per-face
// value (MeshData::face_properties) is held the same way, one value per triangle.
struct VertexProperty {
    std::string name;
    ValueType type = ValueType::float32;
    // value_size(type) bytes per vertex, in the machine's byte order: a uint8 colour costs one byte a point.
    std::vector<unsigned char> bytes;

    size_t size() const { return bytes.size() / value_size(type); }
    // The value of `vertex` (every type's values are exact as doubles).
    double value(size_t vertex) const;
    // Appends `value` as `type`: a float32 takes the nearest float (infinity beyond its range); an integer
    // type takes only whole numbers in its range, else nothing is appended and the result is false.
    bool append(double value);
};

struct MeshData {
    std::vector<double> positions;    // x, y, z of vertex 0, then vertex 1, ...
    std::vector<uint32_t> triangles;  // three vertex indices per triangle, each < vertex_count()
    // nx, ny, nz per vertex, or empty. PLY and OBJ write them (PLY nx/ny/nz, OBJ vn); the PLY reader
    // fills them when the vertices have all three, other readers leave them empty.
    std::vector<float> normals;
    // Other per-vertex values, each with one value per vertex: the PLY reader fills them from the vertex
    // element's other scalar properties, the LAS reader with intensity and colour; the PLY writer writes
    // them after x y z and the normals. Other writers leave them out.
    std::vector<VertexProperty> properties;
    // Per-triangle values, each with one value per triangle: the PLY reader fills them from the face
    // element's scalar properties (a polygon's value repeated for each triangle of its fan; tristrips have
    // none), the PLY writer writes them after vertex_indices. Other formats leave them out.
    std::vector<VertexProperty> face_properties;
    bool has_faces = false;           // the file declares faces (a PLY face element, OBJ f lines, ...), even zero
    // Where the first NaN or infinite vertex coordinate is, in the words of the readers' messages ("line 7"
    // in a text format, "byte offset 1234" in a binary one), or empty when all are finite: a caller that
    // refuses such a point can then say where it is in the file. Other values (normals, colours) are not judged.
    std::string non_finite_at;

    size_t vertex_count() const { return positions.size() / 3; }
    size_t triangle_count() const { return triangles.size() / 3; }
};

enum class MeshFormat {
    ply_binary,  // binary little-endian when writing; reading accepts any PLY
    ply_ascii,   // ascii when writing; reading accepts any PLY
    obj,
    off,
    xyz,         // also .pts; points only
    stl,         // binary when writing; reading accepts binary and ascii STL
    las,         // reading only: LAS 1.0 to 1.4 point records, uncompressed
};

// The outcome of a read or write: ok, or a one-line message naming the problem.
struct IoStatus {
    bool ok = true;
    std::string message;

    static IoStatus success() { return {}; }
    static IoStatus failure(std::string message) { return {false, std::move(message)}; }
    explicit operator bool() const { return ok; }
};

// The format a file name's extension stands for (.ply .obj .off .xyz .pts .stl .las, any letter case), or
// nullopt. .ply gives ply_binary; a reader given either PLY format detects the actual one from the header.
std::optional<MeshFormat> format_from_path(std::string_view path);

// The lower-case name of a format ("ply_binary", "obj", ...).
const char* format_name(MeshFormat format);

// Reads the file at `path`, choosing the reader by its extension. The file is parsed as it is read, so a
// pipe or device works too and input that is not the format fails on its first bad bytes; binary formats
// read no further than their header declares. An endless stream of valid data ends with "out of memory",
// as any input too large for memory does. A regular file gives read_mesh_buffer's results and messages
// for its bytes; a pipe's size is unknown, so a header's lying counts show only when the data runs out.
// On failure `out` is left empty and the message begins with the path. A .laz file (compressed LAS) is
// refused with a message saying to decompress it first.
IoStatus read_mesh(const std::string& path, MeshData& out);

// Reads `size` bytes at `data` as `format`. On failure `out` is left empty. data may be NULL when size is 0.
// Faces are triangulated as fans; faces with fewer than three corners are errors; PLY triangle strips
// are decoded, dropping the zero-area triangles strips use to join their pieces.
IoStatus read_mesh_buffer(const void* data, size_t size, MeshFormat format, MeshData& out);

// Writes `mesh` to `path` as `format`, through write_file (file_output.h): a failed write leaves the file
// that was there untouched. Positions round-trip exactly through every format except STL, which stores
// float32 (exact for coordinates that are floats already). XYZ writes the points only; normals go to PLY
// (float nx ny nz) and OBJ (vn lines, faces as v//vn) and round-trip exactly through PLY, as do the vertex
// properties and face properties, which only PLY writes. Refused: a normal or property array whose length
// does not match the vertices (the triangles for a face property), a property name that is empty, holds a
// blank, repeats or is one of x y z nx ny nz (vertex_indices vertex_index for a face property).
IoStatus write_mesh(const std::string& path, const MeshData& mesh, MeshFormat format);

// As write_mesh, with the format chosen by the extension of `path`.
IoStatus write_mesh(const std::string& path, const MeshData& mesh);

// Writes `mesh` as `format` into `out`, replacing its contents.
IoStatus write_mesh_buffer(const MeshData& mesh, MeshFormat format, std::string& out);

} // namespace dbrg::io
