// Point cleaning: from every point's nearest neighbours, the outliers (far sparser than the rest), the
// near-duplicates (much closer than the local spacing) and a noise estimate (the misfit of a local quadric
// at two neighbourhood sizes); when the points are noisy, a few rounds of projection onto local quadrics.
// Every rule compares a point with its own neighbourhood or the median of all points, so a clean sample
// (no such point, no noise) passes through untouched.
#include "points/point_cleaning.h"

#include <math.h>
#include <string.h>

#include <algorithm>

#include "core/parallel.h"
#include "core/progress_span.h"
#include "core/status.h"
#include "core/vec3.h"
#include "points/local_fit.h"
#include "points/neighbour_search.h"

namespace dbrg {
namespace {

// Neighbours of a point for its spacing and its local fit: enough for a quadric's 6 terms to be
// overdetermined by a margin (the residual of pure noise is then sqrt(1 - 6/17) = 0.80 of it).
constexpr uint32_t NEIGHBOURS = 16;
// The wider neighbourhood of the noise estimate's second scale.
constexpr uint32_t WIDE_NEIGHBOURS = 32;
// Fewer points than this and the wider neighbourhood is more than a sixteenth of the cloud: a neighbourhood
// no longer tells local from global, and the stage leaves the points as they are.
constexpr uint32_t MIN_POINTS = 16 * WIDE_NEIGHBOURS;
// The noise estimate fits every this-many-th point along the curve: a median over an eighth of the points,
// spread evenly over the surface, is as telling as over all of them, for a quarter of the cost ...
constexpr uint32_t NOISE_SAMPLE_STRIDE = 8;
// ... and over this many points at most, a stride of more than 8 for more than 65,536 points: the median's
// standard error is then about 1.4 % of the spread of the misfits, far below the margins of the rules.
constexpr uint32_t NOISE_SAMPLES = 8192;

// A point whose NEIGHBOURS-th neighbour is this many times farther than the median point's sits where the
// sample is about this squared (36) times sparser than typical (clean samples, meshes' vertices and
// simulated scans alike, stay below 4.2) ...
constexpr double OUTLIER_GLOBAL_FACTOR = 6.0;
// Either way, it is an outlier only if its neighbours sample no surface it lies on: a sparse part of a
// surface (a scan's far side, an unevenly decimated mesh's smooth part, next to a dense one) is as sparse,
// but its points lie within a small share of their spacing of the surface their neighbours fit, while a
// point in empty space is about as far from that surface as from them.
constexpr double OFF_SURFACE_SHARE = 0.25;
// ... or this many times farther than the median of its own neighbours': the point stands off a surface
// its neighbours sample densely. (Clean samples stay below 2.6: a border or a density gradient doubles
// it at most.)
constexpr double OUTLIER_LOCAL_FACTOR = 3.0;

// Two points closer than this share of the NEIGHBOURS-th neighbour's distance (of either) are one surface
// point measured twice: no sampling a surface could be grown from varies its spacing by 10^4 within a
// neighbourhood, and the pair would only give needle triangles.
constexpr double NEAR_DUPLICATE_SHARE = 1e-4;

// The points are noisy when the median misfit of a local quadric is above this share of the mean distance
// to the neighbours (noise of about 1/16 of the spacing; below that growing is not hurt) ...
constexpr double NOISE_LEVEL = 0.05;
// ... and the misfit hardly grows from NEIGHBOURS to WIDE_NEIGHBOURS: noise gives the same misfit at every
// scale (1.12x from the fit's degrees of freedom), a shape the quadric misses a misfit that grows with the
// cube of the radius (2.8x). Below this ratio, noise makes up more than about 16/17 of the squared misfit
// (shape misfit under a quarter of the noise): the misfit is noise, not a coarse sample of a curved shape.
constexpr double NOISE_SCALE_RATIO = 1.36;

// ... and the points' distances from their local quadrics are spread like noise: the median over the mean is
// 0.85 for a Gaussian (less after the fit's leverage; 0.76-0.79 measured on noisy scans, 0.88-0.91 with
// misregistered views), 1 when every point is about as far as the others, as on two sheets closer than the
// spacing (a thin plate sampled coarsely), which smoothing would fold into one.
constexpr double NOISE_SPREAD_LIMIT = 0.95;

// Projections onto the local quadric, each over the positions the last one gave (neighbourhoods fixed). Two
// leave handles on some simulated scans (the noisy bunny, a rough cheburashka) that three do not.
constexpr uint32_t SMOOTHING_ITERATIONS = 3;


enum PointFlag : uint8_t { KEPT = 0, OUTLIER = 1, MERGED = 2 };

double median_of(double* values, size_t count) {
    std::nth_element(values, values + count / 2, values + count);
    return values[count / 2];
}

Vec3 point_of(const double* xyz, uint32_t i) { return load_vec3(xyz + 3 * size_t(i)); }

// The fit over point i and its kept neighbours among the first `wanted` of its list, at `xyz`.
LocalFit fit_around(const double* xyz, uint32_t i, const uint32_t* list, uint32_t wanted, const uint8_t* flags) {
    Vec3 offsets[WIDE_NEIGHBOURS + 1];
    uint32_t count = 0;
    const Vec3 point = point_of(xyz, i);
    offsets[count++] = Vec3{0, 0, 0};
    for (uint32_t j = 0; j < wanted; ++j) {
        if (flags[list[j]] == KEPT) offsets[count++] = point_of(xyz, list[j]) - point;
    }
    return fit_local_quadric(offsets, count);
}

class Cleaner {
public:
    Cleaner(ConditionedPoints& points, Context& context)
        : points_(points), context_(context), n_(points.size()), neighbours_(context.memory),
          spacing_(context.memory), flags_(context.memory), positions_(context.memory),
          parts_(part_count(context.params.threads, points.size(), MIN_POINTS_PER_THREAD)) {}

    dbrg_status run(Array<uint32_t>& outliers) {
        const ProgressSpan stage(context_, DBRG_STAGE_CLEAN);
        DBRG_PROPAGATE(stage.report(0, 1));
        // Too few points to tell a point's neighbourhood from the whole cloud: nothing to judge.
        if (n_ < MIN_POINTS) return stage.report(1, 1);
        bool noisy = false;
        {
            // The tree's memory goes back before smoothing.
            NeighbourIndex index(context_.memory);
            DBRG_PROPAGATE(index.build(points_.coordinates.data(), n_, stage.part(0.0, 0.1)));
            DBRG_PROPAGATE(find_nearest_neighbours(index, NEIGHBOURS, stage.part(0.1, 0.4), k_, neighbours_));
            if (!flags_.resize(n_, KEPT) || !spacing_.resize(n_)) return context_.fail_out_of_memory();
            DBRG_PROPAGATE(find_outliers(stage.part(0.4, 0.45)));
            DBRG_PROPAGATE(merge_near_duplicates(stage.part(0.45, 0.5)));
            DBRG_PROPAGATE(estimate_noise(index, stage.part(0.5, 0.6), noisy));
        }
        if (noisy || context_.params.cleaning == DBRG_CLEANING_ON) DBRG_PROPAGATE(smooth(stage.part(0.7, 0.85)));
        neighbours_.release();
        DBRG_PROPAGATE(list_outliers(outliers));
        const dbrg_stats& stats = context_.stats;
        if (stats.outliers > 0 || stats.near_duplicates_merged > 0 || stats.points_smoothed > 0) {
            DBRG_PROPAGATE(rebuild(stage.part(0.85, 1.0)));
        }
        return stage.report(1, 1);
    }

private:
    const uint32_t* list(uint32_t i) const { return neighbours_.data() + size_t(k_) * i; }

    double distance(uint32_t a, uint32_t b) const {
        return length(point_of(points_.coordinates.data(), a) - point_of(points_.coordinates.data(), b));
    }

    dbrg_status find_outliers(const ProgressSpan& progress) {
        for (uint32_t i = 0; i < n_; ++i) spacing_[i] = distance(i, list(i)[NEIGHBOURS - 1]);
        Array<double> sorted(context_.memory);
        if (!sorted.resize(n_)) return context_.fail_out_of_memory();
        memcpy(sorted.data(), spacing_.data(), n_ * sizeof(double));
        const double typical = median_of(sorted.data(), n_);
        sorted.release();
        DBRG_PROPAGATE(progress.for_each_step(n_, parts_, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) {
                double around[NEIGHBOURS];
                double smallest = INFINITY;
                for (uint32_t j = 0; j < NEIGHBOURS; ++j) {
                    around[j] = spacing_[list(uint32_t(i))[j]];
                    smallest = std::min(smallest, around[j]);
                }
                // The median is at least the smallest: most points pass without it.
                const bool locally = spacing_[i] > OUTLIER_LOCAL_FACTOR * smallest &&
                                     spacing_[i] > OUTLIER_LOCAL_FACTOR * median_of(around, NEIGHBOURS);
                const bool sparse = (locally || spacing_[i] > OUTLIER_GLOBAL_FACTOR * typical) && off_surface(uint32_t(i));
                flags_[i] = sparse ? OUTLIER : KEPT;
            }
        }));
        uint32_t count = 0;
        for (uint32_t i = 0; i < n_; ++i) count += flags_[i] == OUTLIER;
        context_.stats.outliers = count;
        return DBRG_OK;
    }

    // Whether point i is farther than OFF_SURFACE_SHARE of its spacing from the local quadric that fits its
    // neighbours (without it).
    bool off_surface(uint32_t i) const {
        Vec3 offsets[NEIGHBOURS];
        const Vec3 point = point_of(points_.coordinates.data(), i);
        for (uint32_t j = 0; j < NEIGHBOURS; ++j) offsets[j] = point_of(points_.coordinates.data(), list(i)[j]) - point;
        return fabs(fit_local_quadric(offsets, NEIGHBOURS).height) > OFF_SURFACE_SHARE * spacing_[i];
    }

    // Greedy along the numbering (which depends on the coordinates only): a kept point absorbs the later
    // kept points within the threshold, so a merged group is never wider than twice the threshold (no chains).
    dbrg_status merge_near_duplicates(const ProgressSpan& progress) {
        uint32_t merged = 0;
        for (uint32_t i = 0; i < n_; ++i) {
            DBRG_PROPAGATE(progress.report_at(i, n_));
            if (flags_[i] != KEPT) continue;
            for (uint32_t j = 0; j < NEIGHBOURS; ++j) {
                const uint32_t other = list(i)[j];
                const double d = distance(i, other);
                // Nearest first: none of the rest is within the threshold either.
                if (!(d < NEAR_DUPLICATE_SHARE * spacing_[i])) break;
                if (other < i || flags_[other] != KEPT) continue;
                if (d < NEAR_DUPLICATE_SHARE * std::min(spacing_[i], spacing_[other])) {
                    flags_[other] = MERGED;
                    ++merged;
                }
            }
        }
        context_.stats.near_duplicates_merged = merged;
        return DBRG_OK;
    }

    // Fits at both scales around every stride-th kept point.
    dbrg_status estimate_noise(const NeighbourIndex& index, const ProgressSpan& progress, bool& noisy) {
        const uint32_t stride = std::max(NOISE_SAMPLE_STRIDE, (n_ + NOISE_SAMPLES - 1) / NOISE_SAMPLES);
        const uint32_t samples = (n_ + stride - 1) / stride;
        Array<double> narrow(context_.memory), wide(context_.memory), offset(context_.memory);
        if (!narrow.resize(samples, -1.0) || !wide.resize(samples, -1.0) || !offset.resize(samples, -1.0)) {
            return context_.fail_out_of_memory();
        }
        const double* xyz = points_.coordinates.data();
        const uint32_t parts = part_count(context_.params.threads, samples, MIN_POINTS_PER_THREAD / NOISE_SAMPLE_STRIDE);
        DBRG_PROPAGATE(progress.for_each_step(samples, parts, [&](size_t begin, size_t end) {
            NearestHint hint;  // samples a stride apart along the curve are still near each other
            for (size_t s = begin; s < end; ++s) {
                const uint32_t v = uint32_t(s * stride);
                if (flags_[v] != KEPT) continue;
                uint32_t around[WIDE_NEIGHBOURS];
                const uint32_t found = index.nearest(v, WIDE_NEIGHBOURS, around, &hint);
                double mean_distance = 0;
                for (uint32_t j = 0; j < NEIGHBOURS; ++j) mean_distance += distance(v, around[j]);
                mean_distance /= NEIGHBOURS;
                if (!(mean_distance > 0)) continue;
                const LocalFit fit = fit_around(xyz, v, around, NEIGHBOURS, flags_.data());
                narrow[s] = fit.rms / mean_distance;
                offset[s] = fabs(fit.height) / mean_distance;
                wide[s] = fit_around(xyz, v, around, found, flags_.data()).rms / mean_distance;
            }
        }));
        // The kept samples' values, at the front of each array.
        size_t kept = 0;
        for (size_t s = 0; s < samples; ++s) {
            if (narrow[s] < 0) continue;
            narrow[kept] = narrow[s];
            wide[kept] = wide[s];
            offset[kept] = offset[s];
            ++kept;
        }
        if (kept == 0) return DBRG_OK;
        const double level = median_of(narrow.data(), kept), wide_level = median_of(wide.data(), kept);
        double mean_offset = 0;
        for (size_t s = 0; s < kept; ++s) mean_offset += offset[s];
        mean_offset /= double(kept);
        const double median_offset = median_of(offset.data(), kept);
        context_.stats.noise_level = level;
        noisy = level > NOISE_LEVEL && wide_level < NOISE_SCALE_RATIO * level &&
                median_offset < NOISE_SPREAD_LIMIT * mean_offset;
        return DBRG_OK;
    }

    dbrg_status smooth(const ProgressSpan& progress) {
        Array<double> next(context_.memory);
        if (!positions_.resize(3 * size_t(n_)) || !next.resize(3 * size_t(n_))) return context_.fail_out_of_memory();
        memcpy(positions_.data(), points_.coordinates.data(), 3 * size_t(n_) * sizeof(double));
        memcpy(next.data(), positions_.data(), 3 * size_t(n_) * sizeof(double));
        for (uint32_t round = 0; round < SMOOTHING_ITERATIONS; ++round) {
            const double* from = positions_.data();
            double* to = next.data();
            DBRG_PROPAGATE(progress.part(double(round) / SMOOTHING_ITERATIONS, double(round + 1) / SMOOTHING_ITERATIONS)
                               .for_each_step(n_, parts_, [&](size_t begin, size_t end) {
                for (size_t i = begin; i < end; ++i) {
                    if (flags_[i] != KEPT) continue;
                    const LocalFit fit = fit_around(from, uint32_t(i), list(uint32_t(i)), NEIGHBOURS, flags_.data());
                    const Vec3 moved = point_of(from, uint32_t(i)) + fit.height * fit.normal;
                    to[3 * i] = moved.x;
                    to[3 * i + 1] = moved.y;
                    to[3 * i + 2] = moved.z;
                }
            }));
            positions_.swap(next);
        }
        uint32_t kept = 0;
        for (uint32_t i = 0; i < n_; ++i) kept += flags_[i] == KEPT;
        context_.stats.points_smoothed = kept;
        context_.stats.smoothing_iterations = SMOOTHING_ITERATIONS;
        return DBRG_OK;
    }

    dbrg_status list_outliers(Array<uint32_t>& outliers) {
        outliers.clear();
        if (!outliers.reserve(context_.stats.outliers)) return context_.fail_out_of_memory();
        for (uint32_t i = 0; i < n_; ++i) {
            if (flags_[i] == OUTLIER) outliers.push_back(points_.input_index[i]);
        }
        std::sort(outliers.begin(), outliers.end());
        return DBRG_OK;
    }

    // The kept points (smoothed where smoothed) conditioned and numbered again, each standing for its
    // caller index.
    dbrg_status rebuild(const ProgressSpan& progress) {
        const double* from = positions_.empty() ? points_.coordinates.data() : positions_.data();
        Array<double> kept_xyz(context_.memory);
        Array<uint32_t> kept_index(context_.memory);
        size_t kept = 0;
        for (uint32_t i = 0; i < n_; ++i) kept += flags_[i] == KEPT;
        if (!kept_xyz.reserve(3 * kept) || !kept_index.reserve(kept)) return context_.fail_out_of_memory();
        // In the caller's frame (exactly the caller's coordinates for points not moved), so that the new
        // conditioning's translation and scale are again the caller's.
        for (uint32_t i = 0; i < n_; ++i) {
            if (flags_[i] != KEPT) continue;
            for (int a = 0; a < 3; ++a) {
                kept_xyz.push_back(ldexp(from[3 * size_t(i) + a], -points_.scale_exponent) + points_.origin[a]);
            }
            kept_index.push_back(points_.input_index[i]);
        }
        positions_.release();
        flags_.release();
        spacing_.release();
        ConditionedPoints fresh(context_.memory);
        DBRG_PROPAGATE(condition_points(kept_xyz.data(), kept, progress.part(0.0, 0.6), fresh));
        kept_xyz.release();
        for (uint32_t v = 0; v < fresh.size(); ++v) fresh.input_index[v] = kept_index[fresh.input_index[v]];
        DBRG_PROPAGATE(renumber_spatially(fresh, progress.part(0.6, 1.0)));
        // Smoothing may bring two points onto one: merged like near-duplicates.
        context_.stats.near_duplicates_merged += fresh.duplicates_merged;
        points_.coordinates.swap(fresh.coordinates);
        points_.input_index.swap(fresh.input_index);
        for (int a = 0; a < 3; ++a) points_.origin[a] = fresh.origin[a];
        points_.scale_exponent = fresh.scale_exponent;
        points_.order = fresh.order;
        return DBRG_OK;
    }

    ConditionedPoints& points_;
    Context& context_;
    const uint32_t n_;
    uint32_t k_ = 0;
    Array<uint32_t> neighbours_;
    Array<double> spacing_;
    Array<uint8_t> flags_;
    Array<double> positions_;  // smoothed positions, when smoothed
    const uint32_t parts_;
};

} // namespace

dbrg_status clean_points(ConditionedPoints& points, Context& context, Array<uint32_t>& outliers) {
    Cleaner cleaner(points, context);
    return cleaner.run(outliers);
}

} // namespace dbrg
