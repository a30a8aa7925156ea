#include "direct_view.h"

#include "rng.h"

namespace glint {

DirectViewSplit::DirectViewSplit(const Scene& scene, int width, int height, int rays)
    : width_(width), height_(height), rays_(rays) {
    if (rays > 0 && (!scene.lights().empty() || !is_black(scene.background())))
        split_.assign(size_t(width) * height, 0);
}

void DirectViewSplit::decide(const PathTracer& tracer, const Camera& camera, Filter filter, int x0, int y0, int x1,
                             int y1) {
    if (!active()) return;
    // Probe centres spread evenly over the footprint [-margin, 1 + margin]² of the pixel.
    const double margin = filter_margin(filter), step = (1 + 2 * margin) / kProbesPerAxis;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const uint64_t pixel = uint64_t(y) * width_ + x;
            const double row_from_bottom = height_ - 1 - y;
            Rgb first{0};
            bool varies = false;
            for (int i = 0; i < kProbesPerAxis * kProbesPerAxis && !varies; ++i) {
                Rng rng(0, pixel, uint64_t(i));  // for a lens and deep glass: fixed, not the job's seed
                const double fx = x - margin + (i % kProbesPerAxis + 0.5) * step;
                const double fy = row_from_bottom - margin + (i / kProbesPerAxis + 0.5) * step;
                const Ray ray = camera.generate(fx, fy, rng.uniform(), rng.uniform());
                const Rgb seen = tracer.radiance(ray, rng, {}, nullptr, DirectView::alone);
                if (i == 0) first = seen;
                varies = seen.x != first.x || seen.y != first.y || seen.z != first.z;
            }
            split_[pixel] = varies;
        }
}

}  // namespace glint
