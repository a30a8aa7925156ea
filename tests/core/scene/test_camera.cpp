// The camera reproduces smallpt's rays, and a thin lens focuses where it says.
#include <gtest/gtest.h>

#include "scene/camera.h"
#include "base/rng.h"

namespace glint {
namespace {

TEST(Camera, ReproducesSmallptsRays) {
    const int w = 1024, h = 768;
    CameraSettings s;
    s.position = {50, 52, 295.6};
    s.direction = normalize(Vec3{0, -0.042612, -1});
    s.fov_degrees = 2 * std::atan(0.5135 / 2) * 180 / kPi;
    s.near = 140;
    const Camera camera(s, w, h);
    // smallpt: cx = (w·.5135/h, 0, 0), cy = normalize(cx × D)·.5135.
    const Vec3 cx{w * 0.5135 / h, 0, 0}, cy = normalize(cross(cx, s.direction)) * 0.5135;
    Rng rng(41, 0, 0);
    for (int i = 0; i < 1000; ++i) {
        const int x = int(rng.uniform() * w), y = int(rng.uniform() * h), sx = i & 1, sy = (i >> 1) & 1;
        const double dx = 2 * rng.uniform() - 1, dy = 2 * rng.uniform() - 1;
        const Vec3 d = normalize(cx * (((sx + 0.5 + dx) / 2 + x) / w - 0.5) + cy * (((sy + 0.5 + dy) / 2 + y) / h - 0.5) +
                                 s.direction);
        const Ray ray = camera.generate(x + (sx + 0.5 + dx) / 2, y + (sy + 0.5 + dy) / 2, 0.5, 0.5);
        EXPECT_NEAR(length(ray.d - d), 0, 1e-12);
        // The origin is 140 units along the unit direction (smallpt under g++).
        EXPECT_NEAR(length(ray.o - (s.position + d * 140)), 0, 1e-9);
    }
}

TEST(Camera, ThinLensRaysMeetOnTheFocusPlane) {
    CameraSettings s;
    s.aperture = 0.5;
    s.focus_distance = 7;
    const Camera camera(s, 64, 48);
    Rng rng(42, 0, 0);
    for (int i = 0; i < 200; ++i) {
        const double fx = 64 * rng.uniform(), fy = 48 * rng.uniform();
        const Ray a = camera.generate(fx, fy, rng.uniform(), rng.uniform());
        const Ray b = camera.generate(fx, fy, rng.uniform(), rng.uniform());
        // Both rays reach the plane z = -7 at the same point.
        const Vec3 pa = a.o + a.d * ((-7 - a.o.z) / a.d.z), pb = b.o + b.d * ((-7 - b.o.z) / b.d.z);
        EXPECT_NEAR(length(pa - pb), 0, 1e-12);
    }
}

}  // namespace
}  // namespace glint
