// A material's BSDF at a shading point: what the integrator and its strategies ask instead of
// which material they hit (the flags say which strategies apply; sample, evaluate and pdf do the
// rest). Directions are world-space unit vectors; wo points back along the path, wi onward.
// Each material's lobes live in the file named after it; this dispatches to them.
#pragma once

#include "scene/glass.h"
#include "scene/lambertian.h"
#include "scene/metallic_roughness.h"
#include "scene/mirror.h"
#include "scene/shading_normal.h"
#include "shapes/interaction.h"

namespace glint {

class Bsdf {
public:
    // n: the unit geometric normal at the point (outward for spheres, by winding for triangles).
    Bsdf(const Material& m, const Vec3& n) : m_(m), n_(n), ng_(n) {}
    Bsdf(Material&&, const Vec3&) = delete;  // it keeps a reference: no temporaries
    // At si, seen from wo: where si has a shading normal, the lobes are about it, bent for wo and
    // held to the geometric surface's sides (shading_normal.h).
    Bsdf(const Material& m, const SurfaceInteraction& si, const Vec3& wo)
        : m_(m), n_(si.shaded ? shading_normal(si.n, si.ns, wo) : si.n), ng_(si.n), shaded_(si.shaded) {}
    Bsdf(Material&&, const SurfaceInteraction&, const Vec3&) = delete;

    // The flags of m's BSDF anywhere on its surface.
    static BsdfFlags flags(const Material& m) {
        switch (m.type) {
            case MaterialType::diffuse: return kLambertianFlags;
            case MaterialType::mirror: return mirror_flags(m);
            case MaterialType::glass: return glass_flags(m);
            case MaterialType::metal:
            case MaterialType::plastic: return metallic_roughness_flags(m);
        }
        return {};
    }
    BsdfFlags flags() const { return flags(m_); }

    // A continuation from wo, with numbers from rng; `given`, if not null, is the pair a
    // non-specular direction takes instead of rng's (a stratified pair). What each material
    // draws, and in which order, is in its file; a weight of 0 is a failed sample.
    BsdfSample sample(const Vec3& wo, Rng& rng, const double* given = nullptr) const {
        if (shaded_) return sample_shaded(wo, rng, given);
        return sample_lobes(wo, rng, given);
    }

    // f(wo, wi)·|cos θi| over the non-specular lobes, and the pdf with which sample() picks wi.
    BsdfValue evaluate(const Vec3& wo, const Vec3& wi) const {
        if (shaded_) return evaluate_shaded(wo, wi);
        return evaluate_lobes(wo, wi);
    }
    Rgb eval(const Vec3& wo, const Vec3& wi) const { return evaluate(wo, wi).f_cos; }
    double pdf(const Vec3& wo, const Vec3& wi) const { return evaluate(wo, wi).pdf; }

    // A specular BSDF with both a reflection and a transmission (smooth glass) as two
    // continuations, each weighted by its share, instead of one picked at random; false where
    // there are not two.
    bool split(const Vec3& wo, BsdfSample& reflected, BsdfSample& transmitted) const {
        if (m_.type != MaterialType::glass || !split_glass(m_, n_, wo, reflected, transmitted)) return false;
        if (shaded_ && !sides_agree(ng_, n_, wo, reflected.wi)) reflected.weight = Rgb{0};
        if (shaded_ && !sides_agree(ng_, n_, wo, transmitted.wi)) transmitted.weight = Rgb{0};
        return true;
    }

    // The reflectance a denoiser's albedo feature and a diffuse light vertex take: the material's
    // albedo (for a Lambertian BSDF, f·π).
    const Rgb& albedo() const { return m_.albedo; }

private:
    // Under a shading normal: the lobes' answer where the geometric normal agrees (shading_normal.h).
    [[gnu::noinline]] BsdfSample sample_shaded(const Vec3& wo, Rng& rng, const double* given) const {
        BsdfSample bs = sample_lobes(wo, rng, given);
        if (!sides_agree(ng_, n_, wo, bs.wi)) bs.weight = Rgb{0};
        return bs;
    }
    [[gnu::noinline]] BsdfValue evaluate_shaded(const Vec3& wo, const Vec3& wi) const {
        return sides_agree(ng_, n_, wo, wi) ? evaluate_lobes(wo, wi) : BsdfValue{};
    }
    BsdfValue evaluate_lobes(const Vec3& wo, const Vec3& wi) const {
        switch (m_.type) {
            case MaterialType::diffuse: return evaluate_lambertian(m_, n_, wo, wi);
            case MaterialType::mirror: return evaluate_mirror(m_, n_, wo, wi);
            case MaterialType::glass: return evaluate_glass(m_, n_, wo, wi);
            case MaterialType::metal:
            case MaterialType::plastic: return evaluate_metallic_roughness(m_, n_, wo, wi);
        }
        return {};
    }
    BsdfSample sample_lobes(const Vec3& wo, Rng& rng, const double* given) const {
        switch (m_.type) {
            case MaterialType::diffuse: {
                double u1, u2;
                direction_numbers(rng, given, u1, u2);
                return sample_lambertian(m_, n_, wo, u1, u2);
            }
            case MaterialType::mirror: return sample_mirror(m_, n_, wo, rng, given);
            case MaterialType::glass: return sample_glass(m_, n_, wo, rng, given);
            case MaterialType::metal:
            case MaterialType::plastic: return sample_metallic_roughness(m_, n_, wo, rng, given);
        }
        return {};
    }

    const Material& m_;
    Vec3 n_;   // the lobes' normal: the geometric one, or the shading normal bent for wo
    Vec3 ng_;  // the geometric normal
    bool shaded_ = false;
};

}  // namespace glint
