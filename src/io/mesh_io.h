// Reading and writing point sets and triangle meshes: PLY, OBJ, OFF, XYZ/PTS and STL.
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

struct MeshData {
    std::vector<double> positions;    // x, y, z of vertex 0, then vertex 1, ...
    std::vector<uint32_t> triangles;  // three vertex indices per triangle, each < vertex_count()
    // nx, ny, nz per vertex, or empty. PLY and OBJ write them (PLY nx/ny/nz, OBJ vn); the PLY reader
    // fills them when the vertices have all three, other readers leave them empty.
    std::vector<float> normals;
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
};

// The outcome of a read or write: ok, or a one-line message naming the problem.
struct IoStatus {
    bool ok = true;
    std::string message;

    static IoStatus success() { return {}; }
    static IoStatus failure(std::string message) { return {false, std::move(message)}; }
    explicit operator bool() const { return ok; }
};

// The format a file name's extension stands for (.ply .obj .off .xyz .pts .stl, any letter case), or
// nullopt. .ply gives ply_binary; a reader given either PLY format detects the actual one from the header.
std::optional<MeshFormat> format_from_path(std::string_view path);

// The lower-case name of a format ("ply_binary", "obj", ...).
const char* format_name(MeshFormat format);

// Reads the file at `path`, choosing the reader by its extension. The file is parsed as it is read, so a
// pipe or device works too and input that is not the format fails on its first bad bytes; binary formats
// read no further than their header declares. An endless stream of valid data ends with "out of memory",
// as any input too large for memory does. A regular file gives read_mesh_buffer's results and messages
// for its bytes; a pipe's size is unknown, so a header's lying counts show only when the data runs out.
// On failure `out` is left empty and the message begins with the path.
IoStatus read_mesh(const std::string& path, MeshData& out);

// Reads `size` bytes at `data` as `format`. On failure `out` is left empty. data may be NULL when size is 0.
// Faces are triangulated as fans; faces with fewer than three corners are errors; PLY triangle strips
// are decoded, dropping the zero-area triangles strips use to join their pieces.
IoStatus read_mesh_buffer(const void* data, size_t size, MeshFormat format, MeshData& out);

// Writes `mesh` to `path` as `format`, through write_file (file_output.h): a failed write leaves the file
// that was there untouched. Positions round-trip exactly through every format except STL, which stores
// float32 (exact for coordinates that are floats already). XYZ writes the points only; normals go to PLY
// (float nx ny nz) and OBJ (vn lines, faces as v//vn) and round-trip exactly through PLY.
IoStatus write_mesh(const std::string& path, const MeshData& mesh, MeshFormat format);

// As write_mesh, with the format chosen by the extension of `path`.
IoStatus write_mesh(const std::string& path, const MeshData& mesh);

// Writes `mesh` as `format` into `out`, replacing its contents.
IoStatus write_mesh_buffer(const MeshData& mesh, MeshFormat format, std::string& out);

} // namespace dbrg::io
