// End-to-end tests of dbrg_reconstruct: the manifold promise on every output, closed shapes closed with
// the right genus, open shapes keeping their borders, and results independent of order, scale and type.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/pi.h"
#include "dbrg/dbrg.h"
#include "delaunay_test_support.h"
#include "io/mesh_io.h"
#include "measure/mesh_report.h"
#include "samples/samples.h"
#include "support/mesh_checks.h"
#include "support/quality_suite.h"
#include "support/shared_data.h"

using namespace dbrg;

namespace {

// Reconstructs `xyz` with the defaults and checks the result is one closed oriented manifold of `genus`.
test::Reconstruction reconstruct_closed(const std::vector<double>& xyz, int genus) {
    test::Reconstruction result = test::reconstruct(xyz);
    REQUIRE(result.status == DBRG_OK);
    const measure::MeshReport report = test::report_of(xyz, result.triangles);
    test::require_valid_manifold(report);
    CHECK(report.components == 1);
    CHECK(report.edges_boundary == 0);
    REQUIRE(report.genus.has_value());
    CHECK(*report.genus == genus);
    return result;
}

// Reconstructs `xyz` with the defaults and checks the result is one oriented manifold with `loops` borders.
test::Reconstruction reconstruct_open(const std::vector<double>& xyz, int loops) {
    test::Reconstruction result = test::reconstruct(xyz);
    REQUIRE(result.status == DBRG_OK);
    const measure::MeshReport report = test::report_of(xyz, result.triangles);
    test::require_valid_manifold(report);
    CHECK(report.components == 1);
    CHECK(report.boundary_loops == uint64_t(loops));
    CHECK(result.boundary_loops == uint32_t(loops));
    return result;
}

} // namespace

TEST_CASE("closed sample shapes come out as closed oriented manifolds of the right genus") {
    const struct {
        samples::Shape shape;
        size_t points;
    } cases[] = {
        {samples::Shape::sphere, 2000},       {samples::Shape::bumpy_sphere, 5000},
        {samples::Shape::torus, 4000},        {samples::Shape::double_torus, 8000},
    };
    for (const auto& c : cases) {
        const samples::ShapeFacts facts = samples::facts(c.shape);
        const std::string name = facts.name;
        CAPTURE(name);
        const std::vector<double> xyz = samples::sample(c.shape, c.points);
        const test::Reconstruction result = reconstruct_closed(xyz, facts.genus);
        CHECK(test::report_of(xyz, result.triangles).vertices == xyz.size() / 3);
        CHECK(test::signed_volume(xyz, result.triangles) > 0);  // outward
    }
}

TEST_CASE("open sample shapes keep their borders and bridge no opening") {
    const samples::Shape shapes[] = {samples::Shape::hemisphere, samples::Shape::open_cylinder, samples::Shape::saddle};
    for (samples::Shape shape : shapes) {
        const samples::ShapeFacts facts = samples::facts(shape);
        const std::string name = facts.name;
        CAPTURE(name);
        const std::vector<double> xyz = samples::sample(shape, 3000);
        const test::Reconstruction result = reconstruct_open(xyz, facts.boundary_loops);
        // A triangle across an opening would have an edge far longer than the sample spacing.
        CHECK(test::longest_edge(xyz, result.triangles) < 4 * test::median_edge(xyz, result.triangles));
    }
}

TEST_CASE("closed shapes sampled unevenly, as a decimated mesh's vertices are, come out closed with their genus") {
    // Density falling 30 times from bottom to top, the cells 2 or 4 times longer one way: the paper's
    // open-surface test against the mean over the whole surface refuses the ordinary triangles of the
    // sparse parts, and hole filling must tell those loops from borders.
    const samples::Shape shapes[] = {samples::Shape::sphere, samples::Shape::bumpy_sphere, samples::Shape::torus,
                                     samples::Shape::double_torus, samples::Shape::capped_cylinder};
    for (samples::Shape shape : shapes) {
        for (double stretch : {2.0, 4.0}) {
            const samples::ShapeFacts facts = samples::facts(shape);
            const std::string name = facts.name;
            CAPTURE(name);
            CAPTURE(stretch);
            reconstruct_closed(samples::sample_clustered(shape, 4000, 30, stretch), facts.genus);
        }
    }
}

TEST_CASE("uniformly random points on a sphere come out closed: folds over a hole are enlarged away") {
    // Random (not evenly spaced) samples have clumps, and growing can fold the surface over a small hole:
    // the faces around it overlap it, so every ear turns over. Two enlargements left a hole open on these
    // two (and on 1 to 23 holes of 100k to 500k points); four close them.
    for (uint64_t seed : {6, 8}) {
        CAPTURE(seed);
        const std::vector<double> xyz = dbrg_test::random_sphere(20000, seed);
        const test::Reconstruction result = reconstruct_closed(xyz, 0);
        CHECK(test::signed_volume(xyz, result.triangles) > 0);
    }
}

TEST_CASE("open shapes sampled unevenly keep their borders, and only those") {
    const samples::Shape shapes[] = {samples::Shape::hemisphere, samples::Shape::open_cylinder, samples::Shape::saddle};
    for (samples::Shape shape : shapes) {
        const samples::ShapeFacts facts = samples::facts(shape);
        const std::string name = facts.name;
        CAPTURE(name);
        reconstruct_open(samples::sample_clustered(shape, 4000, 30, 2), facts.boundary_loops);
    }
}

TEST_CASE("a clustered hemisphere keeps its border loop alone: folds next to the border are closed too" * doctest::test_suite(test::QUALITY_SUITE)) {
    // Growing can pull a vertex across a small hole next to the border (a pleat of one vertex: every ear
    // folds), and enlarging such a hole runs it into the border, so it stayed open: about a quarter of
    // these samples kept a second loop (77 of seeds 1-300), 23 of 300 once the pulled corner's
    // faces are replaced by the triangles of their rim (HoleFiller::fill_without_a_corner). Seeds 1-80
    // here: 62 with the border alone before, 70 since; the bound lies between.
    uint32_t one_loop = 0;
    for (uint64_t seed = 1; seed <= 80; ++seed) {
        const std::vector<double> xyz = samples::sample_clustered(samples::Shape::hemisphere, 4000, 30, 2, seed);
        const test::Reconstruction result = test::reconstruct(xyz);
        REQUIRE(result.status == DBRG_OK);
        const measure::MeshReport report = test::report_of(xyz, result.triangles);
        test::require_valid_manifold(report);
        CHECK(report.boundary_loops >= 1);
        one_loop += report.boundary_loops == 1 && report.components == 1 ? 1 : 0;
    }
    CHECK(one_loop >= 66);
}

namespace {

// A torus tessellated with nearly equilateral triangles: `around` points on each of `rows` circles of the
// tube, every other circle turned by half a step, each point then moved along the surface by up to
// `jitter` steps. Its vertices are the input, the mesh the reference.
io::MeshData staggered_torus(uint32_t around, uint32_t rows, double jitter) {
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> shift(-jitter, jitter);
    io::MeshData mesh;
    for (uint32_t j = 0; j < rows; ++j) {
        for (uint32_t i = 0; i < around; ++i) {
            const double u = 2 * PI * (i + 0.5 * (j % 2) + shift(random)) / around;
            const double v = 2 * PI * (j + shift(random)) / rows;
            const double radius = 2 + 0.7 * std::cos(v);
            mesh.positions.insert(mesh.positions.end(), {radius * std::cos(u), radius * std::sin(u), 0.7 * std::sin(v)});
        }
    }
    const auto at = [&](uint32_t i, uint32_t j) { return (j % rows) * around + i % around; };
    for (uint32_t j = 0; j < rows; ++j) {
        for (uint32_t i = 0; i < around; ++i) {
            // Row j + 1 sits half a step ahead of row j when j is even, behind it when j is odd.
            const uint32_t ahead = j % 2 == 0 ? i : i + 1;
            mesh.triangles.insert(mesh.triangles.end(), {at(i, j), at(i + 1, j), at(ahead, j + 1)});
            mesh.triangles.insert(mesh.triangles.end(), {at(i + 1, j), at(ahead + 1, j + 1), at(ahead, j + 1)});
        }
    }
    mesh.has_faces = true;
    return mesh;
}

// Face recall and the distances both ways between the reconstruction `triangles` of the reference's
// vertices and the reference, in units of the reference's mean side length.
struct Comparison {
    double recall = 0;
    double to_max = 0, to_mean = 0, from_max = 0, from_mean = 0;
};

Comparison compare(const io::MeshData& reference, const std::vector<uint32_t>& triangles) {
    io::MeshData mesh;
    mesh.positions = reference.positions;
    mesh.triangles = triangles;
    measure::MeshReport report;
    REQUIRE(measure::add_face_recall(mesh, reference, report).ok);
    REQUIRE(measure::add_reference_distance(mesh, reference, report).ok);
    REQUIRE(report.face_recall.has_value());
    REQUIRE(report.reference_distance.has_value());
    const measure::ReferenceDistance& d = *report.reference_distance;
    REQUIRE(d.side_mean.has_value());
    REQUIRE(d.to_reference.has_value());
    REQUIRE(d.from_reference.has_value());
    const double side = *d.side_mean;
    const Comparison c{*report.face_recall, d.to_reference->max / side, d.to_reference->mean / side,
                       d.from_reference->max / side, d.from_reference->mean / side};
    MESSAGE("recall " << c.recall << "; in side lengths, distance to the reference " << c.to_max << " at most, "
                      << c.to_mean << " on average; from it " << c.from_max << ", " << c.from_mean);
    return c;
}

// The bars of the shared data's models, in side lengths: on average the reconstruction and the model
// part by a small fraction of a side, and nowhere by more than a few sides. Measured on 2026-12-01 on the
// seven models checked: on average at most 0.009 one way and 0.016 the other (the cow); at most 4.6
// (where hole filling closes the cheburashka's neck; CGAL's advancing front has 5.0 on the bunny's base).
void check_close_to(const io::MeshData& reference, const std::vector<uint32_t>& triangles) {
    const Comparison c = compare(reference, triangles);
    CHECK(c.to_mean < 0.05);
    CHECK(c.from_mean < 0.05);
    CHECK(c.to_max < 6);
    CHECK(c.from_max < 6);
}

} // namespace

TEST_CASE("a tessellated torus's vertices give back its surface: its triangles, and nothing away from it") {
    for (double jitter : {0.0, 0.1, 0.25}) {
        CAPTURE(jitter);
        const io::MeshData reference = staggered_torus(120, 40, jitter);
        const test::Reconstruction result = test::reconstruct(reference.positions);
        REQUIRE(result.status == DBRG_OK);
        const measure::MeshReport report = test::report_of(reference.positions, result.triangles);
        test::require_valid_manifold(report);
        REQUIRE(report.genus.has_value());
        CHECK(*report.genus == 1);
        const Comparison c = compare(reference, result.triangles);
        // Where the jittered points make the other diagonal of two reference triangles the Delaunay one, the
        // two surfaces part by a small fraction of a side; a triangle bridging or spanning anything would
        // have sample points a side or more away.
        CHECK(c.recall >= (jitter == 0 ? 1.0 : 0.9));
        CHECK(c.to_max < 0.25);
        CHECK(c.from_max < 0.25);
    }
}

TEST_CASE("the same points in another order give the same triangles") {
    std::vector<double> xyz = samples::sample(samples::Shape::torus, 3000);
    const test::Reconstruction first = test::reconstruct(xyz);
    REQUIRE(first.status == DBRG_OK);

    std::vector<size_t> order(xyz.size() / 3);
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), std::mt19937(12345));
    std::vector<double> shuffled(xyz.size());
    for (size_t i = 0; i < order.size(); ++i) {
        for (int k = 0; k < 3; ++k) shuffled[3 * i + k] = xyz[3 * order[i] + k];
    }
    const test::Reconstruction second = test::reconstruct(shuffled);
    REQUIRE(second.status == DBRG_OK);
    CHECK(test::triangles_by_position(xyz, first.triangles) == test::triangles_by_position(shuffled, second.triangles));
}

TEST_CASE("scaling or translating by a power of two keeps the connectivity") {
    // Coordinates on a grid of 2^-30 so that adding 1024 is exact.
    std::vector<double> xyz = samples::sample(samples::Shape::double_torus, 3000);
    for (double& x : xyz) x = std::ldexp(std::round(std::ldexp(x, 30)), -30);
    const test::Reconstruction reference = test::reconstruct(xyz);
    REQUIRE(reference.status == DBRG_OK);
    for (double scale : {0x1p-900, 0x1p-20, 0x1p+20, 0x1p+900}) {
        CAPTURE(scale);
        std::vector<double> scaled(xyz);
        for (double& x : scaled) x *= scale;
        const test::Reconstruction result = test::reconstruct(scaled);
        REQUIRE(result.status == DBRG_OK);
        CHECK(result.triangles == reference.triangles);
    }
    std::vector<double> moved(xyz);
    for (double& x : moved) x += 1024.0;
    const test::Reconstruction result = test::reconstruct(moved);
    REQUIRE(result.status == DBRG_OK);
    CHECK(result.triangles == reference.triangles);
}

TEST_CASE("float32 input gives the same mesh as the same values in float64") {
    const std::vector<double> xyz = samples::sample(samples::Shape::bumpy_sphere, 2000);
    std::vector<float> as_float(xyz.begin(), xyz.end());
    const std::vector<double> widened(as_float.begin(), as_float.end());
    const test::Reconstruction from_double = test::reconstruct(widened);
    dbrg_points points{as_float.data(), as_float.size() / 3, 3 * sizeof(float), DBRG_FLOAT32};
    const test::Reconstruction from_float = test::reconstruct(points);
    REQUIRE(from_double.status == DBRG_OK);
    REQUIRE(from_float.status == DBRG_OK);
    CHECK(from_double.triangles == from_float.triangles);
}

TEST_CASE("duplicated points are merged and refer to their first index") {
    std::vector<double> xyz = samples::sample(samples::Shape::sphere, 500);
    const size_t n = xyz.size() / 3;
    xyz.insert(xyz.end(), xyz.begin(), xyz.begin() + 30);  // points 0..9 again, as n..n+9
    const test::Reconstruction result = test::reconstruct(xyz);
    REQUIRE(result.status == DBRG_OK);
    CHECK(result.stats.duplicates_merged == 10);
    CHECK(*std::max_element(result.triangles.begin(), result.triangles.end()) < n);
}

TEST_CASE("degenerate inputs fail with a status that names the problem; a flat grid is a flat square") {
    std::vector<double> plane;
    for (int i = 0; i < 10; ++i) {
        for (int j = 0; j < 10; ++j) plane.insert(plane.end(), {double(i), double(j), 5.0});
    }
    const test::Reconstruction flat = test::reconstruct(plane);
    CHECK(flat.status == DBRG_OK);
    CHECK(flat.triangles.size() / 3 == 2 * 9 * 9);  // every cell of the grid, split once
    CHECK(flat.boundary_loops == 1);
    std::vector<double> line;
    for (int i = 0; i < 10; ++i) line.insert(line.end(), {double(i), 2.0 * i, 3.0 * i});
    CHECK(test::reconstruct(line).status == DBRG_ERR_DEGENERATE_INPUT);
    const std::vector<double> same(30, 1.5);
    CHECK(test::reconstruct(same).status == DBRG_ERR_TOO_FEW_POINTS);
}

TEST_CASE("a lattice cube's surface, massively cospherical, is still a valid manifold") {
    std::vector<double> xyz;
    const int n = 12;
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
            for (int k = 0; k <= n; ++k) {
                if (i == 0 || j == 0 || k == 0 || i == n || j == n || k == n) xyz.insert(xyz.end(), {double(i), double(j), double(k)});
            }
        }
    }
    const test::Reconstruction result = test::reconstruct(xyz);
    REQUIRE(result.status == DBRG_OK);
    const measure::MeshReport report = test::report_of(xyz, result.triangles);
    test::require_valid_manifold(report);
    MESSAGE("lattice cube: " << report.faces << " faces, " << report.edges_boundary << " boundary edges");
}

TEST_CASE("the TetGen backend gives the same surface, or says it is not built in") {
    const std::vector<double> xyz = samples::sample(samples::Shape::torus, 3000);
    dbrg_params params;
    dbrg_params_init(&params);
    params.backend = DBRG_BACKEND_TETGEN;
    const test::Reconstruction with_tetgen = test::reconstruct(xyz, &params);
#ifdef DBRG_HAVE_TETGEN
    REQUIRE(with_tetgen.status == DBRG_OK);
    CHECK(with_tetgen.triangles == test::reconstruct(xyz).triangles);
#else
    CHECK(with_tetgen.status == DBRG_ERR_UNSUPPORTED);
#endif
}

TEST_CASE("the closed models of the shared data come out closed, the bunny keeps its openings, all stay near their meshes" *
          doctest::test_suite(test::SHARED_DATA_SUITE)) {
    const std::string dir = test::shared_data_dir_or_skip();
    if (dir.empty()) return;
    // The folder is there, so every model must be read. The cow's mouth and the cheburashka's legs and neck come closer to themselves than the sample
    // spacing; growing bridges them there, and the small handles this makes are removed after hole filling.
    const struct {
        const char* file;
        int genus;
        bool bridged;  // growing bridges sheets closer than the spacing: small handles must be cut
    } closed[] = {{"spot.obj", 0, false},      {"fandisk.obj", 0, false}, {"homer.off", 0, false},
                  {"rocker-arm.off", 1, false}, {"cow.ply", 0, true},      {"cheburashka.off", 0, true}};
    for (const auto& model : closed) {
        CAPTURE(std::string(model.file));
        io::MeshData mesh;
        const io::IoStatus read = io::read_mesh(dir + "/" + model.file, mesh);
        INFO(read.message);
        REQUIRE(read.ok);
        const test::Reconstruction result = test::reconstruct(mesh.positions);
        REQUIRE(result.status == DBRG_OK);
        const measure::MeshReport report = test::report_of(mesh.positions, result.triangles);
        test::require_valid_manifold(report);
        CHECK(report.edges_boundary == 0);
        REQUIRE(report.genus.has_value());
        CHECK(*report.genus == model.genus);
        CHECK((result.stats.handles_removed > 0) == model.bridged);
        check_close_to(mesh, result.triangles);
    }
    io::MeshData bunny;
    const io::IoStatus read = io::read_mesh(dir + "/stanford-bunny.obj", bunny);
    INFO(read.message);
    REQUIRE(read.ok);
    const test::Reconstruction result = test::reconstruct(bunny.positions);
    REQUIRE(result.status == DBRG_OK);
    // The scan has five openings at its base; the smallest one, 22 edges, may be filled.
    CHECK(test::report_of(bunny.positions, result.triangles).boundary_loops >= 4);
    check_close_to(bunny, result.triangles);
}

namespace {

struct Snapshots {
    std::vector<std::vector<uint32_t>> triangles;
    std::vector<double> reached;
    size_t cancel_at = SIZE_MAX;  // return non-zero from this call on

    // Default parameters asking this object for `count` snapshots.
    dbrg_params params(uint32_t count) {
        dbrg_params p;
        dbrg_params_init(&p);
        p.snapshot = take;
        p.snapshot_user = this;
        p.snapshot_count = count;
        return p;
    }

    static int take(void* user, const uint32_t* triangles, uint32_t count, double points_reached) {
        Snapshots& s = *static_cast<Snapshots*>(user);
        s.triangles.emplace_back(triangles, triangles + 3 * size_t(count));
        s.reached.push_back(points_reached);
        return s.triangles.size() > s.cancel_at ? 1 : 0;
    }
};

} // namespace

TEST_CASE("snapshots show growth at evenly spaced shares of the points, each oriented with manifold edges") {
    const std::vector<double> xyz = samples::sample(samples::Shape::torus, 3000);
    const test::Reconstruction plain = test::reconstruct(xyz);
    REQUIRE(plain.status == DBRG_OK);
    for (uint32_t count : {1u, 5u}) {
        CAPTURE(count);
        Snapshots snapshots;
        const dbrg_params params = snapshots.params(count);
        const test::Reconstruction result = test::reconstruct(xyz, &params);
        REQUIRE(result.status == DBRG_OK);
        CHECK(result.triangles == plain.triangles);  // watching does not change the outcome
        REQUIRE(snapshots.triangles.size() == count);
        for (size_t k = 0; k < count; ++k) {
            CAPTURE(k);
            if (k + 1 < count) {
                CHECK(snapshots.reached[k] >= double(k + 1) / count);
                CHECK(snapshots.reached[k] < double(k + 1) / count + 0.01);  // taken as the share is passed
            }
            if (k > 0) CHECK(snapshots.triangles[k].size() > snapshots.triangles[k - 1].size());
            // Fronts may touch at a vertex before they join, so a bow-tie vertex is allowed while growing.
            const measure::MeshReport report = test::report_of(xyz, snapshots.triangles[k]);
            CHECK(report.edges_nonmanifold == 0);
            CHECK(report.oriented);
            CHECK(report.degenerate_faces == 0);
            CHECK(report.duplicate_faces == 0);
        }
        CHECK(snapshots.reached.back() > 0.99);
    }
}

TEST_CASE("a snapshot count larger than the steps of growth gives at most one snapshot per step") {
    const std::vector<double> xyz = samples::sample(samples::Shape::sphere, 300);
    Snapshots snapshots;
    const dbrg_params params = snapshots.params(UINT32_MAX);
    REQUIRE(test::reconstruct(xyz, &params).status == DBRG_OK);
    CHECK(snapshots.triangles.size() > 100);
    CHECK(snapshots.triangles.size() <= 2 * xyz.size() / 3);  // no more than the faces grown
}

TEST_CASE("a snapshot count above DBRG_MAX_SNAPSHOTS is taken as DBRG_MAX_SNAPSHOTS") {
    // Found by fuzzing: one snapshot for each of a few thousand points copied the surface each time.
    const std::vector<double> xyz = samples::sample(samples::Shape::sphere, 3000);
    for (uint32_t asked : {DBRG_MAX_SNAPSHOTS + 1, UINT32_MAX}) {
        Snapshots snapshots;
        const dbrg_params params = snapshots.params(asked);
        REQUIRE(test::reconstruct(xyz, &params).status == DBRG_OK);
        CHECK(snapshots.triangles.size() == DBRG_MAX_SNAPSHOTS);
    }
}

TEST_CASE("a snapshot callback can cancel") {
    const std::vector<double> xyz = samples::sample(samples::Shape::sphere, 2000);
    Snapshots snapshots;
    snapshots.cancel_at = 1;
    const dbrg_params params = snapshots.params(4);
    CHECK(test::reconstruct(xyz, &params).status == DBRG_ERR_CANCELLED);
    CHECK(snapshots.triangles.size() == 2);
}

TEST_CASE("validation and output report progress inside the stage, not only at its ends") {
    const std::vector<double> xyz = samples::sample(samples::Shape::sphere, 2000);
    struct Log {
        std::vector<std::pair<dbrg_stage, double>> reports;
        static int record(void* user, dbrg_stage stage, double fraction) {
            static_cast<Log*>(user)->reports.emplace_back(stage, fraction);
            return 0;
        }
    } log;
    dbrg_params params;
    dbrg_params_init(&params);
    params.progress = Log::record;
    params.progress_user = &log;
    REQUIRE(test::reconstruct(xyz, &params).status == DBRG_OK);
    // Sorting takes the order validation's renumbering left: it reports its ends only.
    for (dbrg_stage stage : {DBRG_STAGE_VALIDATE, DBRG_STAGE_OUTPUT}) {
        CAPTURE(stage);
        CHECK(std::any_of(log.reports.begin(), log.reports.end(), [stage](const std::pair<dbrg_stage, double>& r) {
            return r.first == stage && r.second > 0.0 && r.second < 1.0;
        }));
    }
    // Stages in the pipeline's order (cleaning, appended to the enum later, comes after validation), each
    // one's fractions in order.
    const auto rank = [](dbrg_stage stage) { return stage == DBRG_STAGE_CLEAN ? 0.5 : double(stage); };
    bool in_order = true;
    for (size_t i = 1; i < log.reports.size(); ++i) {
        const auto &a = log.reports[i - 1], &b = log.reports[i];
        in_order = in_order && (rank(b.first) > rank(a.first) || (b.first == a.first && b.second >= a.second));
    }
    CHECK(in_order);
    CHECK(std::any_of(log.reports.begin(), log.reports.end(),
                      [](const std::pair<dbrg_stage, double>& r) { return r.first == DBRG_STAGE_CLEAN && r.second == 1.0; }));
}

// The cleaning stage is invisible on clean samples: the same triangles with it on (automatic) and off.
void check_cleaning_changes_nothing(const std::vector<double>& xyz) {
    dbrg_params params;
    dbrg_params_init(&params);
    params.cleaning = DBRG_CLEANING_OFF;
    const test::Reconstruction off = test::reconstruct(xyz, &params);
    params.cleaning = DBRG_CLEANING_AUTO;
    const test::Reconstruction automatic = test::reconstruct(xyz, &params);
    REQUIRE(off.status == DBRG_OK);
    REQUIRE(automatic.status == DBRG_OK);
    CHECK(automatic.stats.outliers == 0);
    CHECK(automatic.stats.near_duplicates_merged == 0);
    CHECK(automatic.stats.points_smoothed == 0);
    CHECK(automatic.triangles == off.triangles);
}

TEST_CASE("cleaning changes nothing on the generated clean samples" * doctest::test_suite(test::QUALITY_SUITE)) {
    using samples::Shape;
    for (Shape shape : {Shape::sphere, Shape::torus, Shape::double_torus, Shape::bumpy_sphere, Shape::hemisphere,
                        Shape::open_cylinder, Shape::saddle, Shape::cube, Shape::capped_cylinder, Shape::graded_sphere,
                        Shape::thin_plate}) {
        CAPTURE(samples::facts(shape).name);
        // Coarse samples too: 1,200 points put the thin plate's two sides within one neighbourhood, which
        // must not pass for noise.
        for (size_t count : {size_t(20000), size_t(1200)}) {
            CAPTURE(count);
            check_cleaning_changes_nothing(samples::sample(shape, count));
        }
        // Sampled unevenly: the sparse end, 30 times sparser, is no outlier.
        for (uint64_t seed : {1, 2}) {
            CAPTURE(seed);
            check_cleaning_changes_nothing(samples::sample_clustered(shape, 4000, 30, 4, seed));
        }
    }
}

TEST_CASE("cleaning changes nothing on the vertices of the shared data meshes" * doctest::test_suite(test::SHARED_DATA_SUITE)) {
    const std::string dir = test::shared_data_dir_or_skip();
    if (dir.empty()) return;
    size_t meshes = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string extension = entry.path().extension().string();
        if (extension != ".obj" && extension != ".off" && extension != ".ply") continue;
        CAPTURE(entry.path().string());
        io::MeshData mesh;
        const io::IoStatus read = io::read_mesh(entry.path().string(), mesh);
        INFO(read.message);
        REQUIRE(read.ok);
        check_cleaning_changes_nothing(mesh.positions);
        ++meshes;
    }
    CHECK(meshes > 0);
}

namespace {

// A face by its corners, rotated to start at the smallest: the same face whatever its place in the output.
std::array<uint32_t, 3> face_key(const std::vector<uint32_t>& triangles, size_t t) {
    std::array<uint32_t, 3> key{triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
    std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
    return key;
}

} // namespace

TEST_CASE("the faces hole filling made are flagged, and only those") {
    // A torus sample with the points near one spot of its outer equator taken out: growing leaves a hole
    // there, which filling closes.
    const std::vector<double> full = samples::sample(samples::Shape::torus, 3000);
    std::vector<double> xyz;
    for (size_t i = 0; i < full.size(); i += 3) {
        const double dx = full[i] - 1.35, dy = full[i + 1], dz = full[i + 2];
        if (dx * dx + dy * dy + dz * dz > 0.2 * 0.2) xyz.insert(xyz.end(), &full[i], &full[i] + 3);
    }
    dbrg_params params;
    dbrg_params_init(&params);
    params.fill_holes = 0;
    const test::Reconstruction open = test::reconstruct(xyz, &params);
    const test::Reconstruction filled = test::reconstruct(xyz);
    REQUIRE(open.status == DBRG_OK);
    REQUIRE(filled.status == DBRG_OK);
    REQUIRE(filled.stats.holes_filled > 0);
    REQUIRE(open.face_flags.size() == open.triangles.size() / 3);
    REQUIRE(filled.face_flags.size() == filled.triangles.size() / 3);
    CHECK(std::count(open.face_flags.begin(), open.face_flags.end(), 0) == long(open.face_flags.size()));

    // What filling started from: the faces growing made, and the vertices it left on a boundary or unused.
    std::vector<std::array<uint32_t, 3>> grown;
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    for (size_t t = 0; t < open.triangles.size() / 3; ++t) {
        grown.push_back(face_key(open.triangles, t));
        for (size_t i = 0; i < 3; ++i) edges.emplace_back(open.triangles[3 * t + i], open.triangles[3 * t + (i + 1) % 3]);
    }
    std::sort(grown.begin(), grown.end());
    std::sort(edges.begin(), edges.end());
    std::vector<uint8_t> at_gap(xyz.size() / 3, 1);
    for (uint32_t v : open.triangles) at_gap[v] = 0;
    for (const auto& [a, b] : edges) {
        if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(b, a))) at_gap[a] = at_gap[b] = 1;
    }
    REQUIRE(open.boundary_loops > 0);

    // Filling changes S only at the gaps: a face it made touches one, and a face growing made is not one of them.
    size_t flagged = 0, flagged_grown = 0, flagged_away = 0;
    for (size_t t = 0; t < filled.triangles.size() / 3; ++t) {
        if ((filled.face_flags[t] & DBRG_FACE_FILLED) == 0) continue;
        const auto key = face_key(filled.triangles, t);
        ++flagged;
        flagged_grown += std::binary_search(grown.begin(), grown.end(), key);
        flagged_away += !at_gap[key[0]] && !at_gap[key[1]] && !at_gap[key[2]];
    }
    CHECK(flagged > 0);
    CHECK(flagged_grown == 0);
    CHECK(flagged_away == 0);
    // The unflagged faces are those growing made, or what flips made of two of them (two for two): no more.
    CHECK(flagged + grown.size() >= filled.triangles.size() / 3);
}
