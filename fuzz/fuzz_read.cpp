// Fuzz target: one mesh reader (the build names it with -DFUZZ_READ_FORMAT=ply_binary, obj, off, xyz or
// stl) on arbitrary bytes. A failed read leaves the mesh empty and says why; a successful one gives whole
// triangles over existing vertices that the mesh report and the surface distance accept; and whatever
// the header claims, the reader holds no more than a small multiple of the input's size.
#include <stddef.h>
#include <stdint.h>

#include <cmath>
#include <string>

#include "allocation_meter.h"
#include "fuzz_check.h"
#include "io/mesh_io.h"
#include "io/mesh_report.h"
#include "io/surface_distance.h"

using namespace dbrg;

namespace {

// Doubles from one-digit numbers (8 bytes from 2 characters), 32-bit indices from the same, fans that
// make up to 3 indices per corner, and a vector's doubling: 64 times the input is ample.
size_t memory_allowance(size_t input_size) { return 64 * input_size + (64 << 10); }

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    io::MeshData mesh;
    fuzz::reset_peak_bytes();
    const io::IoStatus status = io::read_mesh_buffer(data, size, io::MeshFormat::FUZZ_READ_FORMAT, mesh);
    const size_t peak = fuzz::peak_bytes();
    FUZZ_CHECK_WHY(peak <= memory_allowance(size),
                   ("the reader held " + std::to_string(peak) + " bytes for " + std::to_string(size) + " bytes of input").c_str());
    if (!status) {
        FUZZ_CHECK(!status.message.empty());
        FUZZ_CHECK(mesh.positions.empty() && mesh.triangles.empty() && !mesh.has_faces);
        return 0;
    }
    FUZZ_CHECK(mesh.positions.size() % 3 == 0 && mesh.triangles.size() % 3 == 0);
    for (uint32_t v : mesh.triangles) FUZZ_CHECK(v < mesh.vertex_count());
    if (!mesh.triangles.empty()) FUZZ_CHECK(mesh.has_faces);

    // The report takes any valid mesh, however tangled: bow-ties, repeated faces, NaN corners.
    io::MeshReport report;
    FUZZ_CHECK(io::make_mesh_report(mesh, report).ok);
    FUZZ_CHECK(report.faces == mesh.triangle_count());
    FUZZ_CHECK(report.vertices + report.vertices_isolated == mesh.vertex_count());
    FUZZ_CHECK(!io::to_json(report).empty());

    // So does the surface distance, here between the first and second half of the triangles: a measure or
    // none, never a NaN, a negative or a hang.
    io::MeshData first = mesh, second = mesh;
    const size_t half = 3 * (mesh.triangle_count() / 2);
    first.triangles.resize(half);
    second.triangles.erase(second.triangles.begin(), second.triangles.begin() + long(half));
    for (const auto& d : {io::surface_distance(first, second), io::surface_distance(second, first)}) {
        if (!d) continue;
        FUZZ_CHECK(std::isfinite(d->max) && d->mean >= 0 && d->mean <= d->max);
    }
    return 0;
}
