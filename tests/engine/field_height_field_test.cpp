// Height fields: bilinear exactness, clamping, analytic gradient, procedural determinism, PNG loading.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

// engine_tests does not get stb's include directory; libstb itself is linked through the engine.
#include <stb/stb_image_write.h>

#include "field/height_field.h"

namespace ug {
namespace {

//   y=1:  4  6  2        3x2 samples, origin (10, 20), cell 0.5 m
//   y=0:  0  2  8
HeightField smallField() {
    return HeightField(glm::vec2(10.0f, 20.0f), 0.5f, 3, 2, {0, 2, 8, 4, 6, 2});
}

TEST(HeightField, BilinearIsExactAtSamplesAndMidpoints) {
    const HeightField hf = smallField();
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) EXPECT_EQ(hf.sample(10.0f + 0.5f * i, 20.0f + 0.5f * j), hf.at(i, j));
    EXPECT_EQ(hf.sample(10.25f, 20.0f), 1.0f);   // edge midpoint
    EXPECT_EQ(hf.sample(10.0f, 20.25f), 2.0f);
    EXPECT_EQ(hf.sample(10.25f, 20.25f), 3.0f);  // (0 + 2 + 4 + 6) / 4
    EXPECT_EQ(hf.sample(10.75f, 20.25f), 4.5f);  // (2 + 8 + 6 + 2) / 4
    EXPECT_EQ(hf.minHeight(), 0.0f);
    EXPECT_EQ(hf.maxHeight(), 8.0f);
}

TEST(HeightField, ClampsOutsideWithAFlatGradientAcross) {
    const HeightField hf = smallField();
    EXPECT_EQ(hf.sample(0.0f, 0.0f), 0.0f);
    EXPECT_EQ(hf.sample(100.0f, 20.0f), 8.0f);
    EXPECT_EQ(hf.sample(100.0f, 100.0f), 2.0f);
    EXPECT_EQ(hf.sample(10.25f, -5.0f), 1.0f);
    const glm::vec2 g = hf.gradient(10.25f, -5.0f);  // clamped in y only
    EXPECT_EQ(g.x, 4.0f);                             // (2 - 0) / 0.5
    EXPECT_EQ(g.y, 0.0f);
}

TEST(HeightField, GradientIsTheBilinearPatchDerivative) {
    const HeightField hf = smallField();
    // Inside cell (0, 0): h = 4x' + 8y' + (6 - 2 - 4)x'y' with x', y' in cells; per metre: / 0.5.
    const glm::vec2 g = hf.gradient(10.25f, 20.25f);
    EXPECT_EQ(g.x, 4.0f);
    EXPECT_EQ(g.y, 8.0f);
    // Finite differences (double) inside cells, h = 1e-3 m, tolerance 1e-3.
    for (float x : {10.1f, 10.3f, 10.6f, 10.9f})
        for (float y : {20.05f, 20.2f, 20.45f}) {
            const float e = 1e-3f;
            const double fx = (double(hf.sample(x + e, y)) - hf.sample(x - e, y)) / (2.0 * e);
            const double fy = (double(hf.sample(x, y + e)) - hf.sample(x, y - e)) / (2.0 * e);
            EXPECT_NEAR(hf.gradient(x, y).x, fx, 1e-2);
            EXPECT_NEAR(hf.gradient(x, y).y, fy, 1e-2);
        }
}

TEST(HeightField, ProceduralIsDeterministicAndWithinAmplitude) {
    ProceduralTerrainDesc desc;
    desc.width = 33;
    desc.height = 17;
    desc.amplitude_m = 3.0f;
    desc.base_height_m = 10.0f;
    HeightField a, b, c;
    std::string error;
    ASSERT_TRUE(makeProceduralHeightField(desc, &a, &error)) << error;
    ASSERT_TRUE(makeProceduralHeightField(desc, &b, &error)) << error;
    desc.seed = 2;
    ASSERT_TRUE(makeProceduralHeightField(desc, &c, &error)) << error;
    EXPECT_EQ(a.heights(), b.heights());
    EXPECT_NE(a.heights(), c.heights());
    EXPECT_GE(a.minHeight(), 7.0f);
    EXPECT_LE(a.maxHeight(), 13.0f);
    EXPECT_GT(a.maxHeight() - a.minHeight(), 0.1f);

    desc.octaves = 0;
    EXPECT_FALSE(makeProceduralHeightField(desc, &a, &error));
    EXPECT_NE(error.find("octaves"), std::string::npos) << error;
    desc.octaves = 3;
    desc.cell_size_m = NAN;
    EXPECT_FALSE(makeProceduralHeightField(desc, &a, &error));
    EXPECT_NE(error.find("cell_size_m"), std::string::npos) << error;
}

std::string tempPath(const char* name) {
    return (std::filesystem::temp_directory_path() / (std::string("ug_field_test_") + name)).string();
}

// stb_image_write only writes 8-bit PNGs; this writes a 16-bit grayscale one with stored (uncompressed)
// deflate blocks, enough for a test image. width/height of the IHDR can be overridden to fake a size.
void writePng16(const std::string& path, int w, int h, const std::vector<uint16_t>& pixels, bool with_data = true) {
    uint32_t crc_table[256];
    for (uint32_t n = 0; n < 256; ++n) {
        uint32_t c = n;
        for (int k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
        crc_table[n] = c;
    }
    std::vector<unsigned char> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    auto be32 = [](std::vector<unsigned char>& v, uint32_t x) {
        for (int s = 24; s >= 0; s -= 8) v.push_back((unsigned char)(x >> s));
    };
    auto chunk = [&](const char* type, const std::vector<unsigned char>& data) {
        be32(out, uint32_t(data.size()));
        std::vector<unsigned char> body(type, type + 4);
        body.insert(body.end(), data.begin(), data.end());
        uint32_t c = 0xffffffffu;
        for (unsigned char b : body) c = crc_table[(c ^ b) & 0xff] ^ (c >> 8);
        out.insert(out.end(), body.begin(), body.end());
        be32(out, c ^ 0xffffffffu);
    };
    std::vector<unsigned char> ihdr;
    be32(ihdr, uint32_t(w));
    be32(ihdr, uint32_t(h));
    ihdr.insert(ihdr.end(), {16, 0, 0, 0, 0});  // 16-bit, grayscale
    chunk("IHDR", ihdr);
    if (with_data) {
        std::vector<unsigned char> raw;
        for (int y = 0; y < h; ++y) {
            raw.push_back(0);  // filter: none
            for (int x = 0; x < w; ++x) {
                raw.push_back((unsigned char)(pixels[size_t(y * w + x)] >> 8));
                raw.push_back((unsigned char)(pixels[size_t(y * w + x)] & 0xff));
            }
        }
        std::vector<unsigned char> z = {0x78, 0x01, 1};  // zlib header, one final stored block
        const uint16_t len = uint16_t(raw.size());
        z.insert(z.end(), {(unsigned char)(len & 0xff), (unsigned char)(len >> 8), (unsigned char)(~len & 0xff),
                           (unsigned char)((~len >> 8) & 0xff)});
        z.insert(z.end(), raw.begin(), raw.end());
        uint32_t a = 1, b = 0;
        for (unsigned char c : raw) {
            a = (a + c) % 65521;
            b = (b + a) % 65521;
        }
        be32(z, (b << 16) | a);
        chunk("IDAT", z);
    }
    chunk("IEND", {});
    FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_TRUE(f);
    std::fwrite(out.data(), 1, out.size(), f);
    std::fclose(f);
}

TEST(HeightField, Loads8BitPngWithRowZeroAtTheTop) {
    // Picture (row 0 on top):  255   0          -> y = 1:  10  0
    //                          51   102         -> y = 0:   2  4     (min 0 m, max 10 m)
    const std::string path = tempPath("h8.png");
    const unsigned char pixels[4] = {255, 0, 51, 102};
    ASSERT_NE(stbi_write_png(path.c_str(), 2, 2, 1, pixels, 2), 0);
    HeightField hf;
    std::string error;
    ASSERT_TRUE(loadHeightFieldPng(path, HeightFieldImageDesc{.cell_size_m = 2.0f, .max_height_m = 10.0f}, &hf, &error))
        << error;
    EXPECT_EQ(hf.width(), 2);
    EXPECT_EQ(hf.height(), 2);
    EXPECT_EQ(hf.cellSize(), 2.0f);
    EXPECT_FLOAT_EQ(hf.at(0, 1), 10.0f);
    EXPECT_FLOAT_EQ(hf.at(1, 1), 0.0f);
    EXPECT_FLOAT_EQ(hf.at(0, 0), 2.0f);
    EXPECT_FLOAT_EQ(hf.at(1, 0), 4.0f);
    std::remove(path.c_str());
}

TEST(HeightField, Loads16BitPngAtFullPrecision) {
    const std::string path = tempPath("h16.png");
    writePng16(path, 3, 1, {0, 1, 65535});
    HeightField hf;
    std::string error;
    ASSERT_TRUE(loadHeightFieldPng(path, HeightFieldImageDesc{.min_height_m = -1.0f, .max_height_m = 65534.0f}, &hf, &error))
        << error;
    EXPECT_EQ(hf.width(), 3);
    EXPECT_EQ(hf.height(), 1);
    EXPECT_FLOAT_EQ(hf.at(0, 0), -1.0f);
    EXPECT_FLOAT_EQ(hf.at(1, 0), 0.0f);  // one step of 65535 is kept, not rounded to 8 bits
    EXPECT_FLOAT_EQ(hf.at(2, 0), 65534.0f);
    std::remove(path.c_str());
}

TEST(HeightField, PngErrorsNameTheFileAndTheReason) {
    HeightField hf;
    std::string error;
    const std::string missing = tempPath("does_not_exist.png");
    EXPECT_FALSE(loadHeightFieldPng(missing, {}, &hf, &error));
    EXPECT_NE(error.find(missing), std::string::npos) << error;
    EXPECT_NE(error.find("cannot open"), std::string::npos) << error;

    const std::string text = tempPath("not_an_image.png");
    FILE* f = std::fopen(text.c_str(), "wb");
    ASSERT_TRUE(f);
    std::fputs("this is not a picture\n", f);
    std::fclose(f);
    EXPECT_FALSE(loadHeightFieldPng(text, {}, &hf, &error));
    EXPECT_NE(error.find(text), std::string::npos) << error;
    EXPECT_NE(error.find("not a PNG file"), std::string::npos) << error;
    std::remove(text.c_str());

    const std::string huge = tempPath("huge.png");
    writePng16(huge, 20000, 2, {}, false);  // header only: refused before decoding
    EXPECT_FALSE(loadHeightFieldPng(huge, {}, &hf, &error));
    EXPECT_NE(error.find("20000x2"), std::string::npos) << error;
    std::remove(huge.c_str());

    EXPECT_TRUE(hf.empty());  // untouched by every failure
}

}  // namespace
}  // namespace ug
