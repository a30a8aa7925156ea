// An equirectangular image of the light around a scene, with what sampling it needs: the
// texels as linear RGB and a distribution over its cells. It is what a file gives, whatever the
// strength and rotation a scene uses it with (scene/environment.h), so that a service builds it
// once per file and shares it between the jobs that use it.
//
// Image coordinates: u from the image's left edge, v from its top row, both in [0, 1]; the row
// at v has latitude θ = π(1/2 − v), z = sin θ.
#pragma once

#include <span>
#include <vector>

#include "base/distribution.h"
#include "base/math.h"
#include "scene/texture.h"

namespace glint {

class EnvironmentMap {
public:
    // width·height linear RGB texels, rows top first; none negative or non-finite (the loader
    // makes sure). Throws std::invalid_argument for a size below 1 or a vector of another size.
    EnvironmentMap(int width, int height, std::vector<float> rgb);
    // From a decoded image: float texels as they are, 8-bit ones decoded from sRGB; one or two
    // channels are grey, a fourth (alpha) is left out.
    static EnvironmentMap from_texture(const Texture& image);

    int width() const { return width_; }
    int height() const { return height_; }
    std::span<const float> texels() const { return rgb_; }  // linear RGB, rows top first
    size_t memory_bytes() const;

    // Bilinear between texel centres, wrapping around in u and held at the poles in v.
    Rgb lookup(double u, double v) const;
    // A point (u, z = sin θ) of the image, in proportion to the luminance above the map's mean
    // over each texel's cell (all of it where nothing is above the mean) weighted by the cell's
    // solid angle, and uniform in solid angle within the cell; its solid-angle density. False
    // where the image is black. The density is zero in the cells below the mean: it is for
    // light sampling that BSDF sampling completes by MIS.
    bool sample(double u1, double u2, double& u, double& z, double& pdf) const;
    double pdf(double u, double v) const;
    // ∫ luminance dω over the sphere.
    double luminance_integral() const { return luminance_integral_; }

private:
    Rgb texel(int i, int j) const;  // i wrapped, j held to the image
    double cell_weight(int i, int j) const;
    double cell_solid_angle(int row) const;
    double cell_pdf(size_t column, size_t row) const;  // solid-angle density of sampling in that cell

    int width_, height_;
    std::vector<float> rgb_;
    Distribution2D distribution_;
    double luminance_integral_ = 0;
};

}  // namespace glint
