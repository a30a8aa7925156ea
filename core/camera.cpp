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

bool Camera::project(const Vec3& p, Projection& out) const {
    const Vec3 v = p - settings_.position;
    out.distance = length(v);
    if (!(out.distance > settings_.near)) return false;
    const Vec3 d = v / out.distance;
    const double cos_theta = dot(d, settings_.direction);
    if (!(cos_theta > 0)) return false;
    // On the plane at unit distance along the view direction, d/cos θ = direction + film offset.
    const Vec3 film = d / cos_theta - settings_.direction;
    const double right2 = dot(right_, right_), up2 = dot(up_, up_);
    out.fx = (dot(film, right_) / right2 + 0.5) * width_;
    out.fy = (dot(film, up_) / up2 + 0.5) * height_;
    out.to_eye = -d;
    const double pixel_area = std::sqrt(right2 * up2) / (double(width_) * height_);
    out.importance = 1 / (pixel_area * cos_theta * cos_theta * cos_theta);
    return true;
}

double Camera::area_density(const Vec3& p, const Vec3& n) const {
    Projection proj;
    if (!project(p, proj)) return 0;
    return proj.importance / (double(width_) * height_) * std::fabs(dot(n, proj.to_eye)) / (proj.distance * proj.distance);
}

}  // namespace glint
