// `dbrg delaunay`: the Delaunay tetrahedralization of a point file, reported as JSON (optionally the
// tetrahedra themselves as a text file).
#include <cstdio>
#include <string>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/resource_usage.h"
#include "dbrg/dbrg.h"
#include "io/json_writer.h"
#include "io/mesh_io.h"

namespace dbrg::cli {
namespace {

const char* const DELAUNAY_USAGE =
    "usage: dbrg delaunay INPUT [--backend builtin|tetgen] [--threads N] [--stats-json FILE] [--tets FILE]\n"
    "\n"
    "Computes the Delaunay tetrahedralization of the points of INPUT (.ply .obj .off .stl .xyz .pts .las;\n"
    "only the vertices are read) and prints a JSON report: points, unique_points, tetrahedra (finite ones), seconds\n"
    "(the tetrahedralization alone, reading excluded), peak_rss_bytes.\n"
    "\n"
    "  --backend builtin|tetgen  the engine (default builtin; tetgen only in builds with -Dtetgen=enabled)\n"
    "  --threads N               threads for the stages that split (0: all, default; 1: none);\n"
    "                            the tetrahedra are the same for any N\n"
    "  --stats-json FILE         write the report to FILE instead of standard output\n"
    "  --tets FILE               also write the tetrahedra, one per line: four input point indices\n"
    "  -h, --help                show this help\n";

bool write_tets(const std::string& path, const dbrg_tetrahedralization* tets, std::string& error) {
    const uint32_t* vertices = dbrg_tetrahedralization_tets(tets);
    const uint32_t count = dbrg_tetrahedralization_tet_count(tets);
    std::string text;
    char line[64];
    for (uint32_t t = 0; t < count; ++t) {
        const int length = std::snprintf(line, sizeof line, "%u %u %u %u\n", vertices[4 * t], vertices[4 * t + 1],
                                         vertices[4 * t + 2], vertices[4 * t + 3]);
        text.append(line, size_t(length));
    }
    return write_text_output(path, text, error);
}

} // namespace

int run_delaunay(int argc, char** argv) {
    const std::vector<OptionSpec> options = {
        {"--backend", nullptr, true},
        {"--stats-json", nullptr, true},
        {"--tets", nullptr, true},
        {"--threads", nullptr, true},
    };
    ParsedArgs args;
    std::string error;
    if (!parse_args(argc, argv, options, args, error)) {
        return report_error(EXIT_USAGE, "delaunay: " + error + " (see 'dbrg delaunay --help')");
    }
    if (args.help) {
        std::fputs(DELAUNAY_USAGE, stdout);
        return EXIT_OK;
    }
    if (args.positional.size() != 1) return report_error(EXIT_USAGE, "delaunay: expected one INPUT file");
    dbrg_params params;
    dbrg_params_init(&params);
    const std::string backend = args.value("--backend", "builtin");
    if (backend != "builtin" && backend != "tetgen") return report_error(EXIT_USAGE, "delaunay: --backend takes builtin or tetgen");
    params.backend = backend == "builtin" ? DBRG_BACKEND_BUILTIN : DBRG_BACKEND_TETGEN;
    if (args.has("--threads") && !parse_count(args.value("--threads"), params.threads)) {
        return report_error(EXIT_USAGE, "delaunay: --threads takes a whole number");
    }

    if (!check_outputs({args.value("--stats-json"), args.value("--tets")}, args.positional[0], error)) {
        return report_error(EXIT_FAILED, "delaunay: " + error);
    }

    io::MeshData mesh;
    const io::IoStatus read = io::read_mesh(args.positional[0], mesh);
    if (!read) return report_error(EXIT_FAILED, read.message);

    const dbrg_points points{mesh.positions.data(), mesh.vertex_count(), 3 * sizeof(double), DBRG_FLOAT64};
    dbrg_tetrahedralization* tets = nullptr;
    const double start = seconds_now();
    const dbrg_status status = dbrg_tetrahedralize(&points, &params, &tets);
    const double seconds = seconds_now() - start;
    if (status != DBRG_OK) {
        const std::string message = tets ? dbrg_tetrahedralization_message(tets) : "out of memory";
        dbrg_tetrahedralization_destroy(tets);
        return report_library_error(status, message.c_str(), args.positional[0], mesh);
    }
    io::JsonObject json;
    json.add_unsigned("points", mesh.vertex_count())
        .add_unsigned("unique_points", dbrg_tetrahedralization_unique_point_count(tets))
        .add_unsigned("tetrahedra", dbrg_tetrahedralization_tet_count(tets))
        .add_string("backend", backend)
        .add_number("seconds", seconds)
        .add_unsigned("peak_rss_bytes", peak_rss_bytes());
    // The tetrahedra first: a report on standard output promises a run that succeeded.
    bool ok = !args.has("--tets") || write_tets(args.value("--tets"), tets, error);
    if (ok) ok = write_text_output(args.value("--stats-json"), json.str() + "\n", error);
    dbrg_tetrahedralization_destroy(tets);
    return ok ? EXIT_OK : report_error(EXIT_FAILED, error);
}

} // namespace dbrg::cli
