// Splitting off the direct view (integrator.h's DirectView: what the camera sees through
// specular vertices only) in the pixels where it varies: the light's edge, its outline in a
// mirror or through glass. There a few pixels hold much of the image's squared error, because a
// pixel the light half covers gets 0 or the light's radiance (12 in smallpt's box) from each
// sample. There each sample estimates the direct view from `rays` extra camera rays, which end
// at their first diffuse vertex, and the sample's own path leaves it out; elsewhere
// the path gathers it as usual. Either way the pixel's estimate is unbiased, so which pixels
// split only decides where the extra rays are spent.
//
// Which pixels split is decided once per job, from probe rays on a grid over the film: a pixel
// splits if the 4 × 4 probes spanning its filter footprint see different direct views.
// Neighbouring footprints overlap, and the grid is laid so they share their probes (half-pixel
// spacing for the tent filter: 4 probes per pixel). The decision depends on neither the seed nor
// the sample range, so the parts of a job split over machines decide alike.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/camera.h"
#include "render/filter.h"
#include "render/integrator.h"

namespace glint {

class DirectViewSplit {
public:
    static constexpr int kProbesPerFootprint = 4;  // along each axis

    // `rays` extra camera rays per sample where a pixel splits. None splits (and nothing is
    // probed) if rays is 0, or if the background is black and the camera can see no emitter,
    // mirror or glass (by their bounding boxes against the view pyramid).
    DirectViewSplit(const Scene& scene, const Camera& camera, Filter filter, int width, int height, int rays);

    // Whether decide() has anything to do.
    bool active() const { return !split_.empty(); }
    int rays() const { return rays_; }
    // Decides for the pixels in [x0, x1) × [y0, y1) (rows from the top); disjoint regions may be
    // decided concurrently.
    void decide(const PathTracer& tracer, const Camera& camera, int x0, int y0, int x1, int y1);
    bool splits(int x, int y) const { return active() && split_[size_t(y) * width_ + x] != 0; }

private:
    // The direct view seen at film position (fx, fy); `key` names the probe.
    static Rgb probe(const PathTracer& tracer, const Camera& camera, double fx, double fy, uint64_t key);

    Filter filter_;
    int width_, height_, rays_;
    std::vector<uint8_t> split_;  // per pixel; empty when inactive
};

}  // namespace glint
