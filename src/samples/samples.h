// Sample point sets on known surfaces, for the demo, the tests and the benchmarks: evenly spread
// (Poisson-disk) points on closed and open shapes whose genus and boundaries are known.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace dbrg::samples {

enum class Shape {
    sphere,         // unit sphere: closed, genus 0
    torus,          // radii 1 and 0.35: closed, genus 1
    double_torus,   // closed, genus 2
    bumpy_sphere,   // a sphere with bumps: closed, genus 0, curvature varies
    hemisphere,     // open: one boundary loop
    open_cylinder,  // open: two boundary loops
    saddle,         // the patch z = x^2 - y^2 over [-1, 1]^2 (the paper's hypersheet): one boundary loop
    cube,           // the surface of a cube: closed, genus 0, sharp edges and corners
    capped_cylinder,// a cylinder with flat caps: closed, genus 0, two circular sharp edges
    graded_sphere,  // a sphere sampled 10 times more densely at one pole than at the other: closed, genus 0
    thin_plate,     // a 2 x 2 x 0.08 box: closed, genus 0, two large faces close together
};

// What is known about a shape's surface.
struct ShapeFacts {
    const char* name;
    int genus;
    int boundary_loops;
};

ShapeFacts facts(Shape shape);

// The shape named `name` ("sphere", "torus", ...); returns false when there is none.
bool shape_from_name(std::string_view name, Shape& shape);

// About `count` points (within a few percent) on `shape`, no two closer than a common spacing, as
// x, y, z triples. Deterministic for a given seed.
std::vector<double> sample(Shape shape, size_t count, uint64_t seed = 1);

// About `count` points (within a few percent) on `shape` spread as the vertices of a mesh decimated
// unevenly: one random point per cell of a grid whose cells grow along z, so that the density falls
// `density_ratio` times from the bottom to the top, and are `stretch` times as long in x as in y.
// Unlike sample's, two points may be much closer than the spacing (across a cell wall). Deterministic
// for a given seed.
std::vector<double> sample_clustered(Shape shape, size_t count, double density_ratio, double stretch, uint64_t seed = 1);

} // namespace dbrg::samples
