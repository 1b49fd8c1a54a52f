#include <gtest/gtest.h>

#include <regex>

#include "scene/project_io.h"
#include "scene_test_util.h"

using namespace dp;
using json = nlohmann::json;

namespace {

/// The ```json blocks of docs/project-format.md.
std::vector<std::string> json_blocks() {
    std::string doc = dp::test::read_text(std::string(DP_SOURCE_DIR) + "/docs/project-format.md");
    std::vector<std::string> blocks;
    std::regex block("```json\\n([\\s\\S]*?)```");
    for (std::sregex_iterator it(doc.begin(), doc.end(), block), end; it != end; ++it)
        blocks.push_back((*it)[1].str());
    return blocks;
}

class ProjectDocs : public dp::test::TempDirTest {};

}  // namespace

TEST_F(ProjectDocs, EveryExampleInTheFormatDocumentIsValid) {
    auto blocks = json_blocks();
    ASSERT_GE(blocks.size(), 4u);
    int complete = 0;
    json base = json::parse(dp::test::kRichProject);
    for (const std::string& text : blocks) {
        SCOPED_TRACE(text);
        json doc;
        if (text.rfind("{", 0) == 0) {
            doc = json::parse(text);
            ++complete;
        } else {
            // A fragment such as "camera": {...}: put it into an otherwise valid project.
            json fragment = json::parse("{" + text + "}");
            doc = base;
            for (auto& [key, value] : fragment.items()) {
                if (key == "transform") doc["objects"][0]["transform"] = value;
                else doc[key] = value;
            }
        }
        EXPECT_NO_THROW(load_project(write("example.json", doc.dump())));
    }
    EXPECT_EQ(complete, 1);
}
