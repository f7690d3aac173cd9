// Replays the image reader's fuzz seeds (tests/fuzz/corpus/image), every input that once
// crashed it (tests/fuzz/regressions/image) and the malformed targets: each file is read
// or refused with vkdr::Error, never anything else. tools/sanitize.sh runs it under
// AddressSanitizer and UndefinedBehaviorSanitizer.
#include <filesystem>

#include <gtest/gtest.h>

#include "core/error.h"
#include "image/image.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

TEST(ImageCorpusReplay, EveryFileIsReadOrRefusedWithAnError) {
    const fs::path tests = VKDR_TESTS_DIR;
    size_t replayed = 0;
    for (const fs::path& directory :
         {tests / "fuzz/corpus/image", tests / "fuzz/regressions/image", tests / "cli/data/malformed"}) {
        if (!fs::exists(directory)) continue;  // no regressions yet
        for (const auto& entry : fs::directory_iterator(directory)) {
            fs::path extension = entry.path().extension();
            if (extension != ".exr" && extension != ".png" && extension != ".jpg") continue;
            try {
                readImage(entry.path());
            } catch (const Error&) {
            }
            ++replayed;
        }
    }
    EXPECT_GT(replayed, 10u);
}

}  // namespace
}  // namespace vkdr::test
