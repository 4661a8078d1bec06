// Fuzz target: every writer, then the matching reader, on produced meshes (grid, special and raw
// coordinates; any triangles over the vertices, repeated corners included). What comes back must be what
// went in: positions bit for bit (NaN as NaN) and the same triangles, except that XYZ keeps the points
// only and STL keeps each triangle's corners as float32, joined by position.
#include <string.h>

#include <string>
#include <vector>

#include "fuzz_check.h"
#include "fuzz_input.h"
#include "io/mesh_io.h"
#include "point_producer.h"

using namespace dbrg;
using namespace dbrg::fuzz;

namespace {

const size_t MAX_VERTICES = 2000;
const size_t MAX_TRIANGLES = 300;

bool same_value(double a, double b) {
    return (a != a && b != b) || memcmp(&a, &b, sizeof a) == 0;
}

bool same_positions(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!same_value(a[i], b[i])) return false;
    }
    return true;
}

// STL: each corner of each triangle, as float32, at the same place (-0 and +0 are one place there).
bool same_stl_corners(const io::MeshData& written, const io::MeshData& read) {
    if (read.triangles.size() != written.triangles.size()) return false;
    for (size_t i = 0; i < written.triangles.size(); ++i) {
        for (size_t k = 0; k < 3; ++k) {
            const double expected = static_cast<float>(written.positions[3 * size_t(written.triangles[i]) + k]);
            const double got = read.positions[3 * size_t(read.triangles[i]) + k];
            if (!same_value(expected, got) && !(expected == 0.0 && got == 0.0)) return false;
        }
    }
    return true;
}

void check_round_trip(const io::MeshData& mesh, io::MeshFormat format) {
    const std::string name = io::format_name(format);
    std::string bytes;
    const io::IoStatus written = io::write_mesh_buffer(mesh, format, bytes);
    FUZZ_CHECK_WHY(written.ok, (name + ": " + written.message).c_str());
    io::MeshData back;
    const io::IoStatus read = io::read_mesh_buffer(bytes.data(), bytes.size(), format, back);
    FUZZ_CHECK_WHY(read.ok, (name + ": " + read.message).c_str());
    switch (format) {
    case io::MeshFormat::xyz:
        FUZZ_CHECK_WHY(same_positions(back.positions, mesh.positions), name.c_str());
        FUZZ_CHECK(back.triangles.empty());
        break;
    case io::MeshFormat::stl: FUZZ_CHECK_WHY(same_stl_corners(mesh, back), name.c_str()); break;
    default:
        FUZZ_CHECK_WHY(same_positions(back.positions, mesh.positions), name.c_str());
        FUZZ_CHECK_WHY(back.triangles == mesh.triangles, name.c_str());
        break;
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzInput input(data, size);
    // Triangle corners are drawn first and reduced modulo the vertex count once the points are known.
    std::vector<uint32_t> corners(3 * input.below(MAX_TRIANGLES + 1));
    for (uint32_t& corner : corners) corner = input.u32();
    const PointSet points = produce_points(input, MAX_VERTICES);

    io::MeshData mesh;
    mesh.positions = points.xyz;
    mesh.has_faces = true;
    if (points.count() > 0) {
        for (uint32_t corner : corners) mesh.triangles.push_back(corner % points.count());
    }
    const io::MeshFormat formats[] = {io::MeshFormat::ply_binary, io::MeshFormat::ply_ascii, io::MeshFormat::obj,
                                      io::MeshFormat::off, io::MeshFormat::xyz, io::MeshFormat::stl};
    for (io::MeshFormat format : formats) check_round_trip(mesh, format);
    return 0;
}
