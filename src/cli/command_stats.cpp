// `dbrg stats`: the topology and quality report of a triangle mesh, as JSON.
#include <cstdio>
#include <string>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "io/mesh_io.h"
#include "measure/mesh_report.h"

namespace dbrg::cli {
namespace {

const char* const STATS_USAGE =
    "usage: dbrg stats MESH [--weld] [--points INPUT] [--reference REF] [-o FILE]\n"
    "\n"
    "Prints a JSON report on the triangle mesh MESH (.ply .obj .off .stl): faces, vertices, manifold /\n"
    "boundary / non-manifold edges, non-manifold (bow-tie) vertices, boundary loops, components,\n"
    "orientation, Euler characteristic, genus (null unless the mesh is closed, manifold and oriented),\n"
    "degenerate faces (a repeated vertex or zero area, decided exactly) and duplicate faces.\n"
    "Vertices are told apart by index, as in the file; duplicate_positions counts the vertices at\n"
    "exactly the position of an earlier one (files that split vertices along texture seams have them):\n"
    "when it is not 0, open edges may be closed by position, which --weld shows.\n"
    "\n"
    "  --weld             merge the vertices at exactly equal coordinates before measuring, so that\n"
    "                     faces meeting at a repeated position count as joined; faces whose corners\n"
    "                     merge count as degenerate. The report says vertices_welded: true and\n"
    "                     vertices_merged (in place of duplicate_positions)\n"
    "  --points INPUT     also count how many points of INPUT (any readable file) are mesh vertices\n"
    "                     (points_input, points_used; matched by exact coordinates)\n"
    "  --reference REF    also report face_recall: the share of REF's triangles that MESH contains\n"
    "                     (corners matched by exact coordinates, in any order), and how far the two\n"
    "                     surfaces stray from each other: distance_to_reference_max / _mean (from\n"
    "                     points on MESH's triangles to REF's surface), distance_from_reference_max /\n"
    "                     _mean (the other way), in REF's units; reference_side_mean, the mean length\n"
    "                     of REF's triangle sides, is the scale to read them in\n"
    "  -o, --output FILE  write the JSON to FILE instead of standard output\n"
    "  -h, --help         show this help\n";

} // namespace

int run_stats(int argc, char** argv) {
    const std::vector<OptionSpec> options = {
        {"--weld", nullptr, false},
        {"--points", nullptr, true},
        {"--reference", nullptr, true},
        {"--output", "-o", true},
    };
    ParsedArgs args;
    std::string error;
    if (!parse_args(argc, argv, options, args, error)) return report_error(EXIT_USAGE, "stats: " + error + " (see 'dbrg stats --help')");
    if (args.help) {
        std::fputs(STATS_USAGE, stdout);
        return EXIT_OK;
    }
    if (args.positional.size() != 1) {
        return report_error(EXIT_USAGE, args.positional.empty() ? "stats: no mesh file given (see 'dbrg stats --help')"
                                                                : "stats: expected one mesh file, got " + std::to_string(args.positional.size()));
    }

    if (!check_outputs({args.value("--output")}, args.positional[0], error)) return report_error(EXIT_FAILED, "stats: " + error);

    io::MeshData mesh;
    io::IoStatus status = io::read_mesh(args.positional[0], mesh);
    if (!status) return report_error(EXIT_FAILED, status.message);
    measure::MeshReport report;
    status = measure::make_mesh_report(mesh, report, args.has("--weld") ? measure::VertexIdentity::position : measure::VertexIdentity::index);
    if (!status) return report_error(EXIT_FAILED, status.message);

    if (args.has("--reference")) {
        io::MeshData reference;
        status = io::read_mesh(args.value("--reference"), reference);
        if (status) status = measure::add_face_recall(mesh, reference, report);
        if (status) status = measure::add_reference_distance(mesh, reference, report);
        if (!status) return report_error(EXIT_FAILED, status.message);
    }
    if (args.has("--points")) {
        io::MeshData points;
        status = io::read_mesh(args.value("--points"), points);
        if (status) status = measure::add_points_used(mesh, points, report);
        if (!status) return report_error(EXIT_FAILED, status.message);
    }
    if (!write_text_output(args.value("--output"), measure::to_json(report), error)) return report_error(EXIT_FAILED, error);
    return EXIT_OK;
}

} // namespace dbrg::cli
