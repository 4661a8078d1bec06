// Compacting a mesh's vertices to those its triangles use.
#include "io/unused_vertices.h"

#include <cstring>

namespace dbrg::io {

std::vector<uint32_t> drop_unused_vertices(MeshData& mesh) {
    const size_t vertex_count = mesh.vertex_count();
    std::vector<uint32_t> old_to_new(vertex_count, DROPPED_VERTEX);
    for (uint32_t vertex : mesh.triangles) old_to_new[vertex] = 0;
    uint32_t kept = 0;
    for (size_t v = 0; v < vertex_count; ++v) {
        if (old_to_new[v] == DROPPED_VERTEX) continue;
        old_to_new[v] = kept;
        // Moving down in place: a kept vertex's new index is never above its old one.
        for (size_t k = 0; k < 3; ++k) {
            mesh.positions[3 * size_t(kept) + k] = mesh.positions[3 * v + k];
            if (!mesh.normals.empty()) mesh.normals[3 * size_t(kept) + k] = mesh.normals[3 * v + k];
        }
        for (VertexProperty& property : mesh.properties) {
            const size_t size = value_size(property.type);
            std::memmove(&property.bytes[kept * size], &property.bytes[v * size], size);
        }
        ++kept;
    }
    mesh.positions.resize(3 * size_t(kept));
    if (!mesh.normals.empty()) mesh.normals.resize(3 * size_t(kept));
    for (VertexProperty& property : mesh.properties) property.bytes.resize(kept * value_size(property.type));
    for (uint32_t& vertex : mesh.triangles) vertex = old_to_new[vertex];
    return old_to_new;
}

} // namespace dbrg::io
