#include <algorithm>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>

#include "core/error.h"
#include "image/atomic_write.h"
#include "image/encoded_image_checks.h"
#include "image/image_formats.h"

namespace vkdr {
namespace {

[[noreturn]] void failToRead(const std::filesystem::path& file, const std::string& reason) {
    throw Error("cannot read EXR '" + file.string() + "': " + reason);
}

std::string channelNames(const Imf::ChannelList& channels) {
    std::string names;
    for (auto c = channels.begin(); c != channels.end(); ++c) names += (names.empty() ? "" : ", ") + std::string(c.name());
    return names.empty() ? "none" : names;
}

// The file's channels that become R, G and B, in that order: the colour channels, or
// Y alone, which readExrFile copies to all three.
std::vector<const char*> channelsToRead(const std::filesystem::path& file, const Imf::ChannelList& channels) {
    if (channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B")) return {"R", "G", "B"};
    if (channels.findChannel("Y")) return {"Y"};
    failToRead(file, "needs channels R, G and B, or Y; found " + channelNames(channels));
}

// OpenEXR checks a header against these before it allocates the line offset table or
// any tile, so that a corrupt header cannot make it claim memory for a huge image.
void limitExrSizes() {
    constexpr int kMaxSide = 1 << 16;
    Imf::Header::setMaxImageSize(kMaxSide, kMaxSide);
    Imf::Header::setMaxTileSize(kMaxSide, kMaxSide);
}

Image readExrFile(const std::filesystem::path& file) {
    limitExrSizes();
    Imf::InputFile input(file.c_str());
    const Imf::Header& header = input.header();
    std::vector<const char*> sources = channelsToRead(file, header.channels());

    // OpenEXR's y axis points down, so the data window's first row is the top one.
    const Imath::Box2i& window = header.dataWindow();
    int64_t width = int64_t(window.max.x) - window.min.x + 1;
    int64_t height = int64_t(window.max.y) - window.min.y + 1;
    if (std::string problem = imageSizeProblem(uint64_t(std::max<int64_t>(width, 0)),
                                               uint64_t(std::max<int64_t>(height, 0)));
        !problem.empty()) {
        failToRead(file, problem);
    }

    Image image;
    image.width = int(width);
    image.height = int(height);
    image.rgb.resize(size_t(width) * size_t(height) * 3);
    Imf::FrameBuffer frameBuffer;
    for (size_t c = 0; c < sources.size(); ++c) {
        // Half channels are converted to float by the library.
        frameBuffer.insert(sources[c], Imf::Slice::Make(Imf::FLOAT, image.rgb.data() + c, window, 3 * sizeof(float),
                                                        size_t(width) * 3 * sizeof(float)));
    }
    input.setFrameBuffer(frameBuffer);
    input.readPixels(window.min.y, window.max.y);
    if (sources.size() == 1)
        for (size_t p = 0; p < image.rgb.size(); p += 3) image.rgb[p + 1] = image.rgb[p + 2] = image.rgb[p];
    return image;
}

}  // namespace

void writeExr(const std::filesystem::path& file, const Image& image, PendingRenames* pending) {
    if (image.width <= 0 || image.height <= 0 || image.rgb.size() != size_t(image.width) * image.height * 3)
        throw Error("cannot write EXR '" + file.string() + "': the image has no pixels or the wrong number of values");
    writeAtomically(file, [&](std::ofstream& out) {
        Imf::Header header(image.width, image.height);
        for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        Imf::FrameBuffer frameBuffer;
        const size_t xStride = 3 * sizeof(float), yStride = size_t(image.width) * xStride;
        // OpenEXR only reads through these pointers while writing.
        char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
        frameBuffer.insert("R", Imf::Slice(Imf::FLOAT, base, xStride, yStride));
        frameBuffer.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xStride, yStride));
        frameBuffer.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xStride, yStride));
        Imf::StdOFStream stream(out, file.c_str());
        Imf::OutputFile output(stream, header);
        output.setFrameBuffer(frameBuffer);
        output.writePixels(image.height);
    }, pending);
}

Image readExr(const std::filesystem::path& file) {
    try {
        return readExrFile(file);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        // OpenEXR reports truncated and corrupt files with Iex exceptions.
        failToRead(file, e.what());
    }
}

}  // namespace vkdr
