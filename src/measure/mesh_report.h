// Topology and quality figures of a triangle mesh (what `dbrg stats` prints), and their JSON form.
//
// Definitions (vertices are identified by index, as in the file: two vertices at the same place are two
// vertices. With VertexIdentity::position the vertices at each position are welded into one first, and
// the figures are those of the welded mesh):
// - A face with a repeated index (a, a, b) has no proper edges. It counts in `faces` and
//   `degenerate_faces` and takes no part in anything else. Every other face is a "proper" face.
// - An edge is an unordered pair of vertices that are consecutive corners of a proper face. It is a
//   boundary edge with one face, manifold with two, non-manifold with three or more (duplicate faces
//   count separately, so a face listed twice makes its edges non-manifold unless the copies are its
//   only neighbours).
// - A vertex is non-manifold when it lies on a non-manifold edge, or when its faces form more than one
//   fan (faces around it joined through shared manifold edges): the bow-tie.
// - Boundary loops are the connected chains of boundary edges, where two boundary edges at a vertex
//   are chained only when they belong to the same fan there: the two holes of a bow-tie are two loops.
// - Components are classes of proper faces joined through shared edges (of any kind); faces that share
//   only a vertex are in different components.
// - `oriented`: each manifold edge is traversed in opposite directions by its two faces. Non-manifold
//   edges are not considered.
// - `euler_characteristic` = vertices - edges + proper faces, with `vertices` the vertices of proper faces.
// - `genus` is known only when the mesh has faces and is closed (no boundary edge), manifold (no
//   non-manifold edge or vertex) and oriented; it is then the sum over components of (2 - chi_c) / 2.
// - Degenerate faces have a repeated index or three collinear corners (zero area), decided exactly for
//   finite coordinates of any size; a face with a NaN or infinite coordinate is not of zero area.
//   Duplicate faces use the same three vertices as an earlier face, in any order.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "io/mesh_io.h"
#include "measure/surface_distance.h"

namespace dbrg::measure {

// Meshes come as the readers give them.
using io::IoStatus;
using io::MeshData;

// How far a mesh and a reference mesh stray from each other (see surface_distance), and the mean length
// of the reference's triangle sides, the unit to read that in. Each figure is none when it cannot be
// measured.
struct ReferenceDistance {
    std::optional<double> side_mean;
    std::optional<SurfaceDistance> to_reference;    // from the mesh's triangles: bridges, spanning triangles
    std::optional<SurfaceDistance> from_reference;  // from the reference's triangles: surface the mesh leaves out
};

// How make_mesh_report tells vertices apart.
enum class VertexIdentity {
    index,     // by their index: the mesh as the file has it
    position,  // by their position: vertices at exactly equal coordinates are welded into one first, as
               // wanted where a file repeats vertices along texture seams. -0 equals 0; NaN equals nothing.
};

struct MeshReport {
    uint64_t faces = 0;
    uint64_t vertices = 0;            // used by at least one proper face
    uint64_t vertices_isolated = 0;   // in the vertex array but used by no proper face
    bool vertices_welded = false;     // the figures are of the welded mesh (VertexIdentity::position)
    // Vertices of the array at exactly the position of an earlier one: the ones welding merges. JSON key
    // "vertices_merged" when welded, "duplicate_positions" otherwise.
    uint64_t duplicate_positions = 0;
    uint64_t edges_manifold = 0;
    uint64_t edges_boundary = 0;
    uint64_t edges_nonmanifold = 0;
    uint64_t vertices_nonmanifold = 0;
    uint64_t boundary_loops = 0;
    uint64_t components = 0;
    bool oriented = true;
    int64_t euler_characteristic = 0;
    std::optional<int64_t> genus;
    uint64_t degenerate_faces = 0;
    uint64_t duplicate_faces = 0;

    // Filled by add_face_recall.
    std::optional<uint64_t> reference_faces;
    std::optional<double> face_recall;  // none when the reference has no faces
    // Filled by add_reference_distance.
    std::optional<ReferenceDistance> reference_distance;
    // Filled by add_points_used.
    std::optional<uint64_t> points_input;
    std::optional<uint64_t> points_used;
};

// Computes the figures of `mesh` into `report`, replacing what it held, with vertices told apart as
// `identity` says. Faces whose corners are welded together count as degenerate, and as duplicates when
// they become the same as an earlier face. Fails only when the arrays are malformed (a length not a
// multiple of 3, an index with no vertex). Linear time and memory.
IoStatus make_mesh_report(const MeshData& mesh, MeshReport& report, VertexIdentity identity = VertexIdentity::index);

// Sets reference_faces and face_recall: the share of the reference's triangles whose three corner
// positions, exactly equal and in any order, are the corners of some triangle of `mesh`.
IoStatus add_face_recall(const MeshData& mesh, const MeshData& reference, MeshReport& report);

// Sets reference_distance.
IoStatus add_reference_distance(const MeshData& mesh, const MeshData& reference, MeshReport& report);

// Sets points_input (the number of points) and points_used: how many of them sit exactly at a vertex
// of one of the mesh's proper faces.
IoStatus add_points_used(const MeshData& mesh, const MeshData& points, MeshReport& report);

// The report as a JSON object with the key names above (optional figures only when they were computed,
// genus and face_recall as null when unknown). Ends with a newline.
std::string to_json(const MeshReport& report);

} // namespace dbrg::measure
