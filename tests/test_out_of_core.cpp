// Tests of out-of-core reconstruction (src/tiles/out_of_core.h, cloud_files.h): the streamed passes give the
// whole-cloud figures, points land in the right bucket files, a bad input leaves nothing behind, and a mesh
// reconstructed from a file with bounded memory matches --tiles N and the single call.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>
#include <random>
#include <set>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/context.h"
#include "dbrg/dbrg.h"
#include "io/mesh_io.h"
#include "io/point_reader.h"
#include "samples/samples.h"
#include "support/mesh_checks.h"
#include "tiles/cloud_files.h"
#include "tiles/out_of_core.h"
#include "support/shared_data.h"
#include "tiles/point_spacing.h"
#include "tiles/seam_manifold.h"
#include "tiles/tiled_reconstruction.h"

using namespace dbrg;
namespace fs = std::filesystem;

namespace {

// A new empty folder, removed with its contents at the end of the test.
struct Folder {
    fs::path path;
    Folder() {
        const char* parent = std::getenv("TMPDIR");
        path = fs::path(parent ? parent : "/tmp") / ("dbrg_test_out_of_core_" + std::to_string(std::random_device()()));
        fs::create_directory(path);
    }
    ~Folder() { fs::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
    size_t entries() const { return size_t(std::distance(fs::directory_iterator(path), {})); }
};

std::string write_points(const Folder& folder, const std::string& name, const std::vector<double>& xyz) {
    io::MeshData mesh;
    mesh.positions = xyz;
    const std::string path = folder.file(name);
    REQUIRE(io::write_mesh(path, mesh));
    return path;
}

void write_text(const std::string& path, const std::string& text) {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    REQUIRE(file);
    std::fputs(text.c_str(), file);
    std::fclose(file);
}

std::string read_text(const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    REQUIRE(file);
    char text[256] = {};
    const size_t length = std::fread(text, 1, sizeof text - 1, file);
    std::fclose(file);
    return std::string(text, length);
}

std::vector<double> shuffled(const std::vector<double>& xyz) {
    std::vector<size_t> order(xyz.size() / 3);
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    std::vector<double> out;
    for (size_t i : order) out.insert(out.end(), xyz.begin() + 3 * i, xyz.begin() + 3 * i + 3);
    return out;
}

double whole_cloud_spacing(const std::vector<double>& xyz) {
    dbrg_params params;
    dbrg_params_init(&params);
    Context context(params);
    double spacing = 0;
    REQUIRE(estimate_spacing(xyz.data(), xyz.size() / 3, context, spacing) == DBRG_OK);
    return spacing;
}

std::vector<double> read_all(io::PointReader& reader, size_t batch) {
    std::vector<double> all, xyz(3 * batch);
    for (size_t count = 1; count > 0;) {
        REQUIRE(reader.read(xyz.data(), batch, count));
        all.insert(all.end(), xyz.begin(), xyz.begin() + 3 * count);
    }
    return all;
}

// A face by its corners: sorted, or (`oriented`) rotated to start at the smallest, keeping its turn.
std::array<uint32_t, 3> face_key(const uint32_t* t, bool oriented) {
    std::array<uint32_t, 3> key{t[0], t[1], t[2]};
    if (oriented) std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
    else std::sort(key.begin(), key.end());
    return key;
}

// The share of `reference`'s faces that `mesh` has (`oriented`: turned the same way).
double face_agreement(const std::vector<uint32_t>& mesh, const std::vector<uint32_t>& reference, bool oriented = false) {
    std::set<std::array<uint32_t, 3>> faces;
    for (size_t f = 0; f < mesh.size(); f += 3) faces.insert(face_key(&mesh[f], oriented));
    size_t found = 0;
    for (size_t f = 0; f < reference.size(); f += 3) found += faces.count(face_key(&reference[f], oriented));
    return reference.empty() ? 1.0 : double(found) / double(reference.size() / 3);
}

} // namespace

TEST_CASE("points stream from binary and ascii PLY and XYZ as read_mesh reads them, in batches of any size") {
    Folder folder;
    const std::vector<double> xyz = samples::sample(samples::Shape::torus, 3000);
    io::MeshData mesh;
    mesh.positions = xyz;
    const std::string binary = folder.file("points.ply"), xyz_path = folder.file("points.xyz");
    REQUIRE(io::write_mesh(binary, mesh));
    REQUIRE(io::write_mesh(xyz_path, mesh));
    // An element before the vertices, a property before x and a list among them are read past.
    const std::string ascii = folder.file("ascii.ply");
    {
        std::FILE* file = std::fopen(ascii.c_str(), "wb");
        REQUIRE(file);
        std::fputs("ply\nformat ascii 1.0\nelement camera 2\nproperty list uchar float k\nelement vertex 2\n"
                   "property uchar red\nproperty float x\nproperty list uchar int extra\nproperty float y\n"
                   "property double z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
                   "2 1 2\n0\n7 1.5 3 1 2 3 2.5 3.5\n8 -1 0 4.25 0.5\n", file);
        std::fclose(file);
    }
    for (const std::string& path : {binary, xyz_path}) {
        CAPTURE(path);
        io::PointReader reader;
        REQUIRE(reader.open(path));
        CHECK(read_all(reader, 1000) == xyz);
        REQUIRE(reader.rewind());
        CHECK(read_all(reader, 7) == xyz);
    }
    io::PointReader reader;
    REQUIRE(reader.open(ascii));
    CHECK(reader.declared_count() == 2u);
    CHECK(read_all(reader, 1) == std::vector<double>{1.5, 2.5, 3.5, -1, 4.25, 0.5});
    // Past 2^32 points, which a mesh's 32-bit indices refuse, the count is taken (and here found to lie).
    const std::string huge = folder.file("huge.ply");
    {
        std::FILE* file = std::fopen(huge.c_str(), "wb");
        REQUIRE(file);
        std::fputs("ply\nformat binary_little_endian 1.0\nelement vertex 5000000000\nproperty float x\n"
                   "property float y\nproperty float z\nend_header\n", file);
        std::fclose(file);
    }
    REQUIRE(reader.open(huge));
    CHECK(reader.declared_count() == 5000000000u);
    std::vector<double> xyz_batch(3);
    size_t count = 0;
    const io::IoStatus status = reader.read(xyz_batch.data(), 1, count);
    CHECK(status.message.find("declares 5000000000 items, more than the rest of the file can hold") != std::string::npos);
    io::MeshData refused;
    CHECK(io::read_mesh(huge, refused).message.find("at most 4294967294") != std::string::npos);
}

TEST_CASE("streamed passes give the whole cloud's count, box and spacing, whatever the order of the points") {
    Folder folder;
    const std::vector<double> xyz = samples::sample(samples::Shape::double_torus, 20000);
    const double expected = whole_cloud_spacing(xyz);
    std::vector<std::vector<double>> walls;
    for (const std::vector<double>& points : {xyz, shuffled(xyz)}) {
        io::PointReader reader;
        REQUIRE(reader.open(write_points(folder, "cloud.ply", points)));
        out_of_core::CloudSummary summary;
        REQUIRE(out_of_core::summarize(reader, summary));
        CHECK(summary.count == xyz.size() / 3);
        CHECK(summary.axis == 0);  // the double torus is longest along x
        CHECK(summary.low[0] == *std::min_element(points.begin(), points.end()) );
        double spacing = 0;
        REQUIRE(out_of_core::stream_spacing(reader, summary, spacing));
        CHECK(spacing == expected);
        walls.push_back(out_of_core::sample_walls(summary, 4, 12 * spacing));
    }
    CHECK(walls[0].size() == 3);
    CHECK(walls[0] == walls[1]);
}

TEST_CASE("the whole cloud's spacing and walls: the sample's 90th percentile nearest distance, and quantiles") {
    // A random sphere with exact duplicates (distance 0: not a neighbour) and isolated outliers on a
    // lattice around it, farther from everything than the search's 16 rings of cells reach (left out).
    std::vector<double> xyz;
    std::mt19937_64 random(5);
    std::normal_distribution<double> normal;
    for (int i = 0; i < 8000; ++i) {
        const double x = normal(random), y = normal(random), z = normal(random), r = std::sqrt(x * x + y * y + z * z);
        xyz.insert(xyz.end(), {x / r, y / r, z / r});
    }
    xyz.insert(xyz.end(), xyz.begin(), xyz.begin() + 3 * 500);
    for (int i = 0; i < 27; ++i) {
        if (i != 13) xyz.insert(xyz.end(), {4.0 * (i % 3 - 1), 4.0 * (i / 3 % 3 - 1), 4.0 * (i / 9 - 1)});
    }
    const size_t count = xyz.size() / 3;
    double low[3] = {xyz[0], xyz[1], xyz[2]}, high[3] = {xyz[0], xyz[1], xyz[2]};
    for (size_t i = 0; i < count; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            low[axis] = std::min(low[axis], xyz[3 * i + axis]);
            high[axis] = std::max(high[axis], xyz[3 * i + axis]);
        }
    }
    const double cell = spacing_grid_cell(std::max({high[0] - low[0], high[1] - low[1], high[2] - low[2]}), count);
    std::vector<double> nearest;
    size_t outliers = 0;
    for (size_t i = 0; i < count; ++i) {
        if (coordinate_hash(&xyz[3 * i]) % spacing_sample_stride(count) != 0) continue;
        double best = HUGE_VAL;
        for (size_t j = 0; j < count; ++j) {
            // The library's formula, so that the same distance comes out to the last bit.
            const double dx = xyz[3 * j] - xyz[3 * i], dy = xyz[3 * j + 1] - xyz[3 * i + 1], dz = xyz[3 * j + 2] - xyz[3 * i + 2];
            const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
            if (d > 0) best = std::min(best, d);
        }
        // In the cloud, or an outlier beyond 16 rings of cells (16 sqrt(3) cells away at the least).
        REQUIRE((best < 5 * cell || best > 30 * cell));
        if (best < 5 * cell) nearest.push_back(best);
        outliers += best > 30 * cell;
    }
    REQUIRE(nearest.size() > 1000);
    REQUIRE(outliers > 0);
    std::sort(nearest.begin(), nearest.end());
    CHECK(whole_cloud_spacing(xyz) == nearest[nearest.size() * 9 / 10]);

    dbrg_params params;
    dbrg_params_init(&params);
    Context context(params);
    TilingPlan plan(context.memory);
    REQUIRE(plan_tiling(xyz.data(), count, 6, context, plan) == DBRG_OK);
    CHECK(plan.spacing == whole_cloud_spacing(xyz));
    // Quantiles of the coordinates, each kept when its slab is wide enough on both sides.
    std::vector<double> along, expected;
    for (size_t i = 0; i < count; ++i) along.push_back(xyz[3 * i + plan.axis]);
    std::sort(along.begin(), along.end());
    for (size_t k = 1; k < 6; ++k) {
        const double wall = along[count * k / 6], previous = expected.empty() ? along.front() : expected.back();
        const double width = MIN_SLAB_SPACINGS * plan.spacing;
        if (wall - previous >= width && along.back() - wall >= width) expected.push_back(wall);
    }
    REQUIRE(expected.size() >= 2);
    CHECK(std::vector<double>(plan.walls.begin(), plan.walls.end()) == expected);
}

TEST_CASE("each point goes to the bucket files of the slabs whose core and halo hold it, its position its id") {
    Folder folder;
    const std::vector<double> xyz = samples::sample(samples::Shape::torus, 4000);
    io::PointReader reader;
    REQUIRE(reader.open(write_points(folder, "cloud.ply", xyz)));
    const std::vector<double> walls = {-0.5, 0.0, 0.7};
    const double halo = 0.2;
    std::vector<std::string> paths;
    for (size_t k = 0; k <= walls.size(); ++k) paths.push_back(folder.file("bucket" + std::to_string(k)));
    REQUIRE(out_of_core::write_buckets(reader, 0, walls, halo, paths));
    size_t records = 0, expected = 0;
    for (size_t k = 0; k <= walls.size(); ++k) {
        const double low = k == 0 ? -HUGE_VAL : walls[k - 1] - halo, high = k == walls.size() ? HUGE_VAL : walls[k] + halo;
        std::vector<out_of_core::PointRecord> bucket;
        REQUIRE(out_of_core::read_records(paths[k], bucket));
        records += bucket.size();
        for (size_t i = 0; i < xyz.size() / 3; ++i) expected += xyz[3 * i] >= low && xyz[3 * i] < high;
        for (const out_of_core::PointRecord& point : bucket) {
            REQUIRE(point.id < xyz.size() / 3);
            CHECK(std::equal(point.xyz, point.xyz + 3, xyz.begin() + 3 * point.id));
            CHECK(point.xyz[0] >= low);
            CHECK(point.xyz[0] < high);
        }
    }
    CHECK(records == expected);
}

TEST_CASE("a truncated or bad input fails naming the problem, leaving no temporary files and the old output") {
    Folder folder;
    const std::vector<double> xyz = samples::sample(samples::Shape::torus, 3000);
    const std::string whole = write_points(folder, "whole.ply", xyz);
    const std::string output = folder.file("mesh.ply");
    write_text(output, "the old mesh");
    const struct {
        std::string name;
        std::string bytes;
        std::string message;
    } cases[] = {
        {"cut.ply", [&] {
             std::FILE* file = std::fopen(whole.c_str(), "rb");
             std::string bytes(fs::file_size(whole), '\0');
             REQUIRE(std::fread(bytes.data(), 1, bytes.size(), file) == bytes.size());
             std::fclose(file);
             return bytes.substr(0, bytes.size() / 2);
         }(),
         "items, more than the rest of the file can hold"},
        {"cut.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1\n", "XYZ line 5: a point needs three coordinates"},
        {"nan.xyz", "0 0 0\n1 0 0\nnan 1 0\n0 0 1\n", "point 2 (counting from 0) has a non-finite coordinate"},
    };
    for (const auto& c : cases) {
        CAPTURE(c.name);
        const std::string input = folder.file(c.name);
        std::FILE* file = std::fopen(input.c_str(), "wb");
        REQUIRE(file);
        std::fwrite(c.bytes.data(), 1, c.bytes.size(), file);
        std::fclose(file);
        out_of_core::Options options;
        dbrg_params_init(&options.params);
        options.tiles = 3;
        out_of_core::Report report;
        const io::IoStatus status = out_of_core::reconstruct_file(input, output, options, report);
        CHECK_FALSE(status);
        CHECK(status.message.find(c.message) != std::string::npos);
        CHECK(status.message.find(input) == 0);
        CHECK(folder.entries() == 3);  // whole.ply, mesh.ply and the input: no bucket or output temporary
        fs::remove(input);
    }
    CHECK(read_text(output) == "the old mesh");  // the old output, untouched
}

namespace {

struct FileRun {
    io::IoStatus status;
    out_of_core::Report report;
    std::vector<uint32_t> triangles;
};

FileRun reconstruct_file(const Folder& folder, const std::vector<double>& xyz, uint32_t tiles, uint64_t max_memory = 0) {
    FileRun run;
    const std::string input = write_points(folder, "cloud.ply", xyz), output = folder.file("mesh.ply");
    out_of_core::Options options;
    dbrg_params_init(&options.params);
    options.tiles = tiles;
    options.max_memory_bytes = max_memory;
    run.status = out_of_core::reconstruct_file(input, output, options, run.report);
    if (!run.status) return run;
    io::MeshData mesh;
    REQUIRE(io::read_mesh(output, mesh));
    CHECK(mesh.positions == xyz);  // every point a vertex, in input order
    run.triangles = mesh.triangles;
    return run;
}

} // namespace

TEST_CASE("out-of-core meshes of a torus, a double torus and a saddle match the single call and --tiles N") {
    const struct {
        samples::Shape shape;
        size_t points;
    } cases[] = {
        {samples::Shape::torus, 20000}, {samples::Shape::double_torus, 30000}, {samples::Shape::saddle, 20000}};
    for (const auto& c : cases) {
        Folder folder;
        const std::string name = samples::facts(c.shape).name;
        const std::vector<double> xyz = samples::sample(c.shape, c.points);
        const test::Reconstruction single = test::reconstruct(xyz);
        REQUIRE(single.status == DBRG_OK);
        const measure::MeshReport single_report = test::report_of(xyz, single.triangles);
        for (uint32_t tiles : {2u, 3u, 5u}) {
            CAPTURE(name);
            CAPTURE(tiles);
            const FileRun run = reconstruct_file(folder, xyz, tiles);
            REQUIRE_MESSAGE(run.status, run.status.message);
            const measure::MeshReport report = test::report_of(xyz, run.triangles);
            const double agreement = face_agreement(run.triangles, single.triangles);
            const test::Reconstruction tiled_run = test::reconstruct_tiled(xyz, tiles);
            REQUIRE(tiled_run.status == DBRG_OK);
            const std::vector<uint32_t>& tiled = tiled_run.triangles;
            const double tiled_agreement = face_agreement(run.triangles, tiled);
            MESSAGE(name << ", " << tiles << " tiles asked, " << run.report.tiles << " run: face agreement " << agreement
                         << " with the single call, " << tiled_agreement << " with --tiles");
            test::require_valid_manifold(report);
            CHECK(run.report.tiles > 1);
            CHECK(run.report.orientation_conflicts == 0);
            CHECK(report.boundary_loops == single_report.boundary_loops);
            CHECK(report.genus == single_report.genus);
            CHECK(run.report.triangles == run.triangles.size() / 3);
            CHECK(agreement >= 0.995);
            // The walls' sample holds every point of a cloud this small, so the walls and the spacing are
            // dbrg_reconstruct_tiled's and so is the mesh, face for face.
            CHECK(tiled_agreement == 1.0);
            CHECK(run.triangles.size() == tiled.size());
            // Turned as the single call turns its surfaces: closed ones outward, open ones up at the top.
            CHECK(face_agreement(run.triangles, single.triangles, true) >= 0.995);
            if (single_report.boundary_loops == 0) CHECK(test::signed_volume(xyz, run.triangles) > 0);
        }
        CHECK(folder.entries() == 2);  // the input and the mesh: the tiles' folder is gone
    }
}

TEST_CASE("a cancel stops the run between its steps or inside a slab, leaving no temporary files and the old output") {
    Folder folder;
    const std::string input = write_points(folder, "cloud.ply", samples::sample(samples::Shape::torus, 6000));
    const std::string output = folder.file("mesh.ply");
    write_text(output, "the old mesh");
    // The k-th report cancels; reports from inside the slabs and stitches come in among the loop's own.
    struct Countdown {
        int left;
        int reports = 0;
        static int callback(void* user, dbrg_stage, double) {
            Countdown& countdown = *static_cast<Countdown*>(user);
            ++countdown.reports;
            return --countdown.left <= 0;
        }
    };
    Countdown whole{1 << 30};
    out_of_core::Options options;
    dbrg_params_init(&options.params);
    options.tiles = 3;
    options.params.progress = Countdown::callback;
    options.params.progress_user = &whole;
    out_of_core::Report report;
    REQUIRE(out_of_core::reconstruct_file(input, folder.file("complete.ply"), options, report));
    REQUIRE(report.tiles == 3);
    REQUIRE(whole.reports > 20);  // far more than the loop's 3 + 3 + 2 + 1 of its own: the pieces' too
    fs::remove(folder.file("complete.ply"));
    for (int k : {1, 4, 8, whole.reports / 2, whole.reports - 1}) {
        CAPTURE(k);
        Countdown countdown{k};
        options.params.progress_user = &countdown;
        const io::IoStatus status = out_of_core::reconstruct_file(input, output, options, report);
        CHECK_FALSE(status);
        CHECK(status.message.find("cancel") != std::string::npos);
        CHECK(countdown.reports == k);  // no report after the cancel
        CHECK(folder.entries() == 2);   // cloud.ply and mesh.ply: no bucket folder, no output temporary
    }
    CHECK(read_text(output) == "the old mesh");  // the old output, untouched
}

TEST_CASE("a run removes the tile folders killed runs left beside its output, never one in use or just made") {
    Folder folder;
    const std::string input = write_points(folder, "cloud.ply", samples::sample(samples::Shape::torus, 3000));
    const auto make_folder = [&](const std::string& name, bool old) {
        fs::create_directory(folder.file(name));
        std::FILE* bucket = std::fopen(folder.file(name + "/tile-0.points").c_str(), "wb");
        REQUIRE(bucket);
        std::fclose(bucket);
        if (old) fs::last_write_time(folder.file(name), fs::file_time_type::clock::now() - std::chrono::hours(1));
    };
    make_folder(".out.dbrg-tiles-killed", true);
    make_folder(".out.dbrg-tiles-in-use", true);
    make_folder(".out.dbrg-tiles-just-made", false);
    make_folder("not-ours", true);
    const int in_use = open(folder.file(".out.dbrg-tiles-in-use").c_str(), O_RDONLY | O_DIRECTORY);
    REQUIRE(in_use >= 0);
    REQUIRE(flock(in_use, LOCK_EX) == 0);  // as the run that made it holds it

    out_of_core::Options options;
    dbrg_params_init(&options.params);
    options.tiles = 2;
    out_of_core::Report report;
    REQUIRE(out_of_core::reconstruct_file(input, folder.file("mesh.ply"), options, report));
    close(in_use);
    CHECK_FALSE(fs::exists(folder.file(".out.dbrg-tiles-killed")));
    CHECK(fs::exists(folder.file(".out.dbrg-tiles-in-use/tile-0.points")));
    CHECK(fs::exists(folder.file(".out.dbrg-tiles-just-made/tile-0.points")));
    CHECK(fs::exists(folder.file("not-ours/tile-0.points")));
    CHECK(folder.entries() == 5);  // the input, the mesh and the three folders kept: the run's own is gone
}

TEST_CASE("a memory budget sets the number of slabs, and no tile holds more than the budget") {
    Folder folder;
    const std::vector<double> xyz = samples::sample(samples::Shape::torus, 30000);
    const uint64_t points = xyz.size() / 3;
    // Slabs of a quarter of the points, or of a fifth and a halo of a twentieth of them: the quotients
    // rounded up. None when the halo alone takes the budget.
    const auto budget_for = [&](double share) { return uint64_t(out_of_core::BASE_BYTES + share * points * out_of_core::TILE_BYTES_PER_POINT); };
    CHECK(out_of_core::tiles_for_budget(points, budget_for(0.26), 0) == 4);
    CHECK(out_of_core::tiles_for_budget(points, budget_for(0.26), 0.05) == 5);
    CHECK(out_of_core::tiles_for_budget(points, budget_for(0.05), 0.05) == 0);
    CHECK(out_of_core::tiles_for_budget(points, budget_for(1.5), 0.05) == 1);
    const uint64_t budget = budget_for(0.3);
    const FileRun run = reconstruct_file(folder, xyz, 0, budget);
    REQUIRE_MESSAGE(run.status, run.status.message);
    MESSAGE("budget " << budget << " bytes: " << run.report.tiles << " tiles, the largest holding "
                      << run.report.tile_peak_bytes << " bytes");
    CHECK(run.report.tiles >= 4);
    CHECK(run.report.tile_peak_bytes > 0);
    // The library's share: the whole cloud in one piece would hold about three times as much.
    CHECK(run.report.tile_peak_bytes <= budget - uint64_t(out_of_core::BASE_BYTES));
}

namespace {

// The faces left out by faces_breaking_manifold, as sorted corner triples.
std::set<std::array<uint64_t, 3>> left_out(const std::vector<uint64_t>& faces,
                                           const std::unordered_set<uint64_t>& checked) {
    std::set<std::array<uint64_t, 3>> out;
    for (size_t f : out_of_core::faces_breaking_manifold(faces.data(), faces.size() / 3, checked)) {
        std::array<uint64_t, 3> corners{faces[3 * f], faces[3 * f + 1], faces[3 * f + 2]};
        std::sort(corners.begin(), corners.end());
        out.insert(corners);
    }
    return out;
}

} // namespace

TEST_CASE("the seam check leaves out repeated faces, third faces on an edge and the smaller fans of a pinch") {
    // A fan of six faces around vertex 0 (ring 1..6), ids far past 2^32.
    const uint64_t big = uint64_t(1) << 40;
    std::vector<uint64_t> fan;
    for (uint64_t i = 1; i <= 6; ++i) fan.insert(fan.end(), {big, big + i, big + i % 6 + 1});
    const std::unordered_set<uint64_t> centre{big};
    CHECK(left_out(fan, centre).empty());

    std::vector<uint64_t> repeated = fan;
    repeated.insert(repeated.end(), {big + 2, big + 3, big});  // face 2 again, turned
    CHECK(left_out(repeated, centre) == std::set<std::array<uint64_t, 3>>{{big, big + 2, big + 3}});
    CHECK(out_of_core::faces_breaking_manifold(repeated.data(), 7, centre) == std::vector<size_t>{6});

    std::vector<uint64_t> fin = fan;
    fin.insert(fin.end(), {big, big + 1, big + 9});  // a third face on the edge 0-1, taken last by its corners
    CHECK(left_out(fin, centre) == std::set<std::array<uint64_t, 3>>{{big, big + 1, big + 9}});

    // A second fan of two faces touching the first at 0 only: the vertex keeps the larger, the fan of six.
    std::vector<uint64_t> pinched = fan;
    pinched.insert(pinched.end(), {big, big + 7, big + 8, big, big + 8, big + 9});
    CHECK(left_out(pinched, centre) ==
          std::set<std::array<uint64_t, 3>>{{big, big + 7, big + 8}, {big, big + 8, big + 9}});
    // Given in another order, the same faces are left out.
    std::vector<uint64_t> reversed;
    for (size_t f = pinched.size() / 3; f-- > 0;) {
        reversed.insert(reversed.end(), pinched.begin() + 3 * f, pinched.begin() + 3 * f + 3);
    }
    CHECK(left_out(reversed, centre) == left_out(pinched, centre));
    // A vertex not checked is not looked at: the pinch at 0 stays when only the ring is checked, and the
    // fin too when neither end of its edge is checked.
    CHECK(left_out(pinched, {big + 3}).empty());
    CHECK(left_out(fin, {big + 4}).empty());
    // Two fans of equal size: the one holding the first face by its sorted corners stays.
    const std::vector<uint64_t> bowtie{5, 1, 2, 5, 3, 4};
    CHECK(left_out(bowtie, {5}) == std::set<std::array<uint64_t, 3>>{{3, 4, 5}});
}

TEST_CASE("out of core, a Moebius band comes out an oriented manifold: faces are left out where it twists") {
    // A band of half-width 0.25 twisted once around a circle of radius 1, sampled on a jittered grid.
    std::vector<double> xyz;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    const int around = 400, across = 16;
    for (int i = 0; i < around; ++i) {
        for (int j = 0; j < across; ++j) {
            const double u = 2 * M_PI * (i + jitter(random)) / around;
            const double v = 0.25 * (2 * (j + 0.5 + jitter(random)) / across - 1);
            xyz.insert(xyz.end(), {(1 + v * std::cos(u / 2)) * std::cos(u), (1 + v * std::cos(u / 2)) * std::sin(u),
                                   v * std::sin(u / 2)});
        }
    }
    Folder folder;
    for (uint32_t tiles : {2u, 3u, 4u}) {
        CAPTURE(tiles);
        const FileRun run = reconstruct_file(folder, xyz, tiles);
        REQUIRE_MESSAGE(run.status, run.status.message);
        MESSAGE(tiles << " slabs: " << run.report.orientation_conflicts << " conflicts, "
                      << run.report.seam_faces_dropped << " faces left out of " << run.triangles.size() / 3);
        const measure::MeshReport report = test::report_of(xyz, run.triangles);
        test::require_valid_manifold(report);
        CHECK(run.report.boundary_edges == report.edges_boundary);  // counted again where faces were left out
        CHECK(run.report.orientation_conflicts > 0);
        CHECK(run.report.seam_faces_dropped > 0);
    }
}

TEST_CASE("out-of-core meshes of the shared data are manifolds, the seams checked as the assembly checks them" *
          doctest::test_suite(test::SHARED_DATA_SUITE)) {
    const std::string dir = test::shared_data_dir_or_skip();
    if (dir.empty()) return;
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (io::format_from_path(entry.path().filename().string())) names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    REQUIRE_FALSE(names.empty());
    Folder folder;
    for (const std::string& name : names) {
        io::MeshData given;
        REQUIRE(io::read_mesh(dir + "/" + name, given));
        for (uint32_t tiles : {2u, 4u, 8u}) {
            CAPTURE(name);
            CAPTURE(tiles);
            const FileRun run = reconstruct_file(folder, given.positions, tiles);
            REQUIRE_MESSAGE(run.status, run.status.message);
            const test::Reconstruction tiled = test::reconstruct_tiled(given.positions, tiles);
            REQUIRE(tiled.status == DBRG_OK);
            const measure::MeshReport report = test::report_of(given.positions, run.triangles);
            MESSAGE(name << " at " << tiles << ": " << run.report.seam_faces_dropped << " seam faces left out ("
                         << tiled.stats.seam_faces_dropped << " by --tiles), " << run.report.orientation_conflicts
                         << " orientation conflicts; face agreement with --tiles "
                         << face_agreement(run.triangles, tiled.triangles));
            test::require_valid_manifold(report);
            CHECK(run.report.boundary_edges == report.edges_boundary);
        }
    }
}
