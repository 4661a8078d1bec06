// dbrg-progress-gaps: how long a caller waits, at worst, between two progress reports (and so for a cancel
// to be seen) while dbrg_reconstruct (or dbrg_tetrahedralize) works on a generated sample.
//
// The callback records the wall-clock time of every report; the call's start and return count as reports
// too, so the wait before the first report and after the last one are measured as well.
// Usage: dbrg-progress-gaps [--points N] [--shape NAME] [--threads N] [--tetrahedralize] [--over SECONDS]
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <chrono>
#include <vector>

#include "dbrg/dbrg.h"
#include "samples/samples.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Report {
    int stage;  // -1: the call's start or return
    double fraction;
    Clock::time_point time;
};

const char* stage_name(int stage) {
    static const char* const NAMES[] = {"validate", "sort", "delaunay", "grow", "fill_holes", "output"};
    return stage >= 0 && stage < 6 ? NAMES[stage] : "call";
}

int record(void* user, dbrg_stage stage, double fraction) {
    auto& reports = *static_cast<std::vector<Report>*>(user);
    if (reports.size() < reports.capacity()) reports.push_back(Report{static_cast<int>(stage), fraction, Clock::now()});
    return 0;
}

double seconds_between(const Report& a, const Report& b) {
    return std::chrono::duration<double>(b.time - a.time).count();
}

void describe(const char* label, const Report& a, const Report& b) {
    printf("%s %.3f s, from %s %.3f to %s %.3f\n", label, seconds_between(a, b), stage_name(a.stage), a.fraction,
           stage_name(b.stage), b.fraction);
}

} // namespace

int main(int argc, char** argv) {
    size_t points = 1000000;
    const char* shape_name = "bumpy_sphere";
    uint32_t threads = 0;
    bool tetrahedralize = false;
    double over = -1;  // list every gap longer than this; below 0, none
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--points") && i + 1 < argc) {
            points = strtoull(argv[++i], nullptr, 10);
        } else if (!strcmp(argv[i], "--shape") && i + 1 < argc) {
            shape_name = argv[++i];
        } else if (!strcmp(argv[i], "--threads") && i + 1 < argc) {
            threads = static_cast<uint32_t>(strtoul(argv[++i], nullptr, 10));
        } else if (!strcmp(argv[i], "--tetrahedralize")) {
            tetrahedralize = true;
        } else if (!strcmp(argv[i], "--over") && i + 1 < argc) {
            over = strtod(argv[++i], nullptr);
        } else {
            fprintf(stderr, "usage: %s [--points N] [--shape NAME] [--threads N] [--tetrahedralize] [--over SECONDS]\n",
                    argv[0]);
            return 2;
        }
    }
    dbrg::samples::Shape shape;
    if (!dbrg::samples::shape_from_name(shape_name, shape)) {
        fprintf(stderr, "unknown shape '%s'\n", shape_name);
        return 2;
    }
    const Clock::time_point generating = Clock::now();
    const std::vector<double> xyz = dbrg::samples::sample(shape, points);
    printf("%s, %zu points (generated in %.1f s), threads %u\n", shape_name, xyz.size() / 3,
           std::chrono::duration<double>(Clock::now() - generating).count(), threads);

    std::vector<Report> reports;
    reports.reserve(1 << 20);  // reserved up front: the callback must not allocate while it is timed
    dbrg_params params;
    dbrg_params_init(&params);
    params.threads = threads;
    params.progress = record;
    params.progress_user = &reports;
    const dbrg_points input = {xyz.data(), xyz.size() / 3, 3 * sizeof(double), DBRG_FLOAT64};
    dbrg_mesh* mesh = nullptr;
    dbrg_tetrahedralization* tets = nullptr;
    reports.push_back(Report{-1, 0.0, Clock::now()});
    const dbrg_status status = tetrahedralize ? dbrg_tetrahedralize(&input, &params, &tets)
                                              : dbrg_reconstruct(&input, &params, &mesh);
    reports.push_back(Report{-1, 1.0, Clock::now()});
    dbrg_stats stats;
    stats.struct_size = sizeof stats;
    dbrg_mesh_stats(mesh, &stats);
    dbrg_mesh_destroy(mesh);
    dbrg_tetrahedralization_destroy(tets);
    if (status != DBRG_OK) {
        fprintf(stderr, "%s: %s\n", tetrahedralize ? "dbrg_tetrahedralize" : "dbrg_reconstruct", dbrg_status_string(status));
        return 1;
    }
    printf("%.2f s in all", seconds_between(reports.front(), reports.back()));
    if (mesh) {
        printf(" (validate %.2f, sort %.2f, delaunay %.2f, grow %.2f, fill_holes %.2f, output %.2f)",
               stats.seconds_validate, stats.seconds_sort, stats.seconds_delaunay, stats.seconds_grow,
               stats.seconds_fill_holes, stats.seconds_output);
    }
    printf("\n");

    // Per stage: the gap before its first report (the end of the stage before it, the start of its own
    // work) and the largest gap between two of its own reports.
    const int STAGES = 6;
    size_t largest = 1, count[STAGES] = {}, entering[STAGES] = {}, within[STAGES] = {};
    for (size_t i = 1; i < reports.size(); ++i) {
        const double gap = seconds_between(reports[i - 1], reports[i]);
        if (gap > seconds_between(reports[largest - 1], reports[largest])) largest = i;
        const int s = reports[i].stage;
        if (s < 0 || s >= STAGES) continue;
        ++count[s];
        size_t& best = reports[i - 1].stage == s ? within[s] : entering[s];
        if (best == 0 || gap > seconds_between(reports[best - 1], reports[best])) best = i;
    }
    printf("%zu reports\n", reports.size() - 2);
    for (int s = 0; s < STAGES; ++s) {
        printf("%-10s %5zu reports\n", stage_name(s), count[s]);
        if (entering[s]) describe("  entering", reports[entering[s] - 1], reports[entering[s]]);
        if (within[s]) describe("  within  ", reports[within[s] - 1], reports[within[s]]);
    }
    if (over >= 0) {
        printf("gaps over %.3f s:\n", over);
        for (size_t i = 1; i < reports.size(); ++i) {
            if (seconds_between(reports[i - 1], reports[i]) > over) describe("  ", reports[i - 1], reports[i]);
        }
    }
    describe("after the last report", reports[reports.size() - 2], reports.back());
    describe("largest gap:", reports[largest - 1], reports[largest]);
    return 0;
}
