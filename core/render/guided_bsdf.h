// A vertex's bounce under path guiding: a one-sample mixture that draws the direction from the
// guide's learned distribution (path_guide.h) with probability `mixture` and from the BSDF
// otherwise. The density of a direction is the mixture's, α·p_guide + (1 - α)·p_bsdf, and that
// is the density every MIS weight that weighs this bounce takes: evaluate() returns it. Without
// a guide (nothing learned around the vertex, guiding off, a specular vertex) it is the BSDF.
#pragma once

#include "render/guide_quadtree.h"
#include "scene/bsdf.h"

namespace glint {

class GuidedBsdf {
public:
    GuidedBsdf(const Bsdf& bsdf, const GuideQuadtree* guide, double mixture)
        : bsdf_(bsdf), guide_(guide), mixture_(mixture) {}

    bool guided() const { return guide_ != nullptr; }

    // f·|cos θi| and the density with which sample() picks wi.
    BsdfValue evaluate(const Vec3& wo, const Vec3& wi) const {
        BsdfValue v = bsdf_.evaluate(wo, wi);
        if (guide_) v.pdf = mix(guide_pdf(wi), v.pdf);
        return v;
    }

    // As Bsdf::sample; with a stratified pair `given`, its first number also picks the component.
    BsdfSample sample(const Vec3& wo, Rng& rng, const double* given = nullptr) const {
        if (!guide_) return bsdf_.sample(wo, rng, given);
        double u = given ? given[0] : rng.uniform();
        if (u < mixture_) {
            double u1, u2;
            if (given) {
                u1 = u / mixture_;
                u2 = given[1];
            } else {
                direction_numbers(rng, nullptr, u1, u2);
            }
            return from_guide(wo, u1, u2);
        }
        const double rest[2] = {(u - mixture_) / (1 - mixture_), given ? given[1] : 0};
        return from_bsdf(wo, rng, given ? rest : nullptr);
    }

    const Rgb& albedo() const { return bsdf_.albedo(); }

private:
    double guide_pdf(const Vec3& wi) const { return guide_->pdf(direction_to_square(wi)) / (4 * kPi); }
    double mix(double guide_pdf, double bsdf_pdf) const { return mixture_ * guide_pdf + (1 - mixture_) * bsdf_pdf; }

    BsdfSample from_guide(const Vec3& wo, double u1, double u2) const {
        double square_pdf;
        const Vec3 wi = square_to_direction(guide_->sample(u1, u2, square_pdf));
        const BsdfValue f = bsdf_.evaluate(wo, wi);
        const double pdf = mix(square_pdf / (4 * kPi), f.pdf);
        BsdfFlags flags = bsdf_.flags();
        flags.bits &= uint8_t(~BsdfFlags::specular);
        return {wi, pdf > 0 ? f.f_cos / pdf : Rgb{0}, pdf, flags};
    }

    BsdfSample from_bsdf(const Vec3& wo, Rng& rng, const double* given) const {
        BsdfSample bs = bsdf_.sample(wo, rng, given);
        if (bs.is_specular()) {  // a delta lobe: the guide never draws it
            bs.weight *= 1 / (1 - mixture_);
            return bs;
        }
        const BsdfValue f = bsdf_.evaluate(wo, bs.wi);
        bs.pdf = mix(guide_pdf(bs.wi), f.pdf);
        bs.weight = bs.pdf > 0 && !is_black(bs.weight) ? f.f_cos / bs.pdf : Rgb{0};
        return bs;
    }

    const Bsdf& bsdf_;
    const GuideQuadtree* guide_;
    double mixture_;
};

}  // namespace glint
