// Split jobs: parts of a render merge into the image of the whole, and the partial format
// refuses what it must.
#include <gtest/gtest.h>

#include <cstring>

#include "assembly/fingerprint.h"
#include "assembly/partial_file.h"
#include "support/test_support.h"

namespace glint {
namespace {

// Renders samples [first, end) and returns them as a partial file's bytes.
std::vector<uint8_t> render_part(LoadedScene s, uint32_t first, uint32_t end) {
    s.settings.adaptive.job_spp = s.settings.spp;  // as `glint render --samples` sets it
    s.settings.first_sample = first;
    s.settings.spp = end - first;
    const auto job = testing::render(s);
    return encode_partial(partial_of(*job, fingerprint(*s.scene, s.settings), end - first));
}

TEST(Partial, ThreePartsMergeIntoTheWholeRender) {
    LoadedScene s = testing::small_cornell();
    s.settings.spp = 48;
    const auto whole = testing::render(s);
    const Partial merged = merge_partials({decode_partial(render_part(s, 32, 48)), decode_partial(render_part(s, 0, 12)),
                                           decode_partial(render_part(s, 12, 32))});
    EXPECT_EQ(merged.first_sample, 0u);
    EXPECT_EQ(merged.end_sample, 48u);
    // Every sample is the same (streams keyed by sample index); only the order of the additions
    // differs (samples one by one, against three partial sums), so the sums agree to rounding.
    double worst = 0;
    for (size_t i = 0; i < merged.film.pixels().size(); ++i) {
        const PixelSums &a = whole->film().pixels()[i], &b = merged.film.pixels()[i];
        ASSERT_EQ(a.count, b.count);
        ASSERT_EQ(a.half_count, b.half_count);
        for (int c = 0; c < 3; ++c) {
            if (a.sum[c] != 0) worst = std::max(worst, std::fabs(a.sum[c] - b.sum[c]) / std::fabs(a.sum[c]));
            if (a.half_sum[c] != 0)
                worst = std::max(worst, std::fabs(a.half_sum[c] - b.half_sum[c]) / std::fabs(a.half_sum[c]));
        }
    }
    EXPECT_LT(worst, 1e-14);
    EXPECT_NEAR(merged.film.error_estimate(), whole->film().error_estimate(), 1e-9 * whole->film().error_estimate());
    // After the mean is rounded to float and to 8 bits, the images are the same bytes.
    EXPECT_EQ(encode_pfm(merged.film.mean()), encode_pfm(whole->film().mean()));
    EXPECT_EQ(encode_png(merged.film.mean(), Encoding::gamma22), encode_png(whole->film().mean(), Encoding::gamma22));
}

TEST(Partial, RefusesGapsOverlapsForeignPartsAndDamage) {
    const LoadedScene s = testing::small_cornell();
    const std::vector<uint8_t> a = render_part(s, 0, 8), b = render_part(s, 8, 16), c = render_part(s, 16, 24);
    auto error = [](std::vector<std::vector<uint8_t>> files) -> std::string {
        try {
            std::vector<Partial> parts;
            for (const auto& f : files) parts.push_back(decode_partial(f));
            merge_partials(std::move(parts));
        } catch (const PartialError& e) {
            return e.what();
        }
        return "no error";
    };
    EXPECT_EQ(error({a, c}), "samples [8, 16) are missing");
    EXPECT_EQ(error({a, b, b}), "parts overlap: [8, 16) and [8, 16)");
    LoadedScene other = testing::small_cornell();
    other.settings.seed = 7;
    EXPECT_EQ(error({a, render_part(other, 8, 16)}), "part [8, 16) is from another scene or settings");
    std::vector<uint8_t> flipped = b;
    flipped[100] ^= 1;
    EXPECT_EQ(error({a, flipped}), "checksum mismatch: the file is corrupt or truncated");
    EXPECT_EQ(error({std::vector<uint8_t>(a.begin(), a.begin() + 500)}), "checksum mismatch: the file is corrupt or truncated");
    EXPECT_EQ(error({std::vector<uint8_t>(20, 0)}), "not a glint partial file");
    EXPECT_EQ(error({}), "no parts to merge");
    EXPECT_EQ(error({b, a, c}), "no error");
}

// The file's bytes with a correct checksum after the header fields were edited.
std::vector<uint8_t> with_checksum(std::vector<uint8_t> bytes) {
    bytes.resize(bytes.size() - 8);
    Fnv1a h;
    h.bytes(bytes.data(), bytes.size());
    const uint64_t sum = h.digest();
    const auto* p = reinterpret_cast<const uint8_t*>(&sum);
    bytes.insert(bytes.end(), p, p + 8);
    return bytes;
}

template <typename T>
void put(std::vector<uint8_t>& bytes, size_t offset, T value) {
    std::memcpy(&bytes[offset], &value, sizeof value);
}

std::string decode_error(const std::vector<uint8_t>& bytes) {
    try {
        decode_partial(bytes);
    } catch (const PartialError& e) {
        return e.what();
    }
    return "no error";
}

// Found by fuzzing (tests/fuzz/regressions/partial/): an unknown encoding was read as gamma 2.2,
// and a 2^31 x 2^31 header passed the size check (64·W·H wrapped to 0) and asked for 2^62 pixels.
TEST(Partial, RefusesUnknownEncodingsAndSizesThatOverflow) {
    Partial p;
    p.end_sample = 4;
    const std::vector<uint8_t> good = encode_partial(p);
    std::vector<uint8_t> encoding = good;
    put(encoding, 28, uint32_t(168));
    EXPECT_EQ(decode_error(with_checksum(encoding)), "unknown PNG encoding 168 (0 gamma 2.2, 1 sRGB)");
    std::vector<uint8_t> huge(good.begin(), good.begin() + 40);
    put(huge, 12, uint32_t(1) << 31);
    put(huge, 16, uint32_t(1) << 31);
    huge.resize(48);
    EXPECT_EQ(decode_error(with_checksum(huge)), "size does not match the header");
    EXPECT_EQ(decode_error(good), "no error");
}

// Versions 2 and 3, from before the sampler's two replicates, must still be read after an
// upgrade (a server's store holds such files): the same image, an unknown error estimate, and
// sampler version 1, so that they are never merged with or resumed by this version's samples.
std::vector<uint8_t> old_version_file(uint32_t version) {
    const size_t pixel = version == 2 ? 120 : 128, after_count = version == 2 ? 96 : 104;
    std::vector<uint8_t> bytes(40 + pixel + 8);
    const char magic[] = "GLNTPART";
    std::copy(magic, magic + 8, bytes.begin());
    put(bytes, 8, version);
    put(bytes, 12, uint32_t(1));   // width
    put(bytes, 16, uint32_t(1));   // height
    put(bytes, 24, uint32_t(8));   // end sample
    put(bytes, 40, 6.0);           // sum r
    put(bytes, 64, 10.0);          // sum of squares r (of the rounds' sums in version 3)
    put(bytes, 88, uint64_t(8));   // count
    if (version == 3) put(bytes, 96, uint64_t(2));  // rounds
    put(bytes, after_count, uint64_t(1));               // dropped
    put(bytes, after_count + 8, int64_t(5));            // splat r
    put(bytes, after_count + 56, uint64_t(2));          // splats dropped
    return bytes;
}

TEST(Partial, ReadsVersionsTwoAndThreeWithoutHalves) {
    for (uint32_t version : {2u, 3u}) {
        const Partial p = decode_partial(with_checksum(old_version_file(version)));
        const PixelSums& px = p.film.pixel(0, 0);
        EXPECT_EQ(px.sum[0], 6.0);
        EXPECT_EQ(px.half_sum, Rgb{0});
        EXPECT_EQ(px.count, 8u);
        EXPECT_EQ(px.half_count, 0u);
        EXPECT_EQ(px.dropped, 1u);
        EXPECT_EQ(px.splat[0], 5);
        EXPECT_EQ(px.splats_dropped, 2u);
        EXPECT_EQ(p.end_sample, 8u);
        EXPECT_EQ(p.sampler_version, 1u);
        EXPECT_TRUE(std::isinf(p.film.error_estimate()));
    }
    std::vector<uint8_t> v6 = old_version_file(3);
    put(v6, 8, uint32_t(6));
    EXPECT_EQ(decode_error(with_checksum(v6)), "unsupported partial file version 6");
}

// Version 4 is version 5 without the flags (and so without AOVs) and the light paths.
TEST(Partial, ReadsVersionFourAndRefusesUnknownFlags) {
    LoadedScene s = testing::small_cornell();
    s.settings.spp = 4;
    const std::vector<uint8_t> v5 = render_part(s, 0, 4);
    std::vector<uint8_t> v4 = v5;
    v4.erase(v4.begin() + 44, v4.begin() + 56);
    put(v4, 8, uint32_t(4));
    const Partial p = decode_partial(with_checksum(v4));
    EXPECT_FALSE(p.film.has_aovs());
    EXPECT_EQ(encode_partial(p), v5);
    std::vector<uint8_t> flags = v5;
    put(flags, 44, uint32_t(2));
    EXPECT_EQ(decode_error(with_checksum(flags)), "unknown flags 2");
}

// With AOVs: their sums survive the file bit for bit, and parts merge into the whole render's
// AOV images (after rounding to float, as the image's).
TEST(Partial, AovsRoundTripAndMergeIntoTheWholeRender) {
    LoadedScene s = testing::small_cornell(16);
    s.settings.aovs = true;
    const auto whole = testing::render(s);
    const std::vector<uint8_t> bytes = encode_partial(partial_of(*whole, fingerprint(*s.scene, s.settings), 16));
    EXPECT_EQ(bytes.size(), partial_file_size(40, 30, true));
    const Partial read = decode_partial(bytes);
    ASSERT_TRUE(read.film.has_aovs());
    EXPECT_EQ(std::memcmp(read.film.aovs().data(), whole->film().aovs().data(), sizeof(AovSums) * 40 * 30), 0);
    EXPECT_EQ(encode_partial(read), bytes);
    const Partial merged = merge_partials({decode_partial(render_part(s, 8, 16)), decode_partial(render_part(s, 0, 8))});
    for (AovLayer layer : {AovLayer::albedo, AovLayer::normal, AovLayer::depth})
        for (AovHalf half : {AovHalf::all, AovHalf::first, AovHalf::second})
            EXPECT_EQ(encode_pfm(merged.film.aov(layer, half)), encode_pfm(whole->film().aov(layer, half)));
}

TEST(Partial, PartsOfAnotherSamplerVersionDoNotMerge) {
    LoadedScene s = testing::small_cornell();
    s.settings.spp = 8;
    Partial first = decode_partial(render_part(s, 0, 4)), second = decode_partial(render_part(s, 4, 8));
    EXPECT_EQ(first.sampler_version, kSamplerVersion);
    second.sampler_version = 1;
    try {
        merge_partials({first, second});
        FAIL() << "merged";
    } catch (const PartialError& e) {
        EXPECT_EQ(std::string(e.what()), "part [4, 8) was rendered by another version of glint's sampler (1, not " +
                                             std::to_string(kSamplerVersion) + ")");
    }
}

TEST(Partial, FingerprintsDependOnWhatDecidesPixels) {
    const LoadedScene s = testing::small_cornell();
    RenderSettings settings = s.settings;
    const uint64_t base = fingerprint(*s.scene, settings);
    settings.spp = 999;
    settings.first_sample = 400;
    settings.encoding = Encoding::srgb;
    EXPECT_EQ(fingerprint(*s.scene, settings), base);  // parts differ in these
    settings.aovs = true;  // films with and without AOVs never merge
    EXPECT_NE(fingerprint(*s.scene, settings), base);
    settings.aovs = false;
    settings.width += 1;
    EXPECT_NE(fingerprint(*s.scene, settings), base);
    EXPECT_NE(fingerprint(*load_scene(GLINT_SCENES_DIR "/caustic.json").scene, s.settings), base);
}

}  // namespace
}  // namespace glint
