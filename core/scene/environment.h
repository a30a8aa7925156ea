// Light from every direction far away: an equirectangular image (scene/environment_map.h) around
// the scene, scaled by a strength and turned about +y. At rotation 0 the texel at (u, v), u
// from the image's left edge, v from its top row, is seen in the direction
// (cos θ cos φ, sin θ, cos θ sin φ) with φ = 2π(u − 1/2), θ = π(1/2 − v): +y up, the image's
// centre along +x, its three-quarter column along +z. A rotation ρ turns that about +y (+x
// toward −z). This is Blender's Environment Texture once Blender's +z-up is made +y-up as its
// glTF importer does.
#pragma once

#include <memory>

#include "scene/environment_map.h"

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
    // Throws std::invalid_argument for a null map.
    Environment(std::shared_ptr<const EnvironmentMap> map, EnvironmentSettings settings);

    const EnvironmentSettings& settings() const { return settings_; }
    const EnvironmentMap& map() const { return *map_; }
    // The radiance arriving from direction d (unit), travelling along −d.
    Rgb radiance(const Vec3& d) const;
    // A unit direction toward the environment, and its solid-angle density; false where the
    // environment is black.
    bool sample(double u1, double u2, Vec3& d, double& pdf) const;
    double pdf(const Vec3& d) const;
    // ∫ luminance(L) dω over the sphere: with the scene's bounding sphere it gives the power
    // that light selection weighs against the scene's emitters.
    double luminance_integral() const { return map_->luminance_integral() * settings_.strength; }

private:
    // The image coordinates (u, v in [0, 1), v from the top) of direction d.
    void to_image(const Vec3& d, double& u, double& v) const;

    std::shared_ptr<const EnvironmentMap> map_;
    EnvironmentSettings settings_;
    double rotation_radians_;
};

}  // namespace glint
