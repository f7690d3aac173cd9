#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include "core/error.h"
#include "image/image.h"
#include "image/srgb.h"
#include "scratch_directory.h"

namespace vkdr {
namespace {

// A minimal PNG encoder for 16-bit samples, which stb_image_write cannot produce:
// unfiltered rows in uncompressed ("stored") deflate blocks. `headerBitDepth` other than
// 16 makes a header that disagrees with the samples, for the checks that refuse it.
class Png16Encoder {
public:
    static std::string encode(int width, int height, int channels, const std::vector<uint16_t>& samples,
                              char headerBitDepth = 16) {
        std::string raw;
        for (int y = 0; y < height; ++y) {
            raw += '\0';  // filter: none
            for (int i = 0; i < width * channels; ++i) {
                uint16_t s = samples[size_t(y) * width * channels + i];
                raw += char(s >> 8);
                raw += char(s & 0xff);
            }
        }
        const char colourTypes[] = {0, 0, 4, 2, 6};  // by channel count: grey, grey+alpha, RGB, RGBA
        std::string header = bigEndian(uint32_t(width)) + bigEndian(uint32_t(height)) + headerBitDepth +
                             colourTypes[channels] + std::string(3, '\0');
        return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + chunk("IDAT", zlibStored(raw)) +
               chunk("IEND", "");
    }

private:
    static std::string bigEndian(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

    static std::string chunk(const std::string& type, const std::string& data) {
        std::string typed = type + data;
        return bigEndian(uint32_t(data.size())) + typed + bigEndian(crc32(typed));
    }

    static uint32_t crc32(const std::string& bytes) {
        uint32_t crc = 0xffffffffu;
        for (unsigned char b : bytes) {
            crc ^= b;
            for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
        }
        return ~crc;
    }

    static std::string zlibStored(const std::string& raw) {
        std::string out = "\x78\x01";
        size_t offset = 0;
        do {
            size_t length = std::min<size_t>(raw.size() - offset, 65535);
            bool last = offset + length == raw.size();
            out += char(last ? 1 : 0);
            out += {char(length & 0xff), char(length >> 8), char(~length & 0xff), char((~length >> 8) & 0xff)};
            out += raw.substr(offset, length);
            offset += length;
        } while (offset < raw.size());
        uint32_t a = 1, b = 0;
        for (unsigned char c : raw) {
            a = (a + c) % 65521;
            b = (b + a) % 65521;
        }
        return out + bigEndian((b << 16) | a);
    }
};

TEST(Png, RoundTripIsWithinOneStepAfterEncoding) {
    test::ScratchDirectory dir;
    Image image{16, 8, {}};
    for (int i = 0; i < 16 * 8 * 3; ++i) image.rgb.push_back(float(i) / (16 * 8 * 3 - 1));
    image.rgb[0] = -1.0f;  // clamped to 0
    image.rgb[1] = 5.0f;   // clamped to 1
    image.pixel(3, 0)[0] = 0.0f;  // top row differs from the bottom: catches flips
    image.pixel(3, 7)[0] = 1.0f;
    writePng(dir / "a.png", image);
    Image read = readImage(dir / "a.png");
    ASSERT_EQ(read.width, 16);
    ASSERT_EQ(read.height, 8);
    for (size_t i = 0; i < image.rgb.size(); ++i)
        // srgbFromLinear clamps, as writePng does.
        EXPECT_NEAR(srgbFromLinear(read.rgb[i]), srgbFromLinear(image.rgb[i]), 1.0f / 255.0f) << i;
}

TEST(Png, EncodesWithRoundingToTheNearestStep) {
    test::ScratchDirectory dir;
    // Linear values whose encodings are 100.4 and 100.6 steps of 1/255.
    Image image{2, 1, {linearFromSrgb(100.4f / 255), 0, 0, linearFromSrgb(100.6f / 255), 0, 0}};
    writePng(dir / "r.png", image);
    Image read = readImage(dir / "r.png");
    EXPECT_NEAR(srgbFromLinear(read.rgb[0]) * 255, 100.0f, 1e-3f);
    EXPECT_NEAR(srgbFromLinear(read.rgb[3]) * 255, 101.0f, 1e-3f);
}

TEST(Png, GreyAndAlphaLayoutsDecodeToRgb) {
    test::ScratchDirectory dir;
    const unsigned char grey[] = {0, 255};
    const unsigned char greyAlpha[] = {0, 9, 255, 9};
    const unsigned char rgba[] = {255, 0, 0, 9, 0, 0, 255, 9};
    ASSERT_TRUE(stbi_write_png((dir / "g.png").c_str(), 2, 1, 1, grey, 2));
    ASSERT_TRUE(stbi_write_png((dir / "ga.png").c_str(), 2, 1, 2, greyAlpha, 4));
    ASSERT_TRUE(stbi_write_png((dir / "rgba.png").c_str(), 2, 1, 4, rgba, 8));
    std::vector<float> blackWhite{0, 0, 0, 1, 1, 1};
    EXPECT_EQ(readImage(dir / "g.png").rgb, blackWhite);
    EXPECT_EQ(readImage(dir / "ga.png").rgb, blackWhite);
    EXPECT_EQ(readImage(dir / "rgba.png").rgb, (std::vector<float>{1, 0, 0, 0, 0, 1}));
}

// PNG allows RGB only 8 or 16 bits a sample; stb_image would decode a 1-bit RGB file.
TEST(Png, BitDepthsPngDoesNotAllowAreRefused) {
    test::ScratchDirectory dir;
    test::writeBytes(dir / "rgb1.png", Png16Encoder::encode(2, 1, 3, {0, 1000, 30000, 65535, 12345, 54321}, 1));
    test::writeBytes(dir / "grey3.png", Png16Encoder::encode(3, 1, 1, {0, 1000, 65535}, 3));
    for (const auto& [file, parts] : std::vector<std::pair<std::string, std::vector<std::string>>>{
             {"rgb1.png", {"colour type 2 has bit depth 1", "allows it 8, 16"}},
             {"grey3.png", {"colour type 0 has bit depth 3", "allows it 1, 2, 4, 8, 16"}}}) {
        try {
            readImage(dir / file);
            ADD_FAILURE() << file << " was read";
        } catch (const Error& e) {
            for (const std::string& part : parts) {
                EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
            }
            EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
        }
    }
}

TEST(Png, SixteenBitSamplesKeepTheirPrecision) {
    test::ScratchDirectory dir;
    std::vector<uint16_t> samples{0, 1000, 30000, 65535, 12345, 54321};
    test::writeBytes(dir / "rgb16.png", Png16Encoder::encode(2, 1, 3, samples));
    test::writeBytes(dir / "grey16.png", Png16Encoder::encode(3, 1, 1, {0, 1000, 65535}));
    Image rgb = readImage(dir / "rgb16.png");
    ASSERT_EQ(rgb.rgb.size(), 6u);
    for (size_t i = 0; i < samples.size(); ++i) EXPECT_FLOAT_EQ(rgb.rgb[i], linearFromSrgb(samples[i] / 65535.0f));
    Image grey = readImage(dir / "grey16.png");
    ASSERT_EQ(grey.width, 3);
    EXPECT_FLOAT_EQ(grey.pixel(1, 0)[2], linearFromSrgb(1000 / 65535.0f));
}

TEST(Jpeg, ReadsAndDecodesSrgb) {
    test::ScratchDirectory dir;
    std::vector<unsigned char> pixels(8 * 8 * 3, 128);
    ASSERT_TRUE(stbi_write_jpg((dir / "grey.jpg").c_str(), 8, 8, 3, pixels.data(), 100));
    Image read = readImage(dir / "grey.jpg");
    ASSERT_EQ(read.width, 8);
    for (float v : read.rgb) EXPECT_NEAR(srgbFromLinear(v), 128.0f / 255, 2.0f / 255);
}

// The decoder refuses images of no pixels or too many for it, and its callers lose its
// reason: the header's size is named instead of "unknown image type".
// stb_image checks no CRC: a byte of the pixel data changed would decode to other pixels.
// A critical chunk whose CRC does not match is refused, as libpng does; an ancillary one,
// which libpng only warns of and stb_image does not read, is not.
TEST(Png, ACriticalChunkWhoseCrcDoesNotMatchIsRefused) {
    test::ScratchDirectory dir;
    const std::string png = Png16Encoder::encode(2, 2, 3, std::vector<uint16_t>(12, 30000));
    const size_t idat = png.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    std::string damaged = png;
    damaged[idat + 4 + 7] ^= 0x01;  // a sample byte of the first row
    test::writeBytes(dir / "damaged.png", damaged);
    try {
        readImage(dir / "damaged.png");
        ADD_FAILURE() << "damaged.png was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the PNG chunk 'IDAT' at byte " + std::to_string(idat - 4) +
                                             " is damaged (its CRC does not match its bytes)"),
                  std::string::npos)
            << e.what();
    }
    // An ancillary text chunk with a wrong CRC before the image data.
    const std::string text = "Comment";
    const std::string ancillary = std::string("\0\0\0\x07", 4) + "tEXt" + text + "\xde\xad\xbe\xef";
    std::string withText = png;
    withText.insert(idat - 4, ancillary);
    test::writeBytes(dir / "text.png", withText);
    test::writeBytes(dir / "good.png", png);
    EXPECT_EQ(readImage(dir / "text.png").rgb, readImage(dir / "good.png").rgb);
}

TEST(EncodedImages, SizesTheHeaderGivesAreNamed) {
    test::ScratchDirectory dir;
    auto expectRefused = [&](const std::string& file, const std::string& part) {
        try {
            readImage(dir / file);
            ADD_FAILURE() << file << " was read";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
        }
    };
    // A header of 20000 x 20000 pixels over one row's samples: the size is checked first.
    std::string huge = Png16Encoder::encode(1, 1, 1, {0});
    const std::string big = {0, 0, 0x4e, 0x20};  // 20000, big-endian
    huge.replace(16, 4, big).replace(20, 4, big);
    test::writeBytes(dir / "huge.png", huge);
    expectRefused("huge.png", "20000 x 20000 pixels is too large");
    std::string empty = Png16Encoder::encode(1, 1, 1, {0});
    empty.replace(16, 4, std::string(4, '\0'));
    test::writeBytes(dir / "empty.png", empty);
    expectRefused("empty.png", "the image is empty (0 x 1 pixels)");

    std::vector<unsigned char> pixels(8 * 8 * 3, 128);
    ASSERT_TRUE(stbi_write_jpg((dir / "grey.jpg").c_str(), 8, 8, 3, pixels.data(), 100));
    std::string jpeg = test::readBytes(dir / "grey.jpg");
    const size_t frame = jpeg.find("\xff\xc0");
    ASSERT_NE(frame, std::string::npos);
    // After the marker: the segment's length (2 bytes), precision (1), height and width (2 each).
    test::writeBytes(dir / "wide.jpg", std::string(jpeg).replace(frame + 5, 4, std::string("\x40\x00\xff\xff", 4)));
    expectRefused("wide.jpg", "65535 x 16384 pixels is too large");
    test::writeBytes(dir / "flat.jpg", std::string(jpeg).replace(frame + 5, 2, std::string(2, '\0')));
    expectRefused("flat.jpg", "leaves its height to a DNL marker");
    test::writeBytes(dir / "narrow.jpg", std::string(jpeg).replace(frame + 7, 2, std::string(2, '\0')));
    expectRefused("narrow.jpg", "the image is empty (0 x 8 pixels)");
}

}  // namespace
}  // namespace vkdr
