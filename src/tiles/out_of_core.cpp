// Out-of-core reconstruction: slabs from bucket files, faces on disk, walls stitched one at a time from
// what lies near them, pieces oriented by a parity union-find, the mesh streamed out (see out_of_core.h).
#include "tiles/out_of_core.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "io/file_output.h"
#include "io/ply_stream_writer.h"
#include "io/point_reader.h"
#include "tiles/cloud_files.h"
#include "tiles/seam_manifold.h"
#include "tiles/tiled_reconstruction.h"

namespace dbrg::out_of_core {
namespace {

using io::IoStatus;

struct FaceRecord {
    uint64_t v[3];
};

// A slab's points by id, for the steps that look up faces' corners.
struct PointMap {
    std::unordered_map<uint64_t, uint32_t> index;
    std::vector<std::array<double, 3>> xyz;

    const double* find(uint64_t id) const {
        const auto found = index.find(id);
        return found == index.end() ? nullptr : xyz[found->second].data();
    }
    void add(const PointRecord& point) {
        if (index.emplace(point.id, uint32_t(xyz.size())).second) xyz.push_back({point.xyz[0], point.xyz[1], point.xyz[2]});
    }
};

// Faces of several slab files, one list a slab, with a flag a face for those left out.
using SlabFaces = std::vector<std::vector<FaceRecord>>;
using LeftOut = std::vector<std::vector<uint8_t>>;

LeftOut none_left_out(const SlabFaces& slabs) {
    LeftOut left_out(slabs.size());
    for (size_t s = 0; s < slabs.size(); ++s) left_out[s].assign(slabs[s].size(), 0);
    return left_out;
}

// The records whose flag in `left_out` is clear, in order.
template <class Record>
std::vector<Record> without(const std::vector<Record>& records, const std::vector<uint8_t>& left_out) {
    std::vector<Record> kept;
    for (size_t i = 0; i < records.size(); ++i) {
        if (!left_out[i]) kept.push_back(records[i]);
    }
    return kept;
}

// Flags in `left_out` the faces that faces_breaking_manifold leaves out around `checked`, looking at the
// faces of `slabs` not left out yet that have a corner there.
void leave_out_breaking(const SlabFaces& slabs, const std::unordered_set<uint64_t>& checked, LeftOut& left_out) {
    std::vector<uint64_t> corners;
    std::vector<std::pair<size_t, size_t>> origin;  // (slab, index) of each face looked at
    for (size_t s = 0; s < slabs.size(); ++s) {
        for (size_t f = 0; f < slabs[s].size(); ++f) {
            const uint64_t* v = slabs[s][f].v;
            if (left_out[s][f] || (!checked.count(v[0]) && !checked.count(v[1]) && !checked.count(v[2]))) continue;
            corners.insert(corners.end(), v, v + 3);
            origin.emplace_back(s, f);
        }
    }
    for (size_t i : faces_breaking_manifold(corners.data(), origin.size(), checked)) {
        left_out[origin[i].first][origin[i].second] = 1;
    }
}

// The triangle's centroid on `axis` as TileCore::owns computes it: the corners summed in lexicographic
// order of their coordinates, so every step assigns a face to the same side of a wall.
double centroid_on(int axis, const double* a, const double* b, const double* c) {
    const double* corners[3] = {a, b, c};
    std::sort(corners, corners + 3,
              [](const double* p, const double* q) { return std::lexicographical_compare(p, p + 3, q, q + 3); });
    return (corners[0][axis] + corners[1][axis] + corners[2][axis]) / 3;
}

IoStatus library_failure(const std::string& where, dbrg_status status, const dbrg_tile_mesh* mesh) {
    return IoStatus::failure(where + ": " + dbrg_status_string(status) + ": " +
                             (mesh ? dbrg_tile_mesh_message(mesh) : "out of memory"));
}

// Parity union-find over the pieces: each piece is oriented consistently inside; parity says whether it
// must be turned over relative to its set's root.
class ParityUnion {
public:
    explicit ParityUnion(size_t count) : parent_(count), parity_(count, 0) { std::iota(parent_.begin(), parent_.end(), 0); }

    // The root of `piece` and the piece's parity relative to it.
    std::pair<uint32_t, uint8_t> find(uint32_t piece) {
        uint8_t parity = 0;
        uint32_t root = piece;
        while (parent_[root] != root) {
            parity ^= parity_[root];
            root = parent_[root];
        }
        // Path compression, keeping each parity relative to the root.
        uint8_t rest = parity;
        while (parent_[piece] != root) {
            const uint32_t next = parent_[piece];
            const uint8_t own = parity_[piece];
            parent_[piece] = root;
            parity_[piece] = rest;
            rest ^= own;
            piece = next;
        }
        return {root, parity};
    }
    // Records that a and b must differ by `parity`; false when that contradicts what is known.
    bool join(uint32_t a, uint32_t b, uint8_t parity) {
        const auto [root_a, parity_a] = find(a);
        const auto [root_b, parity_b] = find(b);
        if (root_a == root_b) return (parity_a ^ parity_b) == parity;
        // The smaller root stays root: the result does not depend on the order of the joins' sides.
        const uint32_t low = std::min(root_a, root_b), high = std::max(root_a, root_b);
        parent_[high] = low;
        parity_[high] = parity_a ^ parity_b ^ parity;
        return true;
    }

private:
    std::vector<uint32_t> parent_;
    std::vector<uint8_t> parity_;
};

// An edge used by one face of a slab's file: where pieces meet across a wall.
struct BorderEdge {
    uint64_t low, high;
    uint32_t piece;
    uint8_t forward;  // the face runs low -> high
    bool operator<(const BorderEdge& o) const { return low != o.low ? low < o.low : high < o.high; }
};

// What the orientation of a whole component needs from each piece: its signed volume (closed
// components face outward) and its highest point's smallest face (open ones face up there, as growing
// seeds them).
struct PieceFacts {
    double volume = 0;
    uint64_t open_edges = 0;
    double top_z = -HUGE_VAL;
    uint64_t top_id = UINT64_MAX;
    double top_radius = HUGE_VAL;
    bool top_up = true;

    // Whether the vertex (z, id) is above the piece's top so far: highest z, then smallest id.
    bool above(double z, uint64_t id) const { return z > top_z || (z == top_z && id < top_id); }
};

double circumradius(const double* a, const double* b, const double* c) {
    const double ab = std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]), bc = std::hypot(c[0] - b[0], c[1] - b[1], c[2] - b[2]);
    const double ca = std::hypot(a[0] - c[0], a[1] - c[1], a[2] - c[2]);
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2], vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const double area2 = std::hypot(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx);
    return area2 > 0 ? ab * bc * ca / (2 * area2) : HUGE_VAL;
}

// The normal of a -> b -> c, and whether it faces up by the seeding rule (+z, else +x, else +y).
bool faces_up(const double* a, const double* b, const double* c) {
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2], vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    return nz != 0 ? nz > 0 : (nx != 0 ? nx > 0 : ny >= 0);
}

class Run {
public:
    Run(const std::string& input, const std::string& output, const Options& options, Report& report)
        : input_(input), output_(output), options_(options), report_(report), piece_params_(options.params) {
        // The pieces report nothing of their own, but pass a cancel on; the loop reports its own progress.
        piece_params_.progress = options.params.progress ? forward_cancel : nullptr;
        piece_params_.progress_user = this;
        piece_params_.snapshot = nullptr;
        piece_params_.snapshot_count = 0;
    }

    IoStatus run() {
        IoStatus status = progress(DBRG_STAGE_VALIDATE, 0.0);
        if (status) status = reader_.open(input_);
        if (status) status = summarize(reader_, summary_);
        if (status) status = progress(DBRG_STAGE_VALIDATE, 0.3);
        if (status) status = stream_spacing(reader_, summary_, report_.spacing);
        if (!status) return status;
        report_.points = summary_.count;
        if (summary_.count < 4) return IoStatus::failure(input_ + ": " + std::to_string(summary_.count) + " points; a surface needs at least 4");
        spacing_ = report_.spacing;
        const double length = summary_.high[summary_.axis] - summary_.low[summary_.axis];
        const double halo_share = length > 0 ? 2 * HALO_SPACINGS * spacing_ / length : 1;
        status = progress(DBRG_STAGE_VALIDATE, 0.7);
        if (!status) return status;
        const uint32_t asked = options_.tiles ? options_.tiles : tiles_for_budget(summary_.count, options_.max_memory_bytes, halo_share);
        if (asked == 0) {
            return IoStatus::failure(input_ + ": " + std::to_string(options_.max_memory_bytes >> 20) +
                                     " MiB is too little for this cloud: a slab's halo alone holds about " +
                                     std::to_string(uint64_t(halo_share * double(summary_.count))) + " of its points, " +
                                     std::to_string(uint64_t(halo_share * double(summary_.count) * TILE_BYTES_PER_POINT + BASE_BYTES) >> 20) +
                                     " MiB");
        }
        if (spacing_ > 0) walls_ = sample_walls(summary_, asked, MIN_SLAB_SPACINGS * spacing_);
        tiles_ = static_cast<uint32_t>(walls_.size() + 1);
        report_.tiles = tiles_;
        const std::string parent = output_ == "-" ? "." : io::folder_of(output_);
        status = folder_.create(parent, "out");
        if (!status) return status;
        std::vector<std::string> buckets;
        for (uint32_t k = 0; k < tiles_; ++k) buckets.push_back(bucket(k));
        status = write_buckets(reader_, summary_.axis, walls_, HALO_SPACINGS * spacing_, buckets);
        for (uint32_t k = 0; status && k < tiles_; ++k) {
            status = progress(DBRG_STAGE_GROW, double(k) / tiles_);
            if (status) status = run_tile(k);
        }
        // The even walls, then the odd ones, as dbrg_reconstruct_tiled stitches them.
        size_t stitched = 0;
        for (size_t parity : {0, 1}) {
            for (size_t w = parity; status && w < walls_.size(); w += 2) {
                status = progress(DBRG_STAGE_FILL_HOLES, double(stitched++) / walls_.size());
                if (status) status = stitch(w);
            }
        }
        for (size_t w = 0; status && w < walls_.size(); ++w) {
            status = progress(DBRG_STAGE_FILL_HOLES, 1.0);
            if (status) status = check_seam(w);
        }
        if (status) status = progress(DBRG_STAGE_OUTPUT, 0.0);
        std::vector<PieceFacts> pieces;
        std::vector<std::vector<BorderEdge>> borders(tiles_);
        unoriented_.assign(tiles_, 0);
        for (uint32_t k = 0; status && k < tiles_; ++k) status = orient_slab(k, pieces, borders[k]);
        if (!status) return status;
        std::vector<uint8_t> flip;
        orient_pieces(pieces, borders, flip);
        for (uint32_t k = 0; status && k < tiles_; ++k) {
            if (unoriented_[k]) status = progress(DBRG_STAGE_OUTPUT, 0.0);
            if (status && unoriented_[k]) status = leave_out_unoriented(k, flip);
        }
        return status ? write_output(flip) : status;
    }

private:
    // The passes over the file as validation, the slabs as growing, the walls as hole filling and the
    // orientation and output as output, as dbrg_reconstruct_tiled reports them. A failure when the
    // callback cancels.
    IoStatus progress(dbrg_stage stage, double fraction) {
        stage_ = stage;
        fraction_ = fraction;
        if (!options_.params.progress || options_.params.progress(options_.params.progress_user, stage, fraction) == 0) {
            return IoStatus::success();
        }
        return IoStatus::failure(input_ + ": cancelled");
    }

    // The pieces' callback: asks the caller's again at the loop's own stage and fraction, so that a cancel
    // stops a slab or a stitch in its middle without the reported progress moving.
    static int forward_cancel(void* user, dbrg_stage, double) {
        const Run& run = *static_cast<const Run*>(user);
        return run.options_.params.progress(run.options_.params.progress_user, run.stage_, run.fraction_);
    }

    std::string bucket(uint32_t k) const { return folder_.file("tile-" + std::to_string(k) + ".points"); }
    std::string faces(uint32_t k) const { return folder_.file("tile-" + std::to_string(k) + ".faces"); }
    std::string piece_file(uint32_t k) const { return folder_.file("tile-" + std::to_string(k) + ".pieces"); }

    void note_peak(const dbrg_tile_mesh* mesh) {
        dbrg_stats stats{};
        stats.struct_size = sizeof stats;
        if (dbrg_tile_mesh_stats(mesh, &stats) == DBRG_OK) report_.tile_peak_bytes = std::max(report_.tile_peak_bytes, stats.peak_bytes);
    }

    // Reconstructs slab k from its bucket and writes the faces its core owns.
    IoStatus run_tile(uint32_t k) {
        std::vector<PointRecord> points;
        IoStatus status = read_records(bucket(k), points);
        if (!status) return status;
        std::vector<FaceRecord> owned;
        if (points.size() >= 4) {
            std::vector<uint64_t> ids(points.size());
            for (size_t i = 0; i < points.size(); ++i) ids[i] = points[i].id;
            const dbrg_points view{points[0].xyz, points.size(), sizeof(PointRecord), DBRG_FLOAT64};
            double low[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, high[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
            if (k > 0) low[summary_.axis] = walls_[k - 1];
            if (k < walls_.size()) high[summary_.axis] = walls_[k];
            dbrg_tile_mesh* mesh = nullptr;
            const dbrg_status result = dbrg_reconstruct_tile(&view, ids.data(), low, high, &piece_params_, &mesh);
            if (result != DBRG_OK) {
                status = library_failure("tile " + std::to_string(k + 1) + " of " + std::to_string(tiles_), result, mesh);
                dbrg_tile_mesh_destroy(mesh);
                return status;
            }
            note_peak(mesh);
            uint64_t outlier_count = 0;
            const uint64_t* outliers = dbrg_tile_mesh_outliers(mesh, &outlier_count);
            outliers_.insert(outliers, outliers + outlier_count);
            const uint64_t* triangles = dbrg_tile_mesh_triangles(mesh);
            owned.resize(dbrg_tile_mesh_triangle_count(mesh));
            for (size_t f = 0; f < owned.size(); ++f) std::copy(triangles + 3 * f, triangles + 3 * f + 3, owned[f].v);
            dbrg_tile_mesh_destroy(mesh);
        }
        return write_records(faces(k), owned);
    }

    // The points of the slabs on either side of wall w within twice the stitch's reach of it, and the
    // faces of both slabs. Both buckets hold every point within a halo of the wall, and each reaches a slab
    // (12 spacings) further on its side: twice the reach keeps the corners of every face near the wall.
    IoStatus read_seam(size_t w, PointMap& near, SlabFaces& sides) {
        const double window = 2 * seam_reach();
        sides.assign(2, {});
        for (uint32_t side = 0; side < 2; ++side) {
            std::vector<PointRecord> points;
            IoStatus status = read_records(bucket(uint32_t(w) + side), points);
            if (status) status = read_records(faces(uint32_t(w) + side), sides[side]);
            if (!status) return status;
            for (const PointRecord& point : points) {
                if (std::fabs(point.xyz[summary_.axis] - walls_[w]) < window) near.add(point);
            }
        }
        return IoStatus::success();
    }

    double seam_reach() const { return (STRIP_SPACINGS + MARGIN_SPACINGS) * spacing_; }

    // A face's distance to wall w: its nearest corner's; HUGE_VAL when a corner is not in `near`.
    double distance_to_wall(const FaceRecord& face, const PointMap& near, size_t w) const {
        double nearest = HUGE_VAL;
        for (uint64_t id : face.v) {
            const double* p = near.find(id);
            if (!p) return HUGE_VAL;
            nearest = std::min(nearest, std::fabs(p[summary_.axis] - walls_[w]));
        }
        return nearest;
    }

    // Stitches wall w from the points and faces near it (those of the slabs on either side), then puts
    // the faces back in the two slabs' files by the side of the wall their centroid is on.
    IoStatus stitch(size_t w) {
        const double wall = walls_[w];
        const int axis = summary_.axis;
        const double strip = STRIP_SPACINGS * spacing_, reach = seam_reach();
        PointMap near;
        SlabFaces sides;
        if (const IoStatus status = read_seam(w, near, sides); !status) return status;
        const auto distance = [&](const FaceRecord& face) { return distance_to_wall(face, near, w); };
        std::unordered_set<uint64_t> cut_corners;
        for (const auto& side : sides) {
            for (const FaceRecord& face : side) {
                if (distance(face) < strip) cut_corners.insert(face.v, face.v + 3);
            }
        }
        // The faces the stitch sees: those within reach and those sharing a corner with a cut face.
        std::vector<uint64_t> selected;
        std::vector<std::pair<uint32_t, size_t>> origin;  // (side, index) of each selected face
        std::unordered_set<uint64_t> corners;
        for (uint32_t side = 0; side < 2; ++side) {
            for (size_t f = 0; f < sides[side].size(); ++f) {
                const FaceRecord& face = sides[side][f];
                const double d = distance(face);
                if (d == HUGE_VAL) continue;
                const bool touches_cut = cut_corners.count(face.v[0]) || cut_corners.count(face.v[1]) || cut_corners.count(face.v[2]);
                if (!(d < reach) && !touches_cut) continue;
                selected.insert(selected.end(), face.v, face.v + 3);
                origin.emplace_back(side, f);
                corners.insert(face.v, face.v + 3);
            }
        }
        std::vector<uint64_t> ids;
        std::vector<double> xyz;
        for (const auto& [id, i] : near.index) {
            const bool within = std::fabs(near.xyz[i][axis] - wall) < reach && !outliers_.count(id);
            if (within || corners.count(id)) ids.push_back(id);
        }
        std::sort(ids.begin(), ids.end());
        for (uint64_t id : ids) xyz.insert(xyz.end(), near.find(id), near.find(id) + 3);
        dbrg_tiling tiling{};
        tiling.struct_size = sizeof tiling;
        tiling.axis = uint32_t(axis);
        tiling.wall_count = uint32_t(walls_.size());
        tiling.spacing = spacing_;
        tiling.halo = HALO_SPACINGS * spacing_;
        tiling.seam_reach = reach;
        const dbrg_points view{xyz.data(), ids.size(), 3 * sizeof(double), DBRG_FLOAT64};
        dbrg_tile_mesh* mesh = nullptr;
        const dbrg_status result = dbrg_seam_stitch(&view, ids.data(), selected.data(), origin.size(), &tiling, wall,
                                                    &piece_params_, &mesh);
        if (result != DBRG_OK) {
            const IoStatus status = library_failure("wall " + std::to_string(w + 1) + " of " + std::to_string(walls_.size()), result, mesh);
            dbrg_tile_mesh_destroy(mesh);
            return status;
        }
        note_peak(mesh);
        uint64_t dropped_count = 0;
        const uint64_t* dropped = dbrg_tile_mesh_dropped(mesh, &dropped_count);
        LeftOut gone = none_left_out(sides);
        for (uint64_t i = 0; i < dropped_count; ++i) gone[origin[dropped[i]].first][origin[dropped[i]].second] = 1;
        std::vector<FaceRecord> kept[2] = {without(sides[0], gone[0]), without(sides[1], gone[1])};
        const uint64_t* added = dbrg_tile_mesh_triangles(mesh);
        for (uint64_t f = 0; f < dbrg_tile_mesh_triangle_count(mesh); ++f) {
            FaceRecord face;
            std::copy(added + 3 * f, added + 3 * f + 3, face.v);
            const double centroid = centroid_on(axis, near.find(face.v[0]), near.find(face.v[1]), near.find(face.v[2]));
            kept[centroid < wall ? 0 : 1].push_back(face);
        }
        dbrg_tile_mesh_destroy(mesh);
        IoStatus status = write_records(faces(uint32_t(w)), kept[0]);
        return status ? write_records(faces(uint32_t(w) + 1), kept[1]) : status;
    }

    // The assembly's manifold check, at wall w once every wall is stitched: the faces of the two slabs
    // around it with a corner where a face within the stitch's reach has one, checked around those corners
    // (faces_breaking_manifold); the faces it leaves out leave their files. Only there do pieces grown apart
    // meet: a slab's own faces and a stitch's are each a manifold.
    IoStatus check_seam(size_t w) {
        PointMap near;
        SlabFaces sides;
        if (const IoStatus status = read_seam(w, near, sides); !status) return status;
        std::unordered_set<uint64_t> checked;
        for (const auto& side : sides) {
            for (const FaceRecord& face : side) {
                if (distance_to_wall(face, near, w) < seam_reach()) checked.insert(face.v, face.v + 3);
            }
        }
        LeftOut gone = none_left_out(sides);
        leave_out_breaking(sides, checked, gone);
        IoStatus status = IoStatus::success();
        for (uint32_t side = 0; status && side < 2; ++side) {
            const size_t count = std::count(gone[side].begin(), gone[side].end(), 1);
            if (count == 0) continue;
            report_.seam_faces_dropped += count;
            status = write_records(faces(uint32_t(w) + side), without(sides[side], gone[side]));
        }
        return status;
    }

    // Orients slab k's faces consistently within each of their edge-connected pieces (a walk from the
    // first face of each in sorted order), numbers the pieces after those of earlier slabs, and gathers
    // what the whole-mesh orientation needs: each piece's facts and the edges only one face of the slab uses.
    IoStatus orient_slab(uint32_t k, std::vector<PieceFacts>& pieces, std::vector<BorderEdge>& border) {
        std::vector<FaceRecord> slab_faces;
        std::vector<PointRecord> points;
        IoStatus status = read_records(faces(k), slab_faces);
        if (status) status = read_records(bucket(k), points);
        if (!status) return status;
        PointMap map;
        for (const PointRecord& point : points) map.add(point);
        points = {};
        for (FaceRecord& face : slab_faces) std::rotate(face.v, std::min_element(face.v, face.v + 3), face.v + 3);
        std::sort(slab_faces.begin(), slab_faces.end(), [](const FaceRecord& a, const FaceRecord& b) {
            return std::lexicographical_compare(a.v, a.v + 3, b.v, b.v + 3);
        });
        struct Use {
            uint64_t low, high;
            uint32_t face;
            uint8_t forward;
        };
        std::vector<Use> uses;
        uses.reserve(3 * slab_faces.size());
        for (uint32_t f = 0; f < slab_faces.size(); ++f) {
            for (int i = 0; i < 3; ++i) {
                const uint64_t a = slab_faces[f].v[i], b = slab_faces[f].v[(i + 1) % 3];
                uses.push_back({std::min(a, b), std::max(a, b), f, uint8_t(a < b)});
            }
        }
        std::sort(uses.begin(), uses.end(), [](const Use& a, const Use& b) {
            return a.low != b.low ? a.low < b.low : a.high != b.high ? a.high < b.high : a.face < b.face;
        });
        // Neighbours across the edges exactly two faces share.
        std::vector<std::array<uint32_t, 3>> neighbour(slab_faces.size(), {UINT32_MAX, UINT32_MAX, UINT32_MAX});
        std::vector<std::array<uint8_t, 3>> same_way(slab_faces.size());
        std::vector<uint8_t> degree(slab_faces.size(), 0);
        for (size_t i = 0; i < uses.size();) {
            size_t j = i;
            while (j < uses.size() && uses[j].low == uses[i].low && uses[j].high == uses[i].high) ++j;
            if (j - i == 2) {
                const Use& a = uses[i];
                const Use& b = uses[i + 1];
                const uint8_t same = a.forward == b.forward;
                neighbour[a.face][degree[a.face]] = b.face;
                same_way[a.face][degree[a.face]++] = same;
                neighbour[b.face][degree[b.face]] = a.face;
                same_way[b.face][degree[b.face]++] = same;
            }
            i = j;
        }
        std::vector<uint8_t> flip(slab_faces.size(), 0), seen(slab_faces.size(), 0);
        std::vector<uint32_t> piece_of(slab_faces.size());
        std::vector<uint32_t> queue;
        for (uint32_t start = 0; start < slab_faces.size(); ++start) {
            if (seen[start]) continue;
            const uint32_t piece = uint32_t(pieces.size());
            pieces.emplace_back();
            seen[start] = 1;
            queue.assign(1, start);
            for (size_t q = 0; q < queue.size(); ++q) {
                const uint32_t f = queue[q];
                piece_of[f] = piece;
                for (int i = 0; i < degree[f]; ++i) {
                    const uint32_t g = neighbour[f][i];
                    if (seen[g]) continue;
                    seen[g] = 1;
                    flip[g] = flip[f] ^ same_way[f][i];
                    queue.push_back(g);
                }
            }
        }
        for (uint32_t f = 0; f < slab_faces.size(); ++f) {
            if (flip[f]) std::swap(slab_faces[f].v[1], slab_faces[f].v[2]);
        }
        // The edges one face uses: the slab's border, where pieces meet across the walls. An edge two faces
        // run the same way: a piece that cannot be oriented (its walk turned a face against a neighbour
        // reached another way).
        for (size_t i = 0; i < uses.size();) {
            size_t j = i;
            while (j < uses.size() && uses[j].low == uses[i].low && uses[j].high == uses[i].high) ++j;
            const Use& use = uses[i];
            if (j - i == 1) {
                pieces[piece_of[use.face]].open_edges += 1;
                border.push_back({use.low, use.high, piece_of[use.face], uint8_t(use.forward ^ flip[use.face])});
            } else if (j - i == 2 && (use.forward ^ flip[use.face]) == (uses[i + 1].forward ^ flip[uses[i + 1].face])) {
                ++report_.orientation_conflicts;
                unoriented_[k] = 1;
            }
            i = j;
        }
        std::sort(border.begin(), border.end());
        for (uint32_t f = 0; f < slab_faces.size(); ++f) {
            const double* corner[3];
            for (int i = 0; i < 3; ++i) corner[i] = map.find(slab_faces[f].v[i]);
            if (!corner[0] || !corner[1] || !corner[2]) continue;  // a corner past the bucket: no say in the turn
            PieceFacts& facts = pieces[piece_of[f]];
            const double* a = corner[0];
            const double* b = corner[1];
            const double* c = corner[2];
            facts.volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                             a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
            for (int i = 0; i < 3; ++i) {
                const double z = corner[i][2];
                const uint64_t id = slab_faces[f].v[i];
                const bool at_top = z == facts.top_z && id == facts.top_id;
                if (!facts.above(z, id) && !at_top) continue;
                const double radius = circumradius(a, b, c);
                if (!at_top) {
                    facts.top_z = z;
                    facts.top_id = id;
                    facts.top_radius = HUGE_VAL;
                }
                if (radius < facts.top_radius) {
                    facts.top_radius = radius;
                    facts.top_up = faces_up(a, b, c);
                }
            }
        }
        std::vector<uint32_t> piece_records(piece_of.begin(), piece_of.end());
        status = write_records(faces(k), slab_faces);
        return status ? write_records(piece_file(k), piece_records) : status;
    }

    // Joins the pieces across the walls (an edge one face of each slab uses must run opposite ways), and
    // turns each component as one process does: outward when closed, its highest point's smallest face
    // up when open. flip[piece]: whether the piece's faces are turned over on output.
    void orient_pieces(std::vector<PieceFacts>& pieces, const std::vector<std::vector<BorderEdge>>& borders,
                       std::vector<uint8_t>& flip) {
        ParityUnion sets(pieces.size());
        for (size_t w = 0; w + 1 < borders.size(); ++w) {
            const std::vector<BorderEdge>& left = borders[w];
            const std::vector<BorderEdge>& right = borders[w + 1];
            size_t j = 0;
            for (const BorderEdge& edge : left) {
                while (j < right.size() && right[j] < edge) ++j;
                if (j == right.size() || edge < right[j]) continue;
                const BorderEdge& other = right[j++];
                if (!sets.join(edge.piece, other.piece, edge.forward == other.forward)) {
                    ++report_.orientation_conflicts;
                    unoriented_[w] = unoriented_[w + 1] = 1;
                }
                pieces[edge.piece].open_edges -= 1;
                pieces[other.piece].open_edges -= 1;
            }
        }
        // Each component's facts, in its root's frame.
        std::vector<PieceFacts> component(pieces.size());
        std::vector<uint8_t> is_root(pieces.size(), 0);
        for (uint32_t p = 0; p < pieces.size(); ++p) {
            const auto [root, parity] = sets.find(p);
            is_root[root] = 1;
            PieceFacts& total = component[root];
            const PieceFacts& own = pieces[p];
            total.volume += parity ? -own.volume : own.volume;
            total.open_edges += own.open_edges;
            const bool at_top = own.top_z == total.top_z && own.top_id == total.top_id;
            if (total.above(own.top_z, own.top_id) || (at_top && own.top_radius < total.top_radius)) {
                total.top_z = own.top_z;
                total.top_id = own.top_id;
                total.top_radius = own.top_radius;
                total.top_up = own.top_up != bool(parity);
            }
        }
        flip.assign(pieces.size(), 0);
        report_.components = 0;
        report_.boundary_edges = 0;
        for (uint32_t p = 0; p < pieces.size(); ++p) {
            if (!is_root[p]) continue;
            ++report_.components;
            report_.boundary_edges += component[p].open_edges;
        }
        for (uint32_t p = 0; p < pieces.size(); ++p) {
            const auto [root, parity] = sets.find(p);
            const PieceFacts& total = component[root];
            const bool turn = total.open_edges == 0 ? total.volume < 0 : !total.top_up;
            flip[p] = uint8_t(parity) ^ uint8_t(turn);
        }
    }

    // Leaves out faces until every edge of slab k's faces runs opposite ways in its two faces once the pieces
    // are turned (`flip`), as the assembly leaves out a face that would run an edge the way its neighbour
    // does: pieces that could not be turned to agree across a wall, or a piece that cannot be oriented
    // itself (stitched faces joined to a slab's own in a twisted band). Of two faces running an edge the
    // same way, the one whose corners sort later goes; then the pinches that leaves at its corners
    // (faces_breaking_manifold). The neighbouring slabs are read too: a face of slab k shares its corners
    // with theirs, and they lose faces here as well. (Three slabs' faces at once, more than a slab's
    // reconstruction holds of them, but only for a slab where such an edge was found.) The boundary edges
    // reported are corrected over those three slabs.
    IoStatus leave_out_unoriented(uint32_t k, const std::vector<uint8_t>& flip) {
        const uint32_t first = k > 0 ? k - 1 : 0, last = std::min(k + 1, tiles_ - 1);
        SlabFaces slabs(last - first + 1);
        std::vector<std::vector<uint32_t>> piece_of(slabs.size());
        for (uint32_t s = 0; s < slabs.size(); ++s) {
            IoStatus status = read_records(faces(first + s), slabs[s]);
            if (status) status = read_records(piece_file(first + s), piece_of[s]);
            if (!status) return status;
        }
        struct Use {
            uint64_t low, high;
            uint32_t slab;
            uint32_t face;
            uint8_t forward;  // the face, turned as its piece is, runs low -> high
        };
        std::vector<Use> uses;
        for (uint32_t s = 0; s < slabs.size(); ++s) {
            for (uint32_t f = 0; f < slabs[s].size(); ++f) {
                const bool turned = flip[piece_of[s][f]] != 0;
                for (int i = 0; i < 3; ++i) {
                    const uint64_t a = slabs[s][f].v[i], b = slabs[s][f].v[(i + 1) % 3];
                    uses.push_back({std::min(a, b), std::max(a, b), s, f, uint8_t((a < b) != turned)});
                }
            }
        }
        std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
            return std::tie(x.low, x.high, x.slab, x.face) < std::tie(y.low, y.high, y.slab, y.face);
        });
        LeftOut gone = none_left_out(slabs);
        std::unordered_set<uint64_t> checked;
        const uint32_t own = k - first;
        const auto for_each_edge = [&](auto&& visit) {
            for (size_t i = 0, j; i < uses.size(); i = j) {
                for (j = i + 1; j < uses.size() && uses[j].low == uses[i].low && uses[j].high == uses[i].high;) ++j;
                visit(i, j);
            }
        };
        for_each_edge([&](size_t i, size_t j) {
            if (j - i != 2) return;
            const Use& x = uses[i];
            const Use& y = uses[i + 1];
            if (x.forward != y.forward || (x.slab != own && y.slab != own) || gone[x.slab][x.face] ||
                gone[y.slab][y.face]) {
                return;
            }
            const bool x_later = sorted_corners(slabs[y.slab][y.face].v) < sorted_corners(slabs[x.slab][x.face].v);
            const Use& later = x_later ? x : y;
            gone[later.slab][later.face] = 1;
            checked.insert(slabs[later.slab][later.face].v, slabs[later.slab][later.face].v + 3);
        });
        leave_out_breaking(slabs, checked, gone);
        // An edge of a face left out was a boundary edge if it had one face, and is one if one face is left.
        for_each_edge([&](size_t i, size_t j) {
            size_t left = 0;
            for (size_t u = i; u < j; ++u) left += !gone[uses[u].slab][uses[u].face];
            if (left == j - i) return;
            report_.boundary_edges = report_.boundary_edges + (left == 1) - (j - i == 1);
        });
        IoStatus status = IoStatus::success();
        for (uint32_t s = 0; status && s < slabs.size(); ++s) {
            const size_t count = std::count(gone[s].begin(), gone[s].end(), 1);
            if (count == 0) continue;
            report_.seam_faces_dropped += count;
            status = write_records(faces(first + s), without(slabs[s], gone[s]));
            if (status) status = write_records(piece_file(first + s), without(piece_of[s], gone[s]));
        }
        return status;
    }

    // The input's points in input order, then every slab's faces, turned as `flip` says.
    IoStatus write_output(const std::vector<uint8_t>& flip) {
        uint64_t triangles = 0;
        for (uint32_t k = 0; k < tiles_; ++k) {
            std::vector<uint32_t> piece_records;
            const IoStatus status = read_records(piece_file(k), piece_records);
            if (!status) return status;
            triangles += piece_records.size();
        }
        report_.triangles = triangles;
        io::PlyStreamWriter writer;
        io::PlyStreamWriter::Layout layout;
        layout.vertex_count = summary_.count;
        layout.triangle_count = triangles;
        layout.double_coordinates = !summary_.float_exact;
        IoStatus status = writer.open(output_, layout);
        if (status) status = reader_.rewind();
        std::vector<double> xyz(3 << 16);
        for (size_t count = 1; status && count > 0;) {
            status = reader_.read(xyz.data(), xyz.size() / 3, count);
            if (status) status = writer.add_vertices(xyz.data(), count);
        }
        for (uint32_t k = 0; status && k < tiles_; ++k) {
            std::vector<FaceRecord> slab_faces;
            std::vector<uint32_t> piece_records;
            status = read_records(faces(k), slab_faces);
            if (status) status = read_records(piece_file(k), piece_records);
            if (!status) break;
            for (size_t f = 0; f < slab_faces.size(); ++f) {
                if (flip[piece_records[f]]) std::swap(slab_faces[f].v[1], slab_faces[f].v[2]);
            }
            status = writer.add_triangles(slab_faces.empty() ? nullptr : slab_faces[0].v, slab_faces.size());
        }
        return status ? writer.finish() : status;
    }

    std::string input_, output_;
    const Options& options_;
    Report& report_;
    dbrg_params piece_params_;
    io::PointReader reader_;
    CloudSummary summary_;
    double spacing_ = 0;
    std::unordered_set<uint64_t> outliers_;  // the slabs' outliers: a stitch gets them only as faces' corners
    std::vector<uint8_t> unoriented_;  // per slab: some of its faces cannot be turned to agree with a neighbour
    std::vector<double> walls_;
    uint32_t tiles_ = 1;
    TempFolder folder_;
    dbrg_stage stage_ = DBRG_STAGE_VALIDATE;  // where the loop last reported
    double fraction_ = 0;
};

} // namespace

uint32_t tiles_for_budget(uint64_t count, uint64_t max_memory_bytes, double halo_share) {
    // A slab of 1/T of the points and its halo: count (1/T + halo_share) points of TILE_BYTES_PER_POINT.
    const double share = (double(max_memory_bytes) - BASE_BYTES) / (double(count) * TILE_BYTES_PER_POINT);
    if (share >= 1) return 1;
    if (!(share > halo_share)) return 0;
    const double tiles = std::ceil(1 / (share - halo_share));
    return tiles >= double(UINT32_MAX) ? 0 : uint32_t(tiles);
}

IoStatus reconstruct_file(const std::string& input, const std::string& output, const Options& options, Report& report) {
    report = Report();
    try {
        return Run(input, output, options, report).run();
    } catch (const std::bad_alloc&) {
        return IoStatus::failure("out of memory (a smaller --max-memory makes smaller tiles)");
    }
}

} // namespace dbrg::out_of_core
