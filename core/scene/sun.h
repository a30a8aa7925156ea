// The sun: light from one direction far away, as Blender's Sun lamp. `irradiance` is what a
// surface facing it receives (W/m², Blender's Strength); `angle` its angular diameter. A disc
// of angular radius α = angle/2 and uniform radiance L gives a facing surface L·π·sin²α, so
// L = irradiance / (π sin²α). At angle 0 it is a delta light, reached by light sampling only.
#pragma once

#include <cmath>

#include "base/math.h"
#include "base/sampling.h"

namespace glint {

struct SunSettings {
    Vec3 direction{0, 1, 0};  // toward the sun; unit
    Rgb irradiance{1};      // W/m², Blender's default Strength
    double angle = 0.526;  // degrees, in [0, 180): the Earth's sun as Blender's default
};

class Sun {
public:
    explicit Sun(const SunSettings& s)
        : settings_(s), cone_(Cone::subtended(std::sin(s.angle * kPi / 360), 1)),
          radiance_(is_delta() ? s.irradiance : s.irradiance / (kPi * cone_.sin2_max)),
          frame_(Frame::around(s.direction)) {}

    const SunSettings& settings() const { return settings_; }
    bool is_delta() const { return !(settings_.angle > 0); }
    // What arrives from direction d (unit): L inside the disc, else nothing (always nothing
    // for a delta sun, which no direction found by chance reaches).
    Rgb radiance(const Vec3& d) const { return pdf(d) > 0 ? radiance_ : Rgb{0}; }
    // A direction toward the sun with the radiance it brings and its solid-angle density;
    // for a delta sun the direction itself, the irradiance, and density 1 (`delta` set).
    void sample(double u1, double u2, Vec3& d, Rgb& value, double& pdf) const {
        value = radiance_;
        if (is_delta()) {
            d = settings_.direction;
            pdf = 1;
            return;
        }
        double sin2_theta;
        d = normalize(frame_.to_world(cone_.sample(u1, u2, sin2_theta)));
        pdf = cone_.pdf();
    }
    double pdf(const Vec3& d) const {
        if (is_delta()) return 0;
        return 1 - dot(d, settings_.direction) <= cone_.one_minus_cos_max ? cone_.pdf() : 0;
    }
    // The power that light selection weighs: irradiance through the scene's bounding disc of
    // radius r, over 2π as the emitters' (area × radiance) weights are.
    double selection_weight(double r) const { return 0.5 * r * r * luminance(settings_.irradiance); }

private:
    SunSettings settings_;
    Cone cone_;
    Rgb radiance_;
    Frame frame_;
};

}  // namespace glint
