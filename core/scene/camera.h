// A perspective camera with smallpt's conventions: rays start `near` units from the eye along
// their own direction (smallpt's camera stands behind its front wall and starts rays 140 units
// out), and an optional thin lens for depth of field.
#pragma once

#include "base/bounds.h"
#include "base/ray.h"

namespace glint {

struct CameraSettings {
    Vec3 position{0, 0, 0};
    Vec3 direction{0, 0, -1};  // unit; a look-at point is turned into this by the scene loader
    Vec3 up{0, 1, 0};
    double fov_degrees = 40;    // vertical
    double near = 0;
    double aperture = 0;        // lens radius; 0 is a pinhole
    double focus_distance = 1;  // along the view direction
};

class Camera {
public:
    Camera() = default;
    Camera(const CameraSettings& settings, int width, int height);

    // A ray through film position (fx, fy) in pixels, fx from the left edge, fy from the
    // bottom edge (smallpt's orientation); (u1, u2) pick the point on the lens.
    Ray generate(double fx, double fy, double u1, double u2) const;

    // The inverse, for light tracing with a pinhole: where on the film (pixels, as generate's
    // fx, fy) the eye sees point p, the unit direction from p to the eye and the distance, and
    // the importance per unit film area: the solid angle at the eye per pixel² is
    // pixel_area·cos³θ, so a pixel's measurement ∫ filter·L dω/(pixel_area·cos³θ) weighs
    // radiance by 1/(pixel_area·cos³θ). False if p is behind the eye or nearer than `near`
    // (camera rays start there).
    struct Projection {
        double fx, fy;
        Vec3 to_eye;
        double distance;
        double importance;
    };
    bool project(const Vec3& p, Projection& out) const;
    // The density, per unit area of a surface through p with unit normal n, with which a
    // camera ray through a uniformly random point of the film meets p (pinhole): the importance
    // shared by all the pixels times |cos|/distance². 0 where the camera cannot see p.
    double area_density(const Vec3& p, const Vec3& n) const;
    bool is_pinhole() const { return !(settings_.aperture > 0); }
    // False only if no camera ray through the film, widened by `margin` pixels on every side,
    // can meet the box: all its corners outside one side of the view pyramid. True with a lens.
    bool may_see(const Bounds3& box, double margin) const;
    double near() const { return settings_.near; }

private:
    CameraSettings settings_;
    Vec3 right_, up_;  // scaled so the film spans [-0.5, 0.5] of each at unit distance
    int width_ = 1, height_ = 1;
};

}  // namespace glint
