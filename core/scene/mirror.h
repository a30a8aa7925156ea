// The mirror: smallpt's perfect reflector of `albedo`, and with roughness a GGX conductor with no
// Fresnel term, albedo·D·G / (4 |cos θo| |cos θi|): Cycles' Glossy BSDF (GGX) of the same Color
// and Roughness.
#pragma once

#include "base/rng.h"
#include "scene/bsdf_flags.h"
#include "scene/material.h"

namespace glint {

BsdfFlags mirror_flags(const Material& m);
// n: the unit geometric normal (either side); wo: toward where the path came from.
// A rough mirror's direction takes two numbers (direction_numbers); a smooth one none.
BsdfSample sample_mirror(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng, const double* given);
BsdfValue evaluate_mirror(const Material& m, const Vec3& n, const Vec3& wo, const Vec3& wi);

}  // namespace glint
