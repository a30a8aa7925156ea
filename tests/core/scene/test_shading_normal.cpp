// Shading normals (scene/shading_normal.h): light never arrives from below the geometric
// surface, and a coarse mesh with vertex normals goes black nowhere its geometry is lit and the
// sphere it approximates is lit.
#include <gtest/gtest.h>

#include <cmath>

#include "base/rng.h"
#include "scene/bsdf.h"
#include "scene/geometry.h"

namespace glint {
namespace {

SurfaceInteraction flat_point_with_normal(const Vec3& ns) {
    SurfaceInteraction si;
    si.n = {0, 0, 1};
    si.ns = normalize(ns);
    si.shaded = !(si.ns == si.n);
    return si;
}

const Material kDiffuse = default_material(MaterialType::diffuse);

Material rough_plastic() {
    Material m = default_material(MaterialType::plastic);
    m.roughness = 0.5;
    return m;
}

TEST(ShadingNormal, NoLightArrivesFromBelowTheGeometricSurface) {
    // The shading normal leans 60° toward +x: directions just below the surface on that side are
    // above the shading normal's horizon.
    const SurfaceInteraction si = flat_point_with_normal({std::sin(1.047), 0, std::cos(1.047)});
    const Vec3 wo = normalize(Vec3{-0.3, 0.2, 1});
    const Vec3 below = normalize(Vec3{1, 0.1, -0.3});
    ASSERT_GT(dot(below, si.ns), 0);
    for (const Material& m : {kDiffuse, rough_plastic()}) {
        const Bsdf bsdf(m, si, wo);
        EXPECT_TRUE(is_black(bsdf.eval(wo, below)));
        Rng rng(7, 0, 0);
        for (int i = 0; i < 20000; ++i) {
            const BsdfSample bs = bsdf.sample(wo, rng);
            if (dot(bs.wi, si.n) < 0) {
                EXPECT_TRUE(is_black(bs.weight)) << i;
            }
        }
    }
}

TEST(ShadingNormal, AViewBelowTheShadingNormalButAboveTheFacetIsNotBlack) {
    // A coarse silhouette: the facet faces the eye, the interpolated normal faces away from it.
    const SurfaceInteraction si = flat_point_with_normal({0.8, 0, 0.6});
    const Vec3 wo = normalize(Vec3{-0.9, 0, 0.2});
    ASSERT_LT(dot(wo, si.ns), 0);
    ASSERT_GT(dot(wo, si.n), 0);
    const Bsdf bsdf(kDiffuse, si, wo);
    EXPECT_GT(max_component(bsdf.eval(wo, Vec3{0, 0, 1})), 0);
    Rng rng(3, 0, 0);
    int kept = 0;
    for (int i = 0; i < 1000; ++i) kept += !is_black(bsdf.sample(wo, rng).weight);
    EXPECT_GT(kept, 400);  // the rest go below the facet: lost, not leaked
}

TEST(ShadingNormal, WithoutAShadingNormalTheBsdfIsTheGeometricOne) {
    SurfaceInteraction si = flat_point_with_normal({0, 0, 1});
    const Vec3 wo = normalize(Vec3{0.3, 0.1, 1}), wi = normalize(Vec3{-0.5, 0.2, 0.7});
    const Material m = rough_plastic();
    const BsdfValue shaded = Bsdf(m, si, wo).evaluate(wo, wi), plain = Bsdf(m, si.n).evaluate(wo, wi);
    EXPECT_EQ(shaded.f_cos, plain.f_cos);
    EXPECT_EQ(shaded.pdf, plain.pdf);
}

// A UV sphere of `segments` × `rings` quads, each vertex's normal the sphere's there.
struct LowPolySphere {
    std::vector<Triangle> triangles;
    TriangleAttributes attributes;
};

LowPolySphere low_poly_sphere(int segments, int rings) {
    auto at = [&](int i, int j) {
        const double theta = kPi * j / rings, phi = 2 * kPi * i / segments;
        return Vec3{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
    };
    LowPolySphere s;
    auto add = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        if (length(cross(b - a, c - a)) == 0) return;
        s.triangles.push_back({a, b, c});
        TriangleNormals n;
        const Vec3* corners[3] = {&a, &b, &c};
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d) n.n[k][d] = float((*corners[k])[d]);
        s.attributes.normals.push_back(n);
    };
    for (int j = 0; j < rings; ++j)
        for (int i = 0; i < segments; ++i) {
            // Wound so that the geometric normals point outward.
            add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    return s;
}

TEST(ShadingNormal, ALowPolySphereLitFromTheSideLeaksNothingAndBlackensNothingItsGeometryLights) {
    LowPolySphere mesh = low_poly_sphere(8, 6);
    Geometry geometry({}, mesh.triangles);
    geometry.attach(std::move(mesh.attributes));
    const Vec3 light = {1, 0, 0};  // a distant light on the eye's right
    int lit = 0, checked = 0;
    for (int y = -40; y <= 40; ++y)
        for (int x = -40; x <= 40; ++x) {
            const Ray ray{{x / 40.0, y / 40.0, 5}, {0, 0, -1}};
            Hit hit;
            if (!geometry.intersect(ray, kNoPrimitive, hit)) continue;
            const SurfaceInteraction si = geometry.interaction(ray, hit);
            ASSERT_TRUE(geometry.smooth(si.prim));
            const Vec3 wo = -ray.d, sphere_normal = normalize(si.p);
            const Rgb f = Bsdf(kDiffuse, si, wo).eval(wo, light);
            ++checked;
            if (dot(si.n, light) <= 0) {
                EXPECT_TRUE(is_black(f)) << "light leaks through the facet at " << x << ", " << y;
            } else if (dot(sphere_normal, light) > 0.01) {
                EXPECT_GT(max_component(f), 0) << "black where the sphere is lit, at " << x << ", " << y;
                ++lit;
            }
        }
    EXPECT_GT(checked, 3000);
    EXPECT_GT(lit, 1000);
}

}  // namespace
}  // namespace glint
