// Light from every direction far away: an equirectangular image (latitude-longitude) around the
// scene. At rotation 0 the texel at (u, v), u from the image's left edge, v from its top row, is
// seen in the direction (cos θ cos φ, sin θ, cos θ sin φ) with φ = 2π(u − 1/2), θ = π(1/2 − v):
// +y up, the image's centre along +x, its three-quarter column along +z. A rotation ρ turns
// that about +y (+x toward −z). This is Blender's Environment Texture once Blender's +z-up is
// made +y-up as its glTF importer does.
//
// Lookups are bilinear between texel centres, wrapping around in u and held at the poles in v.
// Directions are sampled in proportion to the radiance's luminance over each texel's cell,
// weighted by the cell's solid angle.
#pragma once

#include <span>
#include <vector>

#include "base/distribution.h"
#include "base/math.h"
#include "scene/texture.h"

namespace glint {

struct EnvironmentSettings {
    double strength = 1;  // multiplies every texel
    double rotation = 0;  // degrees about +y
    // Whether camera rays, and mirror or glass paths straight from the camera, see it; else
    // they see the film's background (light from it still reaches every surface).
    bool visible = true;
};

class Environment {
public:
    // width·height linear RGB texels, rows top first; none negative or non-finite (the loader
    // makes sure). Throws std::invalid_argument for a size below 1 or a vector of another size.
    Environment(int width, int height, std::vector<float> rgb, EnvironmentSettings settings);
    // From a decoded image: float texels as they are, 8-bit ones decoded from sRGB; one or two
    // channels are grey, a fourth (alpha) is left out.
    static Environment from_texture(const Texture& image, EnvironmentSettings settings);

    const EnvironmentSettings& settings() const { return settings_; }
    int width() const { return width_; }
    int height() const { return height_; }
    std::span<const float> texels() const { return rgb_; }  // linear RGB, rows top first
    // The radiance arriving from direction d (unit), travelling along −d.
    Rgb radiance(const Vec3& d) const;
    // A unit direction toward the environment, and its solid-angle density; false where the
    // environment is black.
    bool sample(double u1, double u2, Vec3& d, double& pdf) const;
    double pdf(const Vec3& d) const;
    // ∫ luminance(L) dω over the sphere: with the scene's bounding sphere it gives the power
    // that light selection weighs against the scene's emitters.
    double luminance_integral() const { return luminance_integral_; }

private:
    // The image coordinates (u, v in [0, 1), v from the top) of direction d, and back.
    void to_image(const Vec3& d, double& u, double& v) const;
    Vec3 from_image(double u, double v) const;
    Rgb texel(int i, int j) const;  // i wrapped, j held to the image
    double cell_weight(int i, int j) const;
    double cell_solid_angle(int row) const;
    double cell_pdf(size_t column, size_t row) const;  // solid-angle density of sampling in that cell

    int width_, height_;
    std::vector<float> rgb_;
    EnvironmentSettings settings_;
    double rotation_radians_;
    Distribution2D distribution_;
    double luminance_integral_ = 0;
};

}  // namespace glint
