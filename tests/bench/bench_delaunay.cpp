// dbrg-bench-delaunay: times the built-in tetrahedralization against TetGen and CGAL on the same points
// (uniform cubes, a torus, an open surface patch, spheres, a cylinder, exact and jittered grids, the real
// meshes' vertices) and prints the ratios.
//
// Each engine runs in a child process of its own, so that its peak resident memory is its own. Times are
// processor seconds of that process.
// Usage: dbrg-bench-delaunay [--quick] [--markdown] [--no-fork] [--data DIR] [--only NAME] [--repeat N]
//                            [--size N] [--threads N] [--engines dbrg,tetgen,cgal]
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "core/pi.h"
#include "core/context.h"
#include "core/splitmix64.h"
#include "points/point_conditioning.h"
#include "delaunay/tetgen_backend.h"
#include "delaunay/tetrahedralization.h"
#include "io/mesh_io.h"
#if DBRG_BENCH_HAVE_CGAL
#include "cgal_delaunay.h"
#endif

namespace {

enum Engine { BUILTIN, TETGEN, CGAL, ENGINE_COUNT };
const char* const ENGINE_NAME[ENGINE_COUNT] = {"dbrg", "tetgen", "cgal"};

struct Dataset {
    std::string name;
    std::vector<double> xyz;
};

// What a child reports back through its pipe.
struct Measure {
    int ok = 0;
    double seconds_condition = 0;  // dbrg only: duplicate merging, rescaling, lexicographic sort, Hilbert renumbering
    double seconds_build = 0;      // the tetrahedralization: spatial sort + insertion (+ conversion for TetGen)
    uint64_t unique_points = 0;
    uint64_t finite_tets = 0;
    uint64_t peak_alloc_bytes = 0;  // dbrg's allocator high-water mark (conditioning included)
    uint64_t predicate_calls = 0;
    uint64_t filter_failures = 0;
    uint64_t rss_start_bytes = 0;
    char message[256] = "";
};

struct Row {
    Measure m;
    uint64_t peak_rss_bytes = 0;  // the child's high-water mark minus what it held at its start
};

unsigned threads = 1;  // --threads: dbrg's threads (0: all); the other engines are single-threaded

// Processor time of this process when every engine is single-threaded: unlike wall time it does not
// count the time other programs on a busy machine take the processor away. Wall time when dbrg runs on
// several threads, whose processor times add up.
double now() {
    timespec t;
    clock_gettime(threads == 1 ? CLOCK_PROCESS_CPUTIME_ID : CLOCK_MONOTONIC, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

uint64_t status_field_bytes(const char* field) {
    FILE* f = fopen("/proc/self/status", "r");
    if (!f) return 0;
    char line[256];
    uint64_t kb = 0;
    const size_t length = strlen(field);
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, field, length) == 0) kb = strtoull(line + length, nullptr, 10);
    }
    fclose(f);
    return kb * 1024;
}

using Random = dbrg::SplitMix64;

Dataset uniform_cube(size_t n) {
    Dataset d{"uniform " + std::to_string(n / 1000) + "k", std::vector<double>(3 * n)};
    Random r(n);
    for (double& c : d.xyz) c = r.uniform();
    return d;
}

// Uniform by area on a torus (R = 1, r = 0.35): the tube angle is drawn with density R + r cos(v).
Dataset torus(size_t n) {
    Dataset d{"torus " + std::to_string(n / 1000) + "k", {}};
    d.xyz.reserve(3 * n);
    Random r(17);
    const double R = 1.0, tube = 0.35, pi = dbrg::PI;
    while (d.xyz.size() < 3 * n) {
        const double u = 2 * pi * r.uniform(), v = 2 * pi * r.uniform();
        if (r.uniform() * (R + tube) > R + tube * cos(v)) continue;
        d.xyz.insert(d.xyz.end(), {(R + tube * cos(v)) * cos(u), (R + tube * cos(v)) * sin(u), tube * sin(v)});
    }
    return d;
}

// Uniform on the unit sphere: every five points are cospherical up to the rounding of their coordinates.
Dataset sphere(size_t n) {
    Dataset d{"sphere " + std::to_string(n / 1000) + "k", {}};
    d.xyz.reserve(3 * n);
    Random r(29);
    while (d.xyz.size() < 3 * n) {
        const double x = 2 * r.uniform() - 1, y = 2 * r.uniform() - 1, z = 2 * r.uniform() - 1;
        const double length = sqrt(x * x + y * y + z * z);
        if (length > 1 || length < 0.01) continue;  // uniform directions: the ball, not the cube
        d.xyz.insert(d.xyz.end(), {x / length, y / length, z / length});
    }
    return d;
}

// Uniform on an open cylinder of radius 1 and height 6: every four points of one circle are cocircular
// up to rounding, and so nearly cospherical with any fifth.
Dataset cylinder(size_t n) {
    Dataset d{"cylinder " + std::to_string(n / 1000) + "k", std::vector<double>(3 * n)};
    Random r(31);
    const double pi = dbrg::PI;
    for (size_t i = 0; i < n; ++i) {
        const double angle = 2 * pi * r.uniform();
        d.xyz[3 * i] = cos(angle);
        d.xyz[3 * i + 1] = sin(angle);
        d.xyz[3 * i + 2] = 6 * r.uniform();
    }
    return d;
}

// The integer points of a cube of side `side` (exactly cospherical in groups of eight and more), moved by
// up to `jitter` along each axis.
Dataset grid(size_t side, double jitter) {
    Dataset d{std::string(jitter > 0 ? "jittered grid " : "grid ") + std::to_string(side * side * side / 1000) + "k", {}};
    d.xyz.reserve(3 * side * side * side);
    Random r(37);
    for (size_t i = 0; i < side; ++i)
        for (size_t j = 0; j < side; ++j)
            for (size_t k = 0; k < side; ++k) {
                const double p[3] = {double(i), double(j), double(k)};
                for (double c : p) d.xyz.push_back(c + jitter * (2 * r.uniform() - 1));
            }
    return d;
}

// An open, curved height-field patch.
Dataset surface_patch(size_t n) {
    Dataset d{"open patch " + std::to_string(n / 1000) + "k", std::vector<double>(3 * n)};
    Random r(23);
    for (size_t i = 0; i < n; ++i) {
        const double x = r.uniform(), y = r.uniform();
        d.xyz[3 * i] = x;
        d.xyz[3 * i + 1] = y;
        d.xyz[3 * i + 2] = 0.2 * sin(4 * x) * cos(3 * y) + 0.1 * x * y;
    }
    return d;
}

Measure run_engine(Engine engine, const Dataset& data) {
    Measure m;
    m.rss_start_bytes = status_field_bytes("VmRSS:");
    dbrg_params params;
    memset(&params, 0, sizeof params);
    params.struct_size = sizeof params;
    params.threads = threads;  // 1 by default, like the engines it is compared with
    const size_t n = data.xyz.size() / 3;
    if (engine == CGAL) {
#if DBRG_BENCH_HAVE_CGAL
        dbrg_bench::CgalRun run;
        m.ok = dbrg_bench::cgal_delaunay(data.xyz.data(), n, run);
        m.seconds_build = run.seconds;
        m.finite_tets = run.finite_tets;
        m.unique_points = n;
        if (!m.ok) snprintf(m.message, sizeof m.message, "CGAL threw");
#endif
        return m;
    }
    dbrg::Context context(params);
    dbrg::ConditionedPoints points(context.memory);
    dbrg::Tetrahedralization tets(context.memory);
    const double t0 = now();
    dbrg_status status = dbrg::condition_points(data.xyz.data(), n, context, points);
    // As the library's pipeline does before every tetrahedralization.
    if (status == DBRG_OK) status = dbrg::renumber_spatially(points, context);
    const double t1 = now();
    if (status == DBRG_OK) {
        status = engine == TETGEN ? dbrg::build_with_tetgen(points.coordinates.data(), points.size(), context, tets)
                                  : tets.build(points.coordinates.data(), points.size(), context);
    }
    const double t2 = now();
    m.ok = status == DBRG_OK;
    if (!m.ok) snprintf(m.message, sizeof m.message, "%s", context.message());
    m.seconds_condition = t1 - t0;
    m.seconds_build = t2 - t1;
    m.unique_points = points.size();
    m.finite_tets = tets.finite_tet_count();
    m.peak_alloc_bytes = context.memory.peak_bytes();
    m.predicate_calls = tets.counters.calls;
    m.filter_failures = tets.counters.filter_failures;
    return m;
}

std::string engine_filter;  // --engines: a comma-separated subset of the engine names

bool engine_available(Engine engine) {
    if (!engine_filter.empty() && engine_filter.find(ENGINE_NAME[engine]) == std::string::npos) return false;
    if (engine == TETGEN) return dbrg::tetgen_available();
#if DBRG_BENCH_HAVE_CGAL
    if (engine == CGAL) return true;
#else
    if (engine == CGAL) return false;
#endif
    return true;
}

Row run_in_child(Engine engine, const Dataset& data, bool fork_children) {
    Row row;
    if (!fork_children) {
        row.m = run_engine(engine, data);
        return row;
    }
    int fds[2];
    if (pipe(fds) != 0) return row;
    fflush(stdout);
    const pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        const Measure m = run_engine(engine, data);
        const ssize_t written = write(fds[1], &m, sizeof m);
        _exit(written == ssize_t(sizeof m) ? 0 : 1);
    }
    close(fds[1]);
    const ssize_t got = read(fds[0], &row.m, sizeof row.m);
    close(fds[0]);
    int status = 0;
    rusage usage;
    memset(&usage, 0, sizeof usage);
    wait4(pid, &status, 0, &usage);
    if (got != ssize_t(sizeof row.m)) {
        row.m.ok = 0;
        snprintf(row.m.message, sizeof row.m.message, "the child process died (status %d)", status);
        return row;
    }
    const uint64_t peak = uint64_t(usage.ru_maxrss) * 1024;
    row.peak_rss_bytes = peak > row.m.rss_start_bytes ? peak - row.m.rss_start_bytes : 0;
    return row;
}

void load_meshes(const std::string& dir, std::vector<Dataset>& out) {
    const char* files[] = {"stanford-bunny.obj", "rocker-arm.off", "cheburashka.off", "fandisk.obj", "homer.off",
                           "teapot.obj", "spot.obj", "cow.ply", "suzanne.obj"};
    for (const char* file : files) {
        dbrg::io::MeshData mesh;
        const dbrg::io::IoStatus status = dbrg::io::read_mesh(dir + "/" + file, mesh);
        if (!status) {
            fprintf(stderr, "skipping %s: %s\n", file, status.message.c_str());
            continue;
        }
        out.push_back(Dataset{file, std::move(mesh.positions)});
    }
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false, markdown = false, fork_children = true;
    int repeat = 1;
    size_t size = 0;  // --size: the point count of the generated large sets instead of 1M (100k with --quick)
    std::string data_dir;
#ifdef DBRG_SHARED_DATA_DIR
    data_dir = DBRG_SHARED_DATA_DIR;
#endif
    if (const char* env = getenv("DBRG_DATA_DIR")) data_dir = env;
    std::string only;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--quick")) quick = true;
        else if (!strcmp(argv[i], "--markdown")) markdown = true;
        else if (!strcmp(argv[i], "--no-fork")) fork_children = false;
        else if (!strcmp(argv[i], "--data") && i + 1 < argc) data_dir = argv[++i];
        else if (!strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
        else if (!strcmp(argv[i], "--repeat") && i + 1 < argc) repeat = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--size") && i + 1 < argc) size = strtoull(argv[++i], nullptr, 10);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc) threads = unsigned(atoi(argv[++i]));
        else if (!strcmp(argv[i], "--engines") && i + 1 < argc) engine_filter = argv[++i];
        else {
            fprintf(stderr, "usage: %s [--quick] [--markdown] [--no-fork] [--data DIR] [--only NAME] [--repeat N] [--size N] [--threads N] [--engines dbrg,tetgen,cgal]\n", argv[0]);
            return 2;
        }
    }
    std::vector<Dataset> sets;
    const size_t big = size ? size : quick ? 100000 : 1000000;
    sets.push_back(uniform_cube(100000));
    if (!quick) sets.push_back(uniform_cube(big));
    sets.push_back(torus(big));
    sets.push_back(surface_patch(big));
    sets.push_back(sphere(20000));
    sets.push_back(sphere(big / 5));
    if (!quick) sets.push_back(sphere(big));
    sets.push_back(cylinder(big / 5));
    if (!quick) sets.push_back(cylinder(big));
    const size_t side = size_t(cbrt(double(big / 5)) + 0.5);
    sets.push_back(grid(side, 0));
    sets.push_back(grid(side, 0x1p-10));
    if (!data_dir.empty()) load_meshes(data_dir, sets);

    printf("engines: dbrg%s%s; times are the best of %d; ratio = other engine's time / dbrg's time\n",
           engine_available(TETGEN) ? ", tetgen" : "", engine_available(CGAL) ? ", cgal" : "", repeat);
    if (markdown) {
        printf("\n| input | points | engine | seconds | Mpoints/s | tets/point | peak alloc B/pt | peak RSS B/pt | filter failures | time ratio |\n");
        printf("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
    } else {
        printf("\n%-22s %9s %-7s %8s %8s %9s %8s %8s %8s %8s %9s\n", "input", "points", "engine", "cond s", "build s",
               "Mpts/s", "tets/pt", "alloc/pt", "RSS/pt", "filter%", "ratio");
    }
    for (const Dataset& data : sets) {
        if (!only.empty() && data.name.find(only) == std::string::npos) continue;
        const size_t n = data.xyz.size() / 3;
        Row rows[ENGINE_COUNT];
        for (int e = 0; e < ENGINE_COUNT; ++e) {
            if (!engine_available(Engine(e))) continue;
            for (int r = 0; r < repeat; ++r) {
                const Row row = run_in_child(Engine(e), data, fork_children);
                const double total = row.m.seconds_condition + row.m.seconds_build;
                const double best = rows[e].m.seconds_condition + rows[e].m.seconds_build;
                if (r == 0 || (row.m.ok && total < best)) rows[e] = row;
            }
        }
        const double ours = engine_available(BUILTIN) ? rows[BUILTIN].m.seconds_condition + rows[BUILTIN].m.seconds_build : NAN;
        for (int e = 0; e < ENGINE_COUNT; ++e) {
            if (!engine_available(Engine(e))) continue;
            const Measure& m = rows[e].m;
            if (!m.ok) {
                printf("%-22s %9zu %-7s failed: %s\n", data.name.c_str(), n, ENGINE_NAME[e], m.message);
                continue;
            }
            const double total = m.seconds_condition + m.seconds_build;
            const double mpts = n / total / 1e6;
            const double tets_per_point = double(m.finite_tets) / double(m.unique_points);
            const double alloc = e == CGAL ? NAN : double(m.peak_alloc_bytes) / n;
            const double rss = double(rows[e].peak_rss_bytes) / n;
            const double filter = m.predicate_calls ? 100.0 * double(m.filter_failures) / double(m.predicate_calls) : NAN;
            const double ratio = total / ours;
            if (markdown) {
                printf("| %s | %zu | %s | %.3f | %.2f | %.2f | %s | %.0f | %s | %s |\n", data.name.c_str(), n, ENGINE_NAME[e],
                       total, mpts, tets_per_point,
                       e == CGAL ? "-" : std::to_string(int(alloc + 0.5)).c_str(), rss,
                       e == BUILTIN ? (std::to_string(filter).substr(0, 5) + "%").c_str() : "-",
                       e == BUILTIN ? "1" : (std::to_string(ratio).substr(0, 4)).c_str());
            } else {
                printf("%-22s %9zu %-7s %8.3f %8.3f %9.2f %8.3f %8.0f %8.0f %8.4f %9.2f\n", data.name.c_str(), n,
                       ENGINE_NAME[e], m.seconds_condition, m.seconds_build, mpts, tets_per_point, alloc, rss, filter,
                       ratio);
            }
            fflush(stdout);
        }
    }
    return 0;
}
