#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>
#include <zlib.h>

#include "core/error.h"
#include "core/printable_text.h"
#include "image/atomic_write.h"
#include "image/image.h"
#include "image/image_formats.h"
#include "scratch_directory.h"

namespace vkdr {
namespace {

Image smallImage() { return Image{2, 2, std::vector<float>(12, 0.5f)}; }

// Runs f and expects a vkdr::Error whose message names file and gives a reason, in
// printable text.
template <typename F>
void expectErrorNaming(const std::filesystem::path& file, F&& f) {
    try {
        f();
        ADD_FAILURE() << "expected vkdr::Error for " << file;
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(file.filename().string()), std::string::npos) << message;
        EXPECT_NE(message.back(), ' ') << "no reason after the file: " << message;
        EXPECT_EQ(printableText(message), message);
    }
}

TEST(AtomicWrite, FailureLeavesThePreviousFileAndNoTemporary) {
    test::ScratchDirectory dir;
    test::writeBytes(dir / "out.exr", "previous good result");
    expectErrorNaming(dir / "out.exr", [&] {
        writeAtomically(dir / "out.exr", [](std::ofstream& out) {
            out << "half of a file";
            throw std::runtime_error("disk full");
        });
    });
    EXPECT_EQ(test::readBytes(dir / "out.exr"), "previous good result");
    EXPECT_EQ(dir.fileCount(), 1u);
}

// Files written together are replaced together: where the second fails, the first is
// left as it was too, and no temporary stays; committed, both are replaced.
TEST(AtomicWrite, FilesWrittenTogetherAreReplacedTogether) {
    test::ScratchDirectory dir;
    test::writeBytes(dir / "out.exr", "previous image");
    test::writeBytes(dir / "out.png", "previous preview");
    expectErrorNaming(dir / "out.png", [&] {
        PendingRenames pending;
        writeExr(dir / "out.exr", smallImage(), &pending);
        writeAtomically(dir / "out.png", [](std::ofstream&) { throw std::runtime_error("disk full"); }, &pending);
        pending.commit();
    });
    EXPECT_EQ(test::readBytes(dir / "out.exr"), "previous image");
    EXPECT_EQ(test::readBytes(dir / "out.png"), "previous preview");
    EXPECT_EQ(dir.fileCount(), 2u);

    {
        PendingRenames pending;
        writeExr(dir / "out.exr", smallImage(), &pending);
        writePng(dir / "out.png", smallImage(), &pending);
        EXPECT_EQ(test::readBytes(dir / "out.exr"), "previous image") << "replaced before the commit";
        pending.commit();
    }
    EXPECT_EQ(readImage(dir / "out.exr").rgb, smallImage().rgb);
    EXPECT_EQ(readImage(dir / "out.png").width, 2);
    EXPECT_EQ(dir.fileCount(), 2u);
}

TEST(AtomicWrite, RemovesTheTemporariesOfKilledWritersOnly) {
    test::ScratchDirectory dir;
    // No process has an id above the kernel's pid_max (at most 2^22).
    test::writeBytes(dir / ".log.jsonl.tmp-2000000000-3", "half of a line");
    std::string ours = ".params.json.tmp-" + std::to_string(getpid()) + "-0";
    test::writeBytes(dir / ours, "being written");
    test::writeBytes(dir / "notes.tmp-2000000000-1", "not a temporary: no leading dot");
    EXPECT_EQ(removeStaleTemporaries(dir.path()), 1u);
    EXPECT_FALSE(std::filesystem::exists(dir / ".log.jsonl.tmp-2000000000-3"));
    EXPECT_TRUE(std::filesystem::exists(dir / ours));
    EXPECT_EQ(dir.fileCount(), 2u);
}

TEST(AtomicWrite, SuccessReplacesTheFile) {
    test::ScratchDirectory dir;
    test::writeBytes(dir / "out.exr", "old");
    writeExr(dir / "out.exr", smallImage());
    EXPECT_EQ(readImage(dir / "out.exr").rgb, smallImage().rgb);
    EXPECT_EQ(dir.fileCount(), 1u);
}

TEST(AtomicWrite, RenameOntoADirectoryFailsCleanly) {
    test::ScratchDirectory dir;
    std::filesystem::create_directory(dir / "taken.png");
    test::writeBytes(dir / "taken.png" / "inside", "x");
    expectErrorNaming(dir / "taken.png", [&] { writePng(dir / "taken.png", smallImage()); });
    expectErrorNaming(dir / "taken.png", [&] { writeExr(dir / "taken.png", smallImage()); });
    EXPECT_EQ(dir.fileCount(), 1u);
    EXPECT_TRUE(std::filesystem::is_directory(dir / "taken.png"));
}

TEST(AtomicWrite, MissingDirectoryIsAnError) {
    test::ScratchDirectory dir;
    expectErrorNaming(dir / "nowhere" / "a.exr", [&] { writeExr(dir / "nowhere" / "a.exr", smallImage()); });
    expectErrorNaming(dir / "nowhere" / "a.png", [&] { writePng(dir / "nowhere" / "a.png", smallImage()); });
    EXPECT_EQ(dir.fileCount(), 0u);
}

TEST(AtomicWrite, ReadOnlyDirectoryIsAnError) {
    if (geteuid() == 0) GTEST_SKIP() << "root writes into read-only directories";
    test::ScratchDirectory dir;
    std::filesystem::permissions(dir.path(), std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    expectErrorNaming(dir / "a.exr", [&] { writeExr(dir / "a.exr", smallImage()); });
}

TEST(ReadImage, MissingFile) {
    test::ScratchDirectory dir;
    expectErrorNaming(dir / "missing.exr", [&] { readImage(dir / "missing.exr"); });
    expectErrorNaming(dir / "missing.png", [&] { readImage(dir / "missing.png"); });
}

TEST(ReadImage, TruncatedExr) {
    test::ScratchDirectory dir;
    Image image{64, 64, std::vector<float>(64 * 64 * 3)};
    for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = float(i % 1013);
    writeExr(dir / "whole.exr", image);
    std::string bytes = test::readBytes(dir / "whole.exr");
    for (size_t length : {size_t(0), size_t(3), size_t(40), bytes.size() / 2, bytes.size() - 1}) {
        test::writeBytes(dir / "cut.exr", bytes.substr(0, length));
        expectErrorNaming(dir / "cut.exr", [&] { readImage(dir / "cut.exr"); });
    }
}

TEST(ReadImage, TruncatedPng) {
    test::ScratchDirectory dir;
    writePng(dir / "whole.png", Image{32, 32, std::vector<float>(32 * 32 * 3, 0.3f)});
    std::string bytes = test::readBytes(dir / "whole.png");
    // 33 bytes: the signature and the header chunk, nothing else; 40: cut inside the next
    // chunk's name.
    for (size_t length : {size_t(0), size_t(8), size_t(33), size_t(40), bytes.size() / 2, bytes.size() - 13}) {
        test::writeBytes(dir / "cut.png", bytes.substr(0, length));
        expectErrorNaming(dir / "cut.png", [&] { readImage(dir / "cut.png"); });
        if (length == 40) {  // stb_image's reason alone would be the name cut short, "IDA"
            try {
                readImage(dir / "cut.png");
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find("damaged"), std::string::npos) << length << ": " << e.what();
            }
        }
    }
}

// Messages may quote a damaged file's own bytes: those that are not printable UTF-8 are
// written as \xNN, so that the message is one printable line (and a Python str).
TEST(ReadImage, DamagedBytesInAMessageAreEscaped) {
    EXPECT_EQ(printableText("a\x03" "b\xf0" "c\n"), "a\\x03b\\xf0c\\x0a");
    EXPECT_EQ(printableText("sc\xc3\xa8ne \xe2\x82\xac"), "sc\xc3\xa8ne \xe2\x82\xac");  // UTF-8 is kept
    EXPECT_EQ(printableText("\xc3"), "\\xc3");                                 // a sequence cut short
    EXPECT_EQ(printableText("\xed\xa0\x80"), "\\xed\\xa0\\x80");              // a UTF-16 surrogate
    EXPECT_EQ(printableText("\xe0\x80\xaf"), "\\xe0\\x80\\xaf");              // an overlong '/'

    test::ScratchDirectory dir;
    writeExr(dir / "whole.exr", smallImage());
    std::string bytes = test::readBytes(dir / "whole.exr");
    const size_t blue = bytes.find(std::string("B\0", 2));
    ASSERT_NE(blue, std::string::npos);
    bytes[blue] = char(0xf0);  // the channel "B" becomes "\xf0"
    test::writeBytes(dir / "renamed.exr", bytes);
    try {
        readImage(dir / "renamed.exr");
        ADD_FAILURE() << "an EXR without a B channel was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("found G, R, \\xf0"), std::string::npos) << e.what();
    }
}

TEST(ReadImage, GarbageBytes) {
    test::ScratchDirectory dir;
    std::string garbage(1000, '\0');
    for (size_t i = 0; i < garbage.size(); ++i) garbage[i] = char(i * 7919 % 251);
    for (const char* name : {"g.exr", "g.png", "g.jpg", "g.jpeg"}) {
        test::writeBytes(dir / name, garbage);
        expectErrorNaming(dir / name, [&] { readImage(dir / name); });
    }
    // A valid EXR magic number followed by nonsense.
    test::writeBytes(dir / "magic.exr", std::string("\x76\x2f\x31\x01\x02\x00\x00\x00", 8) + garbage);
    expectErrorNaming(dir / "magic.exr", [&] { readImage(dir / "magic.exr"); });
}

// A corrupted file either throws vkdr::Error or reads as a consistent image: positive
// sides, no more pixels than the readers allow, three values per pixel, and for PNG
// (8-bit data) values in [0, 1]. A flipped byte in pixel data may still decode, and one
// in an EXR's float data may decode to any float, so EXR values are not checked.
// A PNG chunk's CRC catches a changed byte; every other damaged PNG gets CRCs that match
// its bytes again, as a file made to get past that check would, so that the decoder sees
// the damage.
std::string withMatchingPngCrcs(std::string bytes) {
    auto bigEndian = [&](size_t at) {
        return uint32_t(uint8_t(bytes[at])) << 24 | uint32_t(uint8_t(bytes[at + 1])) << 16 |
               uint32_t(uint8_t(bytes[at + 2])) << 8 | uint32_t(uint8_t(bytes[at + 3]));
    };
    for (size_t offset = 8; offset + 12 <= bytes.size();) {
        const uint32_t length = bigEndian(offset);
        if (length > bytes.size() - offset - 12) break;
        const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(bytes.data() + offset + 4), 4 + length));
        for (int i = 0; i < 4; ++i) bytes[offset + 8 + length + i] = char(crc >> (24 - 8 * i));
        offset += 12 + length;
    }
    return bytes;
}

TEST(ReadImage, RandomlyCorruptedFilesThrowOrReadConsistently) {
    test::ScratchDirectory dir;
    Image image{40, 30, std::vector<float>(40 * 30 * 3)};
    for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = float(i % 97) / 97;
    writeExr(dir / "good.exr", image);
    writePng(dir / "good.png", image);
    std::mt19937 rng(1);
    for (const char* extension : {".exr", ".png"}) {
        std::string good = test::readBytes(dir / ("good" + std::string(extension)));
        std::filesystem::path bad = dir / ("bad" + std::string(extension));
        int thrown = 0, read = 0;
        for (int trial = 0; trial < 300; ++trial) {
            std::string bytes = good;
            for (int k = 0; k <= trial % 8; ++k) bytes[rng() % bytes.size()] = char(rng());
            if (trial % 5 == 0) bytes.resize(rng() % bytes.size());
            if (std::string(extension) == ".png" && trial % 2 == 1) bytes = withMatchingPngCrcs(bytes);
            test::writeBytes(bad, bytes);
            Image decoded;
            try {
                decoded = readImage(bad);
            } catch (const Error&) {
                ++thrown;
                continue;
            }
            ++read;
            SCOPED_TRACE(std::string(extension) + " trial " + std::to_string(trial));
            ASSERT_GT(decoded.width, 0);
            ASSERT_GT(decoded.height, 0);
            ASSERT_LE(size_t(decoded.width) * size_t(decoded.height), kMaxImagePixels);
            ASSERT_EQ(decoded.rgb.size(), size_t(decoded.width) * size_t(decoded.height) * 3);
            if (std::string(extension) == ".png") {
                for (float v : decoded.rgb) ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << v;
            }
        }
        // Both outcomes occur, so both branches above are exercised.
        EXPECT_GT(thrown, 0) << extension;
        EXPECT_GT(read, 0) << extension;
    }
}

TEST(ReadImage, UnknownExtensionOrNotAFile) {
    test::ScratchDirectory dir;
    writeExr(dir / "image.exr", smallImage());
    std::filesystem::copy_file(dir / "image.exr", dir / "image.tiff");
    expectErrorNaming(dir / "image.tiff", [&] { readImage(dir / "image.tiff"); });
    std::filesystem::create_directory(dir / "folder.exr");
    expectErrorNaming(dir / "folder.exr", [&] { readImage(dir / "folder.exr"); });
}

TEST(ReadImage, ExtensionIsCaseInsensitive) {
    test::ScratchDirectory dir;
    writePng(dir / "UPPER.PNG", smallImage());
    EXPECT_EQ(readImage(dir / "UPPER.PNG").width, 2);
}

}  // namespace
}  // namespace vkdr
