// `dbrg reconstruct`: a surface from a point cloud file (or the built-in demo), written as a mesh file.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/interrupt.h"
#include "cli/progress_bar.h"
#include "cli/resource_usage.h"
#include "core/pi.h"
#include "dbrg/dbrg.h"
#include "io/json_writer.h"
#include "io/mesh_io.h"
#include "io/unused_vertices.h"
#include "io/vertex_normals.h"
#include "samples/samples.h"
#include "tiles/out_of_core.h"

namespace dbrg::cli {
namespace {

const char* const RECONSTRUCT_USAGE =
    "usage: dbrg reconstruct INPUT -o OUTPUT [options]\n"
    "       dbrg reconstruct --demo [--demo-shape NAME] [--demo-points N] -o OUTPUT [options]\n"
    "\n"
    "Reconstructs an oriented manifold triangle surface through the points of INPUT (.ply .obj .off .stl\n"
    ".xyz .pts .las; only the vertices are read) and writes it to OUTPUT (.ply binary, .obj, .off, .stl) with\n"
    "every input point as a vertex, in input order, and in .ply and .obj each vertex's normal (pointing\n"
    "to the outside of closed surfaces). A .ply OUTPUT also carries the input's other vertex properties\n"
    "(colours, intensity, ...; LAS intensity and colour) and, per face, 'uchar flags' (bit 0: the face was\n"
    "made by hole filling, not grown from the points). OUTPUT is replaced only once it is completely\n"
    "written.\n"
    "\n"
    "  -o, --output FILE        the mesh to write (required)\n"
    "  --demo                   use a generated sample instead of INPUT\n"
    "  --demo-shape NAME        sphere, torus, double_torus (default), bumpy_sphere, hemisphere,\n"
    "                           open_cylinder, saddle, cube, capped_cylinder, graded_sphere, thin_plate\n"
    "  --demo-points N          about N points, evenly spaced (default 20000, at most 100000000)\n"
    "  --boundary-factor M      open-surface test: refuse triangles larger than M times the mean\n"
    "                           circumradius; 0 turns it off, else M > 1 (default 3; below about 1.5\n"
    "                           growing stops early and a warning says how many points were left out)\n"
    "  --boundary-mean local|global   the mean of that test: around the edge, or over the surface (default)\n"
    "  --sliver-angle DEG       largest dihedral angle between neighbouring triangles, in degrees,\n"
    "                           strictly between 90 and 180 (default 150)\n"
    "  --no-fill-holes          leave the holes that growing could not close\n"
    "  --max-hole-edges N       holes with more boundary edges stay open (default 256)\n"
    "  --max-components N       surfaces grown from separate seeds, at most (default 64)\n"
    "  --backend builtin|tetgen the Delaunay tetrahedralization to use (default builtin)\n"
    "  --cleaning auto|off|on   before the tetrahedralization, leave outliers out, merge near-duplicates\n"
    "                           and, on noisy points, smooth them (auto, the default: each only where the\n"
    "                           data call for it; on: smooth whatever the noise estimate says)\n"
    "  --output-smoothed        write the smoothed positions of the points (default: the input's)\n"
    "  --outliers FILE          write the indices of the points left out as outliers, one a line\n"
    "  --threads N              threads for the stages that split (0: all, default; 1: none);\n"
    "                           the mesh is the same for any N\n"
    "  --tiles N                reconstruct N slabs along the longest axis one after another and\n"
    "                           stitch them (docs/tiles.md): the memory of about one slab at a time\n"
    "                           besides the points; the mesh depends on N (default 1: one piece)\n"
    "  --max-memory SIZE        for clouds larger than memory (.ply or .xyz INPUT, binary .ply OUTPUT):\n"
    "                           read the file in passes and reconstruct slabs sized to SIZE (e.g. 1G or\n"
    "                           1GiB, 512M, 2GB) one after another from files on disk, writing the mesh\n"
    "                           as it goes; no vertex normals or other properties (docs/tiles.md)\n"
    "  --no-normals             write no vertex normals\n"
    "  --drop-unused            write only the vertices the triangles use (renumbered, in input order)\n"
    "  --snapshots K            also write the surface at K evenly spaced stages of growth (points\n"
    "                           reached: 1/K, 2/K, ..., end of growing) as OUTPUT with .growth-1 ...\n"
    "                           .growth-K before its extension\n"
    "  --stats-json FILE        write figures about the run as JSON (- for standard output)\n"
    "  -q, --quiet              no progress bar\n"
    "  -h, --help               show this help\n";

// More slabs than this would be thinner than their own halo on any cloud that fits in memory.
const uint32_t MAX_TILES = 4096;

// A demo this large already needs tens of gigabytes; larger ones are better read from a file.
const uint32_t MAX_DEMO_POINTS = 100000000;

// Fills params from the options; returns false with a message for a malformed value.
bool read_params(const ParsedArgs& args, dbrg_params& params, std::string& error) {
    dbrg_params_init(&params);
    double number;
    if (args.has("--boundary-factor")) {
        if (!parse_number(args.value("--boundary-factor"), number)) return error = "--boundary-factor takes a number", false;
        params.boundary_factor = number;
    }
    if (args.has("--sliver-angle")) {
        // Checked here in the user's unit: the library's own message speaks in radians.
        if (!parse_number(args.value("--sliver-angle"), number) || !(number > 90 && number < 180)) {
            return error = "--sliver-angle takes a number of degrees strictly between 90 and 180", false;
        }
        params.sliver_angle = number * PI / 180;
    }
    if (args.has("--boundary-mean")) {
        const std::string mean = args.value("--boundary-mean");
        if (mean != "local" && mean != "global") return error = "--boundary-mean takes local or global", false;
        params.boundary_mean = mean == "local" ? DBRG_BOUNDARY_MEAN_LOCAL : DBRG_BOUNDARY_MEAN_GLOBAL;
    }
    if (args.has("--no-fill-holes")) params.fill_holes = 0;
    if (args.has("--max-hole-edges") && !parse_count(args.value("--max-hole-edges"), params.max_hole_edges)) {
        return error = "--max-hole-edges takes a whole number", false;
    }
    if (args.has("--max-components") && !parse_count(args.value("--max-components"), params.max_components)) {
        return error = "--max-components takes a whole number", false;
    }
    // A file per snapshot: the library's limit, a thousand, is more than any figure needs.
    if (args.has("--snapshots") &&
        (!parse_count(args.value("--snapshots"), params.snapshot_count) || params.snapshot_count > DBRG_MAX_SNAPSHOTS)) {
        return error = "--snapshots takes a whole number up to 1000", false;
    }
    if (args.has("--threads") && !parse_count(args.value("--threads"), params.threads)) {
        return error = "--threads takes a whole number", false;
    }
    if (args.has("--backend")) {
        const std::string backend = args.value("--backend");
        if (backend != "builtin" && backend != "tetgen") return error = "--backend takes builtin or tetgen", false;
        params.backend = backend == "builtin" ? DBRG_BACKEND_BUILTIN : DBRG_BACKEND_TETGEN;
    }
    if (args.has("--cleaning")) {
        const std::string cleaning = args.value("--cleaning");
        if (cleaning != "auto" && cleaning != "off" && cleaning != "on") return error = "--cleaning takes auto, off or on", false;
        params.cleaning = cleaning == "auto" ? DBRG_CLEANING_AUTO : cleaning == "off" ? DBRG_CLEANING_OFF : DBRG_CLEANING_ON;
    }
    if (args.has("--output-smoothed")) params.output_smoothed = 1;
    char message[256];
    if (dbrg_params_validate(&params, message, sizeof message) != DBRG_OK) return error = message, false;
    return true;
}

// The built-in sample asked for with --demo.
struct Demo {
    samples::Shape shape = samples::Shape::double_torus;
    uint32_t points = 20000;
};

// Reads --demo-shape and --demo-points; returns false with a message for a malformed value.
bool read_demo(const ParsedArgs& args, Demo& demo, std::string& error) {
    if (args.has("--demo-shape") && !samples::shape_from_name(args.value("--demo-shape"), demo.shape)) {
        return error = "unknown --demo-shape '" + args.value("--demo-shape") + "'", false;
    }
    if (args.has("--demo-points") &&
        (!parse_count(args.value("--demo-points"), demo.points) || demo.points < 4 || demo.points > MAX_DEMO_POINTS)) {
        return error = "--demo-points takes a whole number from 4 to " + std::to_string(MAX_DEMO_POINTS) +
                       " (reconstruct a file for more)", false;
    }
    return true;
}

// --snapshots: each stage of growth is written next to OUTPUT, with all input points as vertices.
struct SnapshotFiles {
    io::MeshData* mesh;
    std::string output;
    uint32_t written = 0;
    std::string error;

    // OUTPUT with ".growth-<k>" before its extension (format_from_path has found one).
    std::string path(uint32_t k) const {
        const size_t dot = output.find_last_of('.');
        return output.substr(0, dot) + ".growth-" + std::to_string(k) + output.substr(dot);
    }

    static int write(void* user, const uint32_t* triangles, uint32_t triangle_count, double) {
        SnapshotFiles& files = *static_cast<SnapshotFiles*>(user);
        files.mesh->triangles.assign(triangles, triangles + 3 * size_t(triangle_count));
        files.mesh->has_faces = true;
        const io::IoStatus status = io::write_mesh(files.path(++files.written), *files.mesh);
        files.mesh->triangles.clear();
        if (status) return 0;
        files.error = status.message;
        return 1;  // stops the reconstruction
    }
};

// The triangles hole filling made.
uint32_t faces_filled(const dbrg_mesh* mesh) {
    const uint8_t* flags = dbrg_mesh_face_flags(mesh);
    uint32_t count = 0;
    for (uint32_t t = 0; flags && t < dbrg_mesh_triangle_count(mesh); ++t) count += (flags[t] & DBRG_FACE_FILLED) ? 1 : 0;
    return count;
}

// Reads --tiles; returns false with a message for a malformed value or one that does not combine.
bool read_tiles(const ParsedArgs& args, const dbrg_params& params, uint32_t& tiles, std::string& error) {
    tiles = 1;
    if (!args.has("--tiles")) return true;
    if (!parse_count(args.value("--tiles"), tiles) || tiles < 1 || tiles > MAX_TILES) {
        return error = "--tiles takes a whole number from 1 to " + std::to_string(MAX_TILES), false;
    }
    // Snapshots show one growing surface; tiles grow several.
    if (tiles > 1 && params.snapshot_count > 0) return error = "--snapshots does not combine with --tiles", false;
    return true;
}

// --max-memory: the cloud is read from its file in passes and reconstructed in slabs sized to the budget,
// never held whole, and the mesh streamed to a binary PLY (docs/tiles.md, "Out of core").
int reconstruct_out_of_core(const ParsedArgs& args, const dbrg_params& params, const std::string& input,
                            const std::string& output) {
    uint64_t budget = 0;
    if (!parse_size(args.value("--max-memory"), budget)) {
        return report_error(EXIT_USAGE,
                            "reconstruct: --max-memory takes a size such as 1G, 512MiB, 1.5GB or 1500000000");
    }
    for (const char* option : {"--demo", "--tiles", "--snapshots", "--outliers", "--output-smoothed", "--drop-unused"}) {
        if (args.has(option)) return report_error(EXIT_USAGE, std::string("reconstruct: ") + option + " does not combine with --max-memory");
    }
    if (io::format_from_path(output) != io::MeshFormat::ply_binary) {
        return report_error(EXIT_USAGE, "reconstruct: --max-memory writes binary .ply only: '" + output + "'");
    }
#if defined(__GLIBC__)
    // glibc raises its mmap threshold after large blocks are freed, after which a tile's large arrays come
    // from the heap and stay resident once freed: the peak crept up to 1.6 times one tile's. A fixed
    // threshold gives every large array back to the system when its tile is done.
    mallopt(M_MMAP_THRESHOLD, 256 << 10);
#endif
    out_of_core::Options options;
    options.max_memory_bytes = budget;
    options.params = params;
    ProgressBar bar(!args.has("--quiet"));
    options.params.progress = ProgressBar::callback;
    options.params.progress_user = &bar;
    out_of_core::Report report;
    const double start = seconds_now();
    const io::IoStatus status = out_of_core::reconstruct_file(input, output, options, report);
    const double seconds = seconds_now() - start;
    bar.finish();
    if (!status) return report_error(EXIT_FAILED, status.message);
    if (args.has("--stats-json")) {
        io::JsonObject json;
        json.add_unsigned("points", report.points)
            .add_unsigned("triangles", report.triangles)
            .add_unsigned("boundary_edges", report.boundary_edges)
            .add_unsigned("components", report.components)
            .add_unsigned("tiles", report.tiles)
            .add_number("spacing", report.spacing)
            .add_unsigned("max_memory_bytes", budget)
            .add_unsigned("tile_peak_bytes", report.tile_peak_bytes)
            .add_unsigned("orientation_conflicts", report.orientation_conflicts)
            .add_unsigned("seam_faces_dropped", report.seam_faces_dropped)
            .add_number("seconds_total", seconds)
            .add_unsigned("peak_rss_bytes", peak_rss_bytes());
        std::string error;
        if (!write_text_output(args.value("--stats-json"), json.str() + "\n", error)) return report_error(EXIT_FAILED, error);
    }
    if (!args.has("--quiet")) {
        std::fprintf(stderr, "dbrg: %llu points -> %llu triangles in %u tiles in %.3f s; wrote %s\n",
                     static_cast<unsigned long long>(report.points), static_cast<unsigned long long>(report.triangles),
                     report.tiles, seconds, output.c_str());
    }
    return EXIT_OK;
}

std::string stats_json(const dbrg_stats& s, const dbrg_mesh* mesh, double seconds_read, double seconds_write) {
    // A single call ran as one tile, which held everything the library held.
    const bool tiled = s.tiles > 1;
    io::JsonObject json;
    json.add_unsigned("points", s.input_points)
        .add_unsigned("unique_points", s.unique_points)
        .add_unsigned("duplicates_merged", s.duplicates_merged)
        .add_unsigned("tetrahedra", s.tetrahedra)
        .add_unsigned("triangles", s.triangles)
        .add_unsigned("vertices_used", s.vertices_used)
        .add_unsigned("unused_points", s.unique_points - s.vertices_used)
        .add_unsigned("boundary_edges", s.boundary_edges)
        .add_unsigned("boundary_loops", dbrg_mesh_boundary_loop_count(mesh))
        .add_unsigned("components", s.components)
        .add_unsigned("pinch_faces_removed", s.pinch_faces_removed)
        .add_unsigned("candidates_evaluated", s.candidates_evaluated)
        .add_unsigned("rejected_edge_nonmanifold", s.rejected_edge_nonmanifold)
        .add_unsigned("rejected_orientation", s.rejected_orientation)
        .add_unsigned("rejected_bowtie", s.rejected_bowtie)
        .add_unsigned("rejected_dihedral", s.rejected_dihedral)
        .add_unsigned("rejected_boundary", s.rejected_boundary)
        .add_unsigned("holes_found", s.holes_found)
        .add_unsigned("holes_filled", s.holes_filled)
        .add_unsigned("holes_left_open", s.holes_left_open)
        .add_unsigned("hole_triangles_delaunay", s.hole_triangles_delaunay)
        .add_unsigned("hole_triangles_added", s.hole_triangles_added)
        .add_unsigned("hole_triangles_removed", s.hole_triangles_removed)
        .add_unsigned("faces_filled", faces_filled(mesh))
        .add_unsigned("handles_removed", s.handles_removed)
        .add_unsigned("points_inserted", s.points_inserted)
        .add_unsigned("outliers", s.outliers)
        .add_unsigned("near_duplicates_merged", s.near_duplicates_merged)
        .add_unsigned("points_smoothed", s.points_smoothed)
        .add_unsigned("smoothing_iterations", s.smoothing_iterations)
        .add_number("noise_level", s.noise_level)
        .add_unsigned("predicate_calls", s.predicate_calls)
        .add_unsigned("predicate_filter_failures", s.predicate_filter_failures)
        .add_unsigned("predicate_perturbations", s.predicate_perturbations)
        .add_number("seconds_read", seconds_read)
        .add_number("seconds_validate", s.seconds_validate)
        .add_number("seconds_sort", s.seconds_sort)
        .add_number("seconds_clean", s.seconds_clean)
        .add_number("seconds_delaunay", s.seconds_delaunay)
        .add_number("seconds_growing", s.seconds_grow)
        .add_number("seconds_fill_holes", s.seconds_fill_holes)
        .add_number("seconds_output", s.seconds_output)
        .add_number("seconds_total", s.seconds_total)
        .add_number("seconds_write", seconds_write)
        .add_unsigned("library_peak_bytes", s.peak_bytes)
        .add_unsigned("tiles", tiled ? s.tiles : 1)
        .add_unsigned("tile_peak_bytes", tiled ? s.tile_peak_bytes : s.peak_bytes)
        .add_unsigned("seam_faces_dropped", s.seam_faces_dropped)
        .add_unsigned("peak_rss_bytes", peak_rss_bytes());
    return json.str() + "\n";
}

} // namespace

int run_reconstruct(int argc, char** argv) {
    const std::vector<OptionSpec> options = {
        {"--output", "-o", true},          {"--demo", nullptr, false},           {"--demo-shape", nullptr, true},
        {"--demo-points", nullptr, true},  {"--boundary-factor", nullptr, true}, {"--boundary-mean", nullptr, true},
        {"--sliver-angle", nullptr, true}, {"--no-fill-holes", nullptr, false},  {"--max-hole-edges", nullptr, true},
        {"--max-components", nullptr, true}, {"--backend", nullptr, true},       {"--stats-json", nullptr, true},
        {"--threads", nullptr, true},      {"--snapshots", nullptr, true},       {"--quiet", "-q", false},
        {"--no-normals", nullptr, false},  {"--drop-unused", nullptr, false},     {"--tiles", nullptr, true},
        {"--cleaning", nullptr, true},     {"--output-smoothed", nullptr, false}, {"--outliers", nullptr, true},
        {"--max-memory", nullptr, true},
    };
    ParsedArgs args;
    std::string error;
    if (!parse_args(argc, argv, options, args, error)) {
        return report_error(EXIT_USAGE, "reconstruct: " + error + " (see 'dbrg reconstruct --help')");
    }
    if (args.help) {
        std::fputs(RECONSTRUCT_USAGE, stdout);
        return EXIT_OK;
    }
    const size_t inputs_expected = args.has("--demo") ? 0 : 1;
    if (args.positional.size() != inputs_expected) {
        return report_error(EXIT_USAGE, inputs_expected ? "reconstruct: expected one INPUT file (or --demo)"
                                                        : "reconstruct: --demo takes no INPUT file");
    }
    if (!args.has("--output")) return report_error(EXIT_USAGE, "reconstruct: -o OUTPUT is required");
    const std::string output = args.value("--output");
    const std::optional<io::MeshFormat> format = io::format_from_path(output);
    if (!format || *format == io::MeshFormat::xyz || *format == io::MeshFormat::las) {
        const std::string problem = !format ? "cannot tell the format of '" + output + "'"
                                    : *format == io::MeshFormat::las ? "LAS files are read, not written: '" + output + "'"
                                                                     : "'" + output + "' would hold the points without the triangles";
        return report_error(EXIT_USAGE, "reconstruct: " + problem + " (use .ply .obj .off .stl)");
    }
    dbrg_params params;
    Demo demo;
    uint32_t tiles;
    if (!read_params(args, params, error) || !read_tiles(args, params, tiles, error) ||
        (args.has("--demo") && !read_demo(args, demo, error))) {
        return report_error(EXIT_USAGE, "reconstruct: " + error);
    }
    io::MeshData mesh;
    SnapshotFiles snapshots{&mesh, output, 0, {}};
    std::vector<std::string> outputs = {output, args.value("--stats-json"), args.value("--outliers")};
    for (uint32_t k = 1; k <= params.snapshot_count; ++k) outputs.push_back(snapshots.path(k));
    const std::string input = args.has("--demo") ? "" : args.positional[0];
    if (!check_outputs(outputs, input, error)) return report_error(EXIT_FAILED, "reconstruct: " + error);
    // From here a Ctrl-C cancels the reconstruction at its next progress report, which leaves no files: a
    // file being read is read to its end first (a second Ctrl-C stops the program at once).
    watch_interrupts();
    if (args.has("--max-memory")) return reconstruct_out_of_core(args, params, input, output);

    double start = seconds_now();
    if (args.has("--demo")) {
        mesh.positions = samples::sample(demo.shape, demo.points);
    } else {
        const io::IoStatus read = io::read_mesh(input, mesh);
        if (!read) return report_error(EXIT_FAILED, read.message);
        // The surface's normals replace the input's; its other vertex properties go to the output as read.
        // Its faces, if any, are not the surface's: their values go.
        mesh.normals.clear();
        mesh.face_properties.clear();
    }
    const double seconds_read = seconds_now() - start;

    ProgressBar bar(!args.has("--quiet"));
    params.progress = ProgressBar::callback;
    params.progress_user = &bar;
    if (params.snapshot_count > 0) {
        params.snapshot = SnapshotFiles::write;
        params.snapshot_user = &snapshots;
    }
    const dbrg_points points{mesh.positions.data(), mesh.vertex_count(), 3 * sizeof(double), DBRG_FLOAT64};
    dbrg_mesh* result = nullptr;
    const dbrg_status status = tiles > 1 ? dbrg_reconstruct_tiled(&points, tiles, &params, &result)
                                         : dbrg_reconstruct(&points, &params, &result);
    bar.finish();
    if (!snapshots.error.empty()) {
        dbrg_mesh_destroy(result);
        return report_error(EXIT_FAILED, snapshots.error);
    }
    if (status != DBRG_OK) {
        const std::string message = result ? dbrg_mesh_message(result) : "out of memory";
        dbrg_mesh_destroy(result);
        return report_library_error(status, message.c_str(), input, mesh);
    }

    start = seconds_now();
    const uint32_t* triangles = dbrg_mesh_triangles(result);
    mesh.triangles.assign(triangles, triangles + 3 * size_t(dbrg_mesh_triangle_count(result)));
    mesh.has_faces = true;
    const uint8_t* flags = dbrg_mesh_face_flags(result);
    mesh.face_properties = {{"flags", io::ValueType::uint8, {}}};
    mesh.face_properties[0].bytes.assign(flags, flags + (flags ? mesh.triangle_count() : 0));
    if (const double* smoothed = dbrg_mesh_smoothed_points(result)) {
        mesh.positions.assign(smoothed, smoothed + mesh.positions.size());
    }
    const bool format_has_normals = *format == io::MeshFormat::ply_binary || *format == io::MeshFormat::obj;
    if (format_has_normals && !args.has("--no-normals")) mesh.normals = io::vertex_normals(mesh.positions, mesh.triangles);
    if (args.has("--drop-unused")) io::drop_unused_vertices(mesh);
    const io::IoStatus written = io::write_mesh(output, mesh);
    const double seconds_write = seconds_now() - start;

    dbrg_stats stats;
    stats.struct_size = sizeof stats;
    dbrg_mesh_stats(result, &stats);
    std::string summary_error;
    bool summary_ok = true;
    if (args.has("--stats-json")) {
        summary_ok = write_text_output(args.value("--stats-json"), stats_json(stats, result, seconds_read, seconds_write),
                                       summary_error);
    }
    if (summary_ok && args.has("--outliers")) {
        uint32_t count = 0;
        const uint32_t* outliers = dbrg_mesh_outliers(result, &count);
        std::string lines;
        for (uint32_t i = 0; i < count; ++i) lines += std::to_string(outliers[i]) + "\n";
        summary_ok = write_text_output(args.value("--outliers"), lines, summary_error);
    }
    // On success the library's message is empty or a warning (e.g. most points left out of the surface).
    if (*dbrg_mesh_message(result)) std::fprintf(stderr, "dbrg: %s\n", dbrg_mesh_message(result));
    if (!args.has("--quiet") && written) {
        std::fprintf(stderr, "dbrg: %u points -> %u triangles, %u boundary loops in %.3f s; wrote %s\n",
                     stats.input_points, stats.triangles, dbrg_mesh_boundary_loop_count(result), stats.seconds_total,
                     output.c_str());
    }
    dbrg_mesh_destroy(result);
    if (!written) return report_error(EXIT_FAILED, written.message);
    if (!summary_ok) return report_error(EXIT_FAILED, summary_error);
    return EXIT_OK;
}

} // namespace dbrg::cli
