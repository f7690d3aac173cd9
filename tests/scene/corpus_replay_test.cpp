// Replays the scene loader's fuzz seeds (tests/fuzz/corpus/scene), every input that once
// crashed it (tests/fuzz/regressions/scene) and the malformed-input corpus: each file
// loads or is refused with vkdr::Error, never anything else. tools/sanitize.sh runs it
// under AddressSanitizer and UndefinedBehaviorSanitizer.
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

TEST(SceneCorpusReplay, EveryFileLoadsOrIsRefusedWithAnError) {
    const fs::path tests = VKDR_TESTS_DIR;
    size_t replayed = 0;
    for (const fs::path& directory :
         {tests / "fuzz/corpus/scene", tests / "fuzz/regressions/scene", tests / "cli/data/malformed"}) {
        if (!fs::exists(directory)) continue;  // no regressions yet
        for (const auto& entry : fs::directory_iterator(directory)) {
            fs::path extension = entry.path().extension();
            if (extension != ".gltf" && extension != ".glb") continue;
            try {
                loadScene(entry.path());
            } catch (const Error&) {
            }
            ++replayed;
        }
    }
    EXPECT_GT(replayed, 40u);
}

}  // namespace
}  // namespace vkdr::test
