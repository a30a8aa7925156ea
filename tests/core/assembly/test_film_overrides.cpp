// The film overrides and the one check of a film's settings, which the scene loader, `glint
// render` and the HTTP request parser share: the bounds follow the limits, and each fault names
// its field.
#include <gtest/gtest.h>

#include <cmath>

#include "assembly/film_overrides.h"

namespace glint {
namespace {

// The error that overrides set by `set` give on the default settings and limits.
template <typename Set>
std::string error_of(Set set) {
    FilmOverrides overrides;
    set(overrides);
    RenderSettings settings;
    try {
        apply_film_overrides(overrides, settings, SceneLimits{});
    } catch (const SceneError& e) {
        return e.what();
    }
    return "no error";
}

TEST(FilmOverrides, RangesFollowTheLimits) {
    SceneLimits limits;
    limits.max_dimension = 640;
    limits.max_spp = 256;
    EXPECT_EQ(film_range(FilmInteger::width, limits).text(), "[1, 640]");
    EXPECT_EQ(film_range(FilmInteger::height, limits).text(), "[1, 640]");
    EXPECT_EQ(film_range(FilmInteger::spp, limits).text(), "[1, 256]");
    EXPECT_EQ(film_range(FilmInteger::seed, limits).text(), "[0, 9223372036854775807]");
    EXPECT_STREQ(film_key(FilmInteger::spp), "spp");
    EXPECT_TRUE(film_range(FilmInteger::spp, limits).contains(256));
    EXPECT_FALSE(film_range(FilmInteger::spp, limits).contains(257));
}

TEST(FilmOverrides, SetFieldsReplaceTheScenesAndUnsetOnesKeepThem) {
    RenderSettings settings;
    FilmOverrides overrides;
    overrides.spp = 8;
    overrides.encoding = encoding_named("srgb");
    apply_film_overrides(overrides, settings, {});
    EXPECT_EQ(settings.spp, 8u);
    EXPECT_EQ(settings.encoding, Encoding::srgb);
    EXPECT_EQ(settings.width, RenderSettings{}.width);
    EXPECT_EQ(encoding_named("gamma2.2"), Encoding::gamma22);
}

TEST(FilmOverrides, EachFaultNamesItsField) {
    EXPECT_EQ(error_of([](FilmOverrides& o) { o.width = 0; }), "film.width: must be in [1, 16384]");
    EXPECT_EQ(error_of([](FilmOverrides& o) { o.spp = 0; }), "film.spp: must be in [1, 1048576]");
    EXPECT_EQ(error_of([](FilmOverrides& o) { o.width = o.height = 5000; }),
              "film: image of 25000000 pixels exceeds the limit of 16777216");
    EXPECT_EQ(error_of([](FilmOverrides& o) { o.first_sample = 2; }),
              "--samples: must start at a multiple of 4 (the tent filter renders whole rounds of 4 "
              "subpixels)");
    EXPECT_EQ(error_of([](FilmOverrides& o) { o.time_limit = -1; }), "film.time_limit: must be a finite number >= 0 (0: off)");
    EXPECT_EQ(error_of([](FilmOverrides& o) { o.seed = UINT64_MAX; }), "no error");
    EXPECT_EQ(error_of([](FilmOverrides& o) { o.adaptive_threshold = -0.1; }),
              "film.adaptive.threshold: must be a number in [0, 1] (0: off)");
    EXPECT_EQ(error_of([](FilmOverrides& o) { o.adaptive_threshold = std::nan(""); }),
              "film.adaptive.threshold: must be a number in [0, 1] (0: off)");
    EXPECT_EQ(error_of([](FilmOverrides& o) { o.adaptive_min_spp = 2000000; }),
              "film.adaptive.min_spp: must be an integer in [0, 1048576] (0: automatic)");
}

// `--samples A:B` keeps the whole job's spp, which the part's threshold is scaled by.
TEST(FilmOverrides, APartKnowsItsWholeJobsSamples) {
    RenderSettings settings;
    settings.spp = 256;
    FilmOverrides part;
    part.first_sample = 64;
    part.spp = 64;
    part.adaptive_threshold = 0.01;
    apply_film_overrides(part, settings, {});
    EXPECT_EQ(settings.adaptive.job_spp, 256u);
    EXPECT_EQ(settings.adaptive.threshold, 0.01);
    RenderSettings given;
    part.job_spp = 128;  // --spp 128 --samples 64:128
    apply_film_overrides(part, given, {});
    EXPECT_EQ(given.adaptive.job_spp, 128u);
}

}  // namespace
}  // namespace glint
