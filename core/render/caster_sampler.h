// Mirror and glass spheres as the lights they are to a diffuse point that sees them: the light
// they reflect or refract onto it (a caustic) arrives from within the cone each one subtends.
// Light tracing reaches these paths from the light when the camera sees the diffuse point
// directly; when it sees it only in a mirror or through glass, the path tracer must find them,
// and a cosine-sampled bounce enters a small ball by chance: smallpt's fireflies on the walls
// seen in its balls. Sampling a direction in a ball's cone finds them as often as the ball is
// big in the point's view; the path tracer combines that with its bounce by MIS.
#pragma once

#include <vector>

#include "scene/scene.h"

namespace glint {

class CasterSampler {
public:
    CasterSampler() = default;
    // The scene's mirror and glass spheres.
    explicit CasterSampler(const Scene& scene);

    bool empty() const { return casters_.empty(); }
    // A direction from p into the cone of one of the casters p is outside of, chosen uniformly;
    // false if there is none. `pdf` is the density of wi over all the choices (see pdf()).
    bool sample(const Vec3& p, double u_pick, double u1, double u2, Vec3& wi, double& pdf) const;
    // The solid-angle density with which sample() picks wi at p.
    double pdf(const Vec3& p, const Vec3& wi) const;

private:
    struct Caster {
        Vec3 centre;
        double radius;
        bool outside(const Vec3& p) const;
        bool holds(const Vec3& p, const Vec3& wi) const;  // whether the ray from p along wi meets it
    };
    int count_outside(const Vec3& p) const;
    // pdf(), counting `chosen`'s cone as holding wi without testing it (rounding could say no).
    double density(const Vec3& p, const Vec3& wi, const Caster* chosen) const;

    std::vector<Caster> casters_;
};

}  // namespace glint
