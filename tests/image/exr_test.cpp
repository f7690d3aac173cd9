#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfLineOrder.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <half.h>

#include "core/error.h"
#include "image/image.h"
#include "scratch_directory.h"

namespace vkdr {
namespace {

Image randomImage(int width, int height, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> value(-10.0f, 1000.0f);
    Image image{width, height, std::vector<float>(size_t(width) * height * 3)};
    for (float& v : image.rgb) v = value(rng);
    return image;
}

// Writes `values` (one per pixel of the window, per channel) with the raw OpenEXR API.
void writeRawExr(const std::filesystem::path& file, const Imath::Box2i& dataWindow,
                 const std::vector<std::string>& channels, Imf::PixelType type, const std::vector<float>& values) {
    Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(99, 99));
    Imf::Header header(display, dataWindow);
    int width = dataWindow.max.x - dataWindow.min.x + 1, height = dataWindow.max.y - dataWindow.min.y + 1;
    std::vector<half> halves(values.begin(), values.end());
    Imf::FrameBuffer frameBuffer;
    for (size_t c = 0; c < channels.size(); ++c) {
        header.channels().insert(channels[c], Imf::Channel(type));
        size_t sampleSize = type == Imf::HALF ? sizeof(half) : sizeof(float);
        const char* base = type == Imf::HALF ? reinterpret_cast<const char*>(halves.data())
                                             : reinterpret_cast<const char*>(values.data());
        frameBuffer.insert(channels[c],
                           Imf::Slice::Make(type, base + c * size_t(width) * height * sampleSize, dataWindow,
                                            sampleSize, size_t(width) * sampleSize));
    }
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frameBuffer);
    out.writePixels(height);
}

TEST(Exr, RoundTripIsBitExact) {
    test::ScratchDirectory dir;
    Image image = randomImage(17, 9, 1);
    image.rgb[0] = std::numeric_limits<float>::infinity();
    image.rgb[1] = -0.0f;
    image.rgb[2] = std::numeric_limits<float>::denorm_min();
    writeExr(dir / "a.exr", image);
    Image read = readImage(dir / "a.exr");
    ASSERT_EQ(read.width, image.width);
    ASSERT_EQ(read.height, image.height);
    ASSERT_EQ(read.rgb.size(), image.rgb.size());
    EXPECT_EQ(std::memcmp(read.rgb.data(), image.rgb.data(), image.rgb.size() * sizeof(float)), 0);
}

TEST(Exr, FirstScanlineInTheFileIsTheTopRow) {
    test::ScratchDirectory dir;
    Image image{4, 3, std::vector<float>(4 * 3 * 3, 0.0f)};
    for (int x = 0; x < 4; ++x) image.pixel(x, 0)[1] = 7.0f;  // the top row is green
    writeExr(dir / "top.exr", image);

    Imf::InputFile in((dir / "top.exr").c_str());
    EXPECT_EQ(in.header().lineOrder(), Imf::INCREASING_Y);
    const Imath::Box2i& window = in.header().dataWindow();
    std::vector<float> firstLine(4);
    Imf::FrameBuffer frameBuffer;
    // A buffer for just the first scanline: its origin sits at (min.x, min.y).
    frameBuffer.insert("G", Imf::Slice::Make(Imf::FLOAT, firstLine.data(), Imath::V2i(window.min.x, window.min.y),
                                             int64_t(4), int64_t(1), sizeof(float)));
    in.setFrameBuffer(frameBuffer);
    in.readPixels(window.min.y, window.min.y);
    EXPECT_EQ(firstLine, std::vector<float>(4, 7.0f));
}

TEST(Exr, ReadsHalfChannelsInAnOffsetDataWindow) {
    test::ScratchDirectory dir;
    Imath::Box2i window(Imath::V2i(10, -5), Imath::V2i(12, -4));  // 3 x 2
    std::vector<float> values;  // R plane, G plane, B plane
    for (int c = 0; c < 3; ++c)
        for (int p = 0; p < 6; ++p) values.push_back(float(c * 10 + p) + 0.5f);
    writeRawExr(dir / "half.exr", window, {"R", "G", "B"}, Imf::HALF, values);
    Image read = readImage(dir / "half.exr");
    ASSERT_EQ(read.width, 3);
    ASSERT_EQ(read.height, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(read.pixel(x, y)[c], float(c * 10 + y * 3 + x) + 0.5f);
}

TEST(Exr, LuminanceOnlyReadsAsGrey) {
    test::ScratchDirectory dir;
    writeRawExr(dir / "y.exr", Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(1, 0)), {"Y"}, Imf::FLOAT, {0.25f, 3.0f});
    Image read = readImage(dir / "y.exr");
    ASSERT_EQ(read.rgb.size(), 6u);
    EXPECT_EQ(read.rgb, (std::vector<float>{0.25f, 0.25f, 0.25f, 3.0f, 3.0f, 3.0f}));
}

TEST(Exr, MissingColourChannelsAreNamed) {
    test::ScratchDirectory dir;
    writeRawExr(dir / "az.exr", Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(0, 0)), {"A", "R", "Z"}, Imf::FLOAT,
                {1.0f, 2.0f, 3.0f});
    try {
        readImage(dir / "az.exr");
        FAIL() << "expected vkdr::Error";
    } catch (const Error& e) {
        std::string message = e.what();
        EXPECT_NE(message.find("az.exr"), std::string::npos) << message;
        EXPECT_NE(message.find("A, R, Z"), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace vkdr
