#include "camera.h"

#include "sampling.h"

namespace glint {

Camera::Camera(const CameraSettings& settings, int width, int height)
    : settings_(settings), width_(width), height_(height) {
    const double film_height = 2 * std::tan(settings.fov_degrees * kPi / 360);
    const Vec3 right = normalize(cross(settings.direction, settings.up));
    right_ = right * (film_height * width / height);
    up_ = normalize(cross(right, settings.direction)) * film_height;
}

Ray Camera::generate(double fx, double fy, double u1, double u2) const {
    const Vec3 d = normalize(right_ * (fx / width_ - 0.5) + up_ * (fy / height_ - 0.5) + settings_.direction);
    Vec3 eye = settings_.position;
    Vec3 dir = d;
    if (settings_.aperture > 0) {
        // Every ray through this film point meets at the focus plane, distance focus_distance
        // along the view direction.
        const Vec3 focus = eye + d * (settings_.focus_distance / dot(d, settings_.direction));
        double lx, ly;
        sample_disk(u1, u2, lx, ly);
        eye = eye + (normalize(right_) * lx + normalize(up_) * ly) * settings_.aperture;
        dir = normalize(focus - eye);
    }
    return Ray{eye + dir * settings_.near, dir};
}

}  // namespace glint
