#include "scene/camera.h"

#include "base/sampling.h"

namespace glint {

Camera::Camera(const CameraSettings& settings, int width, int height)
    : settings_(settings), width_(width), height_(height) {
    const double film_height = 2 * std::tan(settings.fov_degrees * kPi / 360);
    const Vec3 right = normalize(cross(settings.direction, settings.up));
    right_ = right * (film_height * width / height);
    up_ = normalize(cross(right, settings.direction)) * film_height;
}

bool Camera::may_see(const Bounds3& box, double margin) const {
    if (!is_pinhole()) return true;
    // A point eye + a·right + b·up + c·direction is in the pyramid when |a| <= kx·c and
    // |b| <= ky·c: four half-spaces through the eye, which together exclude everything behind it.
    const double kx = 0.5 + margin / width_, ky = 0.5 + margin / height_;
    const double right2 = dot(right_, right_), up2 = dot(up_, up_);
    unsigned outside_all = 0xF;  // sides every corner so far is beyond
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p{corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y, corner & 4 ? box.hi.z : box.lo.z};
        const Vec3 v = p - settings_.position;
        const double a = dot(v, right_) / right2, b = dot(v, up_) / up2, c = dot(v, settings_.direction);
        const unsigned outside = unsigned(a > kx * c) | unsigned(a < -kx * c) << 1 | unsigned(b > ky * c) << 2 |
                                 unsigned(b < -ky * c) << 3;
        outside_all &= outside;
    }
    return outside_all == 0;
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
