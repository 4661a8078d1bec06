// Surface output: S handed over as the caller sees it, in the caller's point indexing (see surface_output.h).
#include "surface_output.h"

#include "core/progress_span.h"
#include "core/status.h"
#include "core/vec3.h"

static_assert(dbrg::FACE_FILLED == DBRG_FACE_FILLED, "the face flags are handed over as they are");

namespace dbrg {
namespace {

// Which components to turn over: the closed ones (no boundary half-edge) whose signed volume is negative.
dbrg_status find_inward_components(const Surface& surface, const ConditionedPoints& points, const ProgressSpan& progress,
                                   Array<uint32_t>& face_component, Array<uint8_t>& flip) {
    Context& context = progress.context();
    const uint32_t components = surface.label_components(face_component);
    if (components == NO_FACE) return context.fail_out_of_memory();
    Array<double> volume(context.memory);
    Array<uint8_t> open(context.memory);
    if (!volume.resize(components, 0.0) || !open.resize(components, 0) || !flip.resize(components, 0)) {
        return context.fail_out_of_memory();
    }
    for (uint32_t f = 0; f < surface.face_count(); ++f) {
        DBRG_PROPAGATE(progress.report_at(f, surface.face_count()));
        const uint32_t k = face_component[f];
        if (k == NO_FACE) continue;
        for (uint32_t i = 0; i < 3; ++i) open[k] |= surface.is_boundary(3 * f + i) ? 1 : 0;
        const Vec3 a = load_vec3(points.point(surface.corner(f, 0)));
        const Vec3 b = load_vec3(points.point(surface.corner(f, 1)));
        const Vec3 c = load_vec3(points.point(surface.corner(f, 2)));
        volume[k] += dot(a, cross(b, c));
    }
    for (uint32_t k = 0; k < components; ++k) flip[k] = !open[k] && volume[k] < 0;
    context.stats.components = components;
    return DBRG_OK;
}

} // namespace

dbrg_status emit_surface(const Surface& surface, const ConditionedPoints& conditioned, Context& context,
                         SurfaceResult& result) {
    const ProgressSpan progress(context, DBRG_STAGE_OUTPUT);
    DBRG_PROPAGATE(progress.report(0, 1));
    const uint32_t faces = surface.face_count();
    Array<uint32_t> face_component(context.memory);
    Array<uint8_t> flip(context.memory);
    DBRG_PROPAGATE(find_inward_components(surface, conditioned, progress.part(0.0, 0.4), face_component, flip));
    if (!result.triangles.reserve(3 * size_t(surface.live_face_count())) ||
        !result.face_flags.reserve(surface.live_face_count())) {
        return context.fail_out_of_memory();
    }
    const ProgressSpan writing = progress.part(0.4, 0.7), tracing = progress.part(0.7, 0.9), counting = progress.part(0.9, 1.0);
    for (uint32_t f = 0; f < faces; ++f) {
        DBRG_PROPAGATE(writing.report_at(f, faces));
        if (surface.face_removed(f)) continue;
        const bool turn = flip[face_component[f]] != 0;
        result.triangles.push_back(conditioned.input_index[surface.corner(f, 0)]);
        result.triangles.push_back(conditioned.input_index[surface.corner(f, turn ? 2 : 1)]);
        result.triangles.push_back(conditioned.input_index[surface.corner(f, turn ? 1 : 2)]);
        result.face_flags.push_back(surface.face_flags(f));
    }
    // Boundary loops, each from its first boundary half-edge. (Only closed components are turned over,
    // and they have no loops.)
    Array<uint8_t> visited(context.memory);
    if (!visited.resize(3 * size_t(faces), 0) || !result.loop_offsets.push_back(0)) return context.fail_out_of_memory();
    uint32_t boundary_edges = 0;
    for (uint32_t start = 0; start < 3 * faces; ++start) {
        DBRG_PROPAGATE(tracing.report_at(start, 3 * size_t(faces)));
        if (!surface.is_boundary(start) || visited[start]) continue;
        const bool walked = surface.walk_loop(start, [&](uint32_t h) {
            visited[h] = 1;
            ++boundary_edges;
            return result.loop_vertices.push_back(conditioned.input_index[surface.origin(h)]);
        });
        if (!walked || !result.loop_offsets.push_back(static_cast<uint32_t>(result.loop_vertices.size()))) {
            return context.fail_out_of_memory();
        }
    }
    uint32_t vertices_used = 0;
    for (uint32_t v = 0; v < surface.vertex_count(); ++v) {
        DBRG_PROPAGATE(counting.report_at(v, surface.vertex_count()));
        vertices_used += surface.is_used(v) ? 1 : 0;
    }
    context.stats.triangles = surface.live_face_count();
    context.stats.vertices_used = vertices_used;
    context.stats.boundary_edges = boundary_edges;
    context.stats.boundary_loops = static_cast<uint32_t>(result.loop_offsets.size() - 1);
    return DBRG_OK;
}

} // namespace dbrg
