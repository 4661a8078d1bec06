// dbrg-bench-neighbours: the cleaning stage's neighbour work on a point file (the points conditioned and
// numbered along the Hilbert curve as `dbrg reconstruct` does): the tree, the 16 nearest of every point and the
// 32 nearest of every 8th, searched from each query's leaf with hints (as the stage searches) and, as the
// reference in the same run, from the root alone. Prints the median processor seconds of each over the rounds
// (taken in turn), their ratio, and whether the two gave the same lists.
// Usage: dbrg-bench-neighbours FILE.xyz [--rounds N]
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <algorithm>
#include <vector>

#include "core/context.h"
#include "points/neighbour_search.h"
#include "points/point_conditioning.h"

using namespace dbrg;

namespace {

double processor_seconds() {
    timespec now;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

// The tree and every search of one round; the lists go to `lists`. Returns the processor seconds taken.
double run_round(const ConditionedPoints& points, Context& context, bool from_root, std::vector<uint32_t>& lists) {
    const uint32_t n = points.size();
    lists.assign(size_t(16) * n + size_t(32) * ((n + 7) / 8), 0);
    const double start = processor_seconds();
    NeighbourIndex index(context.memory);
    if (index.build(points.coordinates.data(), n, ProgressSpan(context, DBRG_STAGE_CLEAN)) != DBRG_OK) exit(1);
    uint32_t* out = lists.data();
    for (uint32_t wide = 0; wide < 2; ++wide) {
        const uint32_t k = wide ? 32 : 16, stride = wide ? 8 : 1;
        NearestHint hint;
        for (uint32_t v = 0; v < n; v += stride, out += k) {
            if (from_root) index.nearest_from_root(v, k, out);
            else index.nearest(v, k, out, &hint);
        }
    }
    return processor_seconds() - start;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: dbrg-bench-neighbours FILE.xyz [--rounds N]\n");
        return 2;
    }
    int rounds = 5;
    for (int a = 2; a + 1 < argc; a += 2) {
        if (strcmp(argv[a], "--rounds") == 0) rounds = std::max(1, atoi(argv[a + 1]));
    }
    FILE* file = fopen(argv[1], "r");
    if (file == nullptr) {
        fprintf(stderr, "cannot open %s\n", argv[1]);
        return 1;
    }
    std::vector<double> xyz;
    double x, y, z;
    while (fscanf(file, "%lf %lf %lf%*[^\n]", &x, &y, &z) == 3) xyz.insert(xyz.end(), {x, y, z});
    fclose(file);
    dbrg_params params;
    memset(&params, 0, sizeof params);
    params.struct_size = sizeof params;
    params.threads = 1;
    Context context(params);
    ConditionedPoints points(context.memory);
    if (condition_points(xyz.data(), xyz.size() / 3, context, points) != DBRG_OK ||
        renumber_spatially(points, context) != DBRG_OK) {
        fprintf(stderr, "%s: %s\n", argv[1], context.message());
        return 1;
    }
    std::vector<double> leaf_first, root;
    std::vector<uint32_t> lists, reference;
    for (int round = 0; round < rounds; ++round) {
        leaf_first.push_back(run_round(points, context, false, lists));
        root.push_back(run_round(points, context, true, reference));
    }
    printf("%u points, %d rounds: from the leaf %.4f s, from the root %.4f s (median processor seconds), ratio %.3f; "
           "lists %s\n",
           points.size(), rounds, median(leaf_first), median(root), median(leaf_first) / median(root),
           lists == reference ? "the same" : "DIFFERENT");
    return lists == reference ? 0 : 1;
}
