#include "render/direct_view.h"

#include <cmath>

#include "render/sampler.h"
#include "scene/bsdf.h"

namespace glint {

namespace {

bool may_see_direct_view(const Scene& scene, const Camera& camera, Filter filter) {
    if (!is_black(scene.background())) return true;
    if (scene.environment() && scene.environment()->settings().visible) return true;
    if (scene.sun() && !scene.sun()->is_delta()) return true;
    const Geometry& geometry = scene.geometry();
    for (uint32_t prim = 0; prim < geometry.primitive_count(); ++prim) {
        const Material& m = scene.material(prim);
        if (m.is_emissive() || scene.flags(prim).is_specular()) {
            const Bounds3 box = geometry.is_sphere(prim) ? geometry.sphere(prim).bounds() : geometry.triangle(prim).bounds();
            if (camera.may_see(box, filter_margin(filter))) return true;
        }
    }
    return false;
}

}  // namespace

DirectViewSplit::DirectViewSplit(const Scene& scene, const Camera& camera, Filter filter, int width, int height,
                                 int rays)
    : filter_(filter), width_(width), height_(height), rays_(rays) {
    if (rays > 0 && may_see_direct_view(scene, camera, filter)) split_.assign(size_t(width) * height, 0);
}

Rgb DirectViewSplit::probe(const PathTracer& tracer, const Camera& camera, double fx, double fy, uint64_t key) {
    Rng rng = probe_stream(key);  // for a lens and deep glass: fixed, not the job's seed
    const double lens1 = rng.uniform(), lens2 = rng.uniform();
    return tracer.radiance(camera.generate(fx, fy, lens1, lens2), rng, kNoLightPath, nullptr, DirectView::alone);
}

void DirectViewSplit::decide(const PathTracer& tracer, const Camera& camera, int x0, int y0, int x1, int y1) {
    if (!active()) return;
    // The footprint [-margin, 1 + margin] of a pixel holds probes 0..3 of the pixel, spaced so
    // that the next pixel's start `per_pixel` probes further on: 2 per pixel for the tent's 1.5
    // pixels, 3 for the box's 1.
    const double margin = filter_margin(filter_), spacing = (1 + 2 * margin) / (kProbesPerFootprint - 1);
    const int per_pixel = int(std::lround(1 / spacing));
    const int columns = (x1 - x0 - 1) * per_pixel + kProbesPerFootprint, rows = (y1 - y0 - 1) * per_pixel + kProbesPerFootprint;
    const uint64_t grid_width = uint64_t(width_ - 1) * per_pixel + kProbesPerFootprint;
    std::vector<Rgb> seen(size_t(columns) * rows);
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            // Rows of probes, like pixels, from the top; the film's y counts from the bottom.
            const int gx = x0 * per_pixel + i, gy = y0 * per_pixel + j;
            const double fx = gx * spacing - margin, fy = height_ + margin - gy * spacing;
            seen[size_t(j) * columns + i] = probe(tracer, camera, fx, fy, uint64_t(gy) * grid_width + gx);
        }
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const Rgb* corner = &seen[size_t(y - y0) * per_pixel * columns + size_t(x - x0) * per_pixel];
            bool varies = false;
            for (int j = 0; j < kProbesPerFootprint; ++j)
                for (int i = 0; i < kProbesPerFootprint; ++i) {
                    varies = varies || corner[size_t(j) * columns + i] != *corner;
                }
            split_[size_t(y) * width_ + x] = varies;
        }
}

}  // namespace glint
