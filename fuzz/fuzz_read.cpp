// Fuzz target: one mesh reader (the build names it with -DFUZZ_READ_FORMAT=ply_binary, obj, off, xyz, stl
// or las) on arbitrary bytes. A failed read leaves the mesh empty and says why; a successful one gives whole
// triangles over existing vertices and one value per vertex in each vertex property that the mesh report and the surface distance accept; whatever the
// header claims, the reader holds no more than a small multiple of the input's size; and the bytes read
// in small pieces, as from a file or a pipe, give the same mesh and message.
#include <stddef.h>
#include <stdint.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

#include "allocation_meter.h"
#include "fuzz_check.h"
#include "io/formats.h"
#include "io/mesh_io.h"
#include "measure/mesh_report.h"
#include "measure/surface_distance.h"

using namespace dbrg;

namespace {

// Doubles from one-digit numbers (8 bytes from 2 characters), 32-bit indices from the same, fans that
// make up to 3 indices per corner, and a vector's doubling: 64 times the input is ample.
const io::MeshFormat FORMAT = io::MeshFormat::FUZZ_READ_FORMAT;

size_t memory_allowance(size_t input_size) { return 64 * input_size + (64 << 10); }

bool same_mesh(const io::MeshData& a, const io::MeshData& b) {
    const bool same_positions = a.positions.size() == b.positions.size() &&
        (a.positions.empty() || std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(double)) == 0);
    bool same_properties = a.properties.size() == b.properties.size();
    for (size_t i = 0; same_properties && i < a.properties.size(); ++i) {
        same_properties = a.properties[i].name == b.properties[i].name && a.properties[i].type == b.properties[i].type &&
                          a.properties[i].bytes == b.properties[i].bytes;
    }
    return same_positions && same_properties && a.triangles == b.triangles && a.has_faces == b.has_faces &&
           a.non_finite_at == b.non_finite_at;
}

// Reads the input through a source that hands it out in pieces of 1 to 13 bytes (sizes set by the input
// itself) into a 16-byte first buffer, so that lines, tokens and values straddle refills.
io::IoStatus read_in_pieces(const uint8_t* data, size_t size, bool size_known, io::MeshData& out) {
    size_t at = 0;
    io::ByteSource source(
        [&](char* destination, size_t capacity) {
            const size_t wanted = 1 + (at < size ? data[at] % 13 : 0);
            const size_t piece = std::min({capacity, size - at, wanted});
            if (piece > 0) std::memcpy(destination, data + at, piece);
            at += piece;
            return piece;
        },
        size_known ? std::optional<uint64_t>(size) : std::nullopt, 16);
    return io::read_mesh_source(source, FORMAT, out);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    io::MeshData mesh;
    fuzz::reset_peak_bytes();
    const io::IoStatus status = io::read_mesh_buffer(data, size, FORMAT, mesh);
    const size_t peak = fuzz::peak_bytes();
    FUZZ_CHECK_WHY(peak <= memory_allowance(size),
                   ("the reader held " + std::to_string(peak) + " bytes for " + std::to_string(size) + " bytes of input").c_str());

    // With the size known (a file), the same mesh and message. Without it (a pipe), the same mesh or
    // failure: a lying count shows only when the data runs out, and STL can no longer tell ascii by size.
    io::MeshData piecewise;
    const io::IoStatus piecewise_status = read_in_pieces(data, size, true, piecewise);
    FUZZ_CHECK(piecewise_status.ok == status.ok);
    FUZZ_CHECK_WHY(piecewise_status.message == status.message, (status.message + " | in pieces: " + piecewise_status.message).c_str());
    FUZZ_CHECK(same_mesh(piecewise, mesh));
    if (FORMAT != io::MeshFormat::stl) {
        const io::IoStatus unsized_status = read_in_pieces(data, size, false, piecewise);
        FUZZ_CHECK(unsized_status.ok == status.ok);
        FUZZ_CHECK(same_mesh(piecewise, mesh));
    }
    if (!status) {
        FUZZ_CHECK(!status.message.empty());
        FUZZ_CHECK(mesh.positions.empty() && mesh.triangles.empty() && mesh.properties.empty() && !mesh.has_faces);
        return 0;
    }
    FUZZ_CHECK(mesh.positions.size() % 3 == 0 && mesh.triangles.size() % 3 == 0);
    for (const io::VertexProperty& property : mesh.properties) FUZZ_CHECK(property.size() == mesh.vertex_count());
    for (uint32_t v : mesh.triangles) FUZZ_CHECK(v < mesh.vertex_count());
    if (!mesh.triangles.empty()) FUZZ_CHECK(mesh.has_faces);

    // The report takes any valid mesh, however tangled: bow-ties, repeated faces, NaN corners.
    measure::MeshReport report;
    FUZZ_CHECK(measure::make_mesh_report(mesh, report).ok);
    FUZZ_CHECK(report.faces == mesh.triangle_count());
    FUZZ_CHECK(report.vertices + report.vertices_isolated == mesh.vertex_count());
    FUZZ_CHECK(!measure::to_json(report).empty());

    // So does the surface distance, here between the first and second half of the triangles: a measure or
    // none, never a NaN, a negative or a hang.
    io::MeshData first = mesh, second = mesh;
    const size_t half = 3 * (mesh.triangle_count() / 2);
    first.triangles.resize(half);
    second.triangles.erase(second.triangles.begin(), second.triangles.begin() + long(half));
    for (const auto& d : {measure::surface_distance(first, second), measure::surface_distance(second, first)}) {
        if (!d) continue;
        FUZZ_CHECK(std::isfinite(d->max) && d->mean >= 0 && d->mean <= d->max);
    }
    return 0;
}
