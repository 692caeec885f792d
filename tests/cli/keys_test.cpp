// The keys as a user meets them: `softbody keys`, the documents' key tables (the same text),
// and `--set` on a named spring and on every soft body.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "child_process.h"

namespace {

using softbody_test::describe;
using softbody_test::read_text;
using softbody_test::Result;
using softbody_test::run;

// The text between two marker lines of a file ("" when they are not there).
std::string between(const std::string& text, const std::string& begin, const std::string& end) {
    const auto a = text.find(begin + "\n");
    if (a == std::string::npos) return "";
    const auto from = a + begin.size() + 1;
    const auto b = text.find("\n" + end, from);
    if (b == std::string::npos) return "";
    return text.substr(from, b + 1 - from);
}

TEST(Keys, TheDocumentsTablesAreSoftbodyKeysMarkdown) {
    const Result r = run({"keys", "--markdown"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const std::string doc = read_text(std::string(SOFTBODY_SOURCE) + "/app/README.md");
    const std::string tables = between(doc, "<!-- keys: softbody keys --markdown -->", "<!-- end keys -->");
    ASSERT_FALSE(tables.empty()) << "app/README.md lacks the key tables between their markers";
    EXPECT_EQ(tables, r.out) << "app/README.md's key tables differ from `softbody keys --markdown`: paste its output between the markers";
}

TEST(Keys, ListsEveryOwnerAsTextAndJson) {
    const Result text = run({"keys"});
    ASSERT_EQ(text.exit_code, 0) << describe(text);
    for (const char* owner : {"Keys of a world", "Keys of a soft body", "Keys of a rigid body", "Keys of a spring"}) {
        EXPECT_NE(text.out.find(owner), std::string::npos) << owner;
    }
    const Result js = run({"keys", "--json"});
    ASSERT_EQ(js.exit_code, 0) << describe(js);
    const auto keys = nlohmann::json::parse(js.out);
    bool spring_stiffness = false;
    for (const auto& k : keys) spring_stiffness |= k["owner"] == "spring" && k["name"] == "stiffness" && k["unit"] == "N/m";
    EXPECT_TRUE(spring_stiffness);
    const Result both = run({"keys", "--json", "--markdown"});
    EXPECT_EQ(both.exit_code, 2) << describe(both);
}

// The spring lesson's k, by the spring's name: four times k halves the period (T = 2 pi
// sqrt(m / k): 0.99 s at 40 N/m, 0.497 s at 160 N/m), predicted and measured.
TEST(Keys, ASpringsStiffnessIsSetByItsName) {
    const std::string scene = std::string(SOFTBODY_ASSETS) + "/scenes/spring.json";
    const Result r = run({"simulate", "--scene", scene, "--seconds", "3", "--set", "spring.stiffness=160"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const Result before = run({"simulate", "--scene", scene, "--seconds", "3"});
    ASSERT_EQ(before.exit_code, 0) << describe(before);
    EXPECT_NE(nlohmann::json::parse(r.out)["state_hash"], nlohmann::json::parse(before.out)["state_hash"]);
    const Result bad = run({"simulate", "--scene", scene, "--seconds", "1", "--set", "stiffness=160"});
    EXPECT_EQ(bad.exit_code, 2) << describe(bad);
    EXPECT_NE(bad.err.find("spring.stiffness"), std::string::npos) << bad.err;  // the key it could have meant
    const Result negative = run({"simulate", "--scene", scene, "--seconds", "1", "--set", "spring.stiffness=-1"});
    EXPECT_EQ(negative.exit_code, 2) << describe(negative);
    EXPECT_NE(negative.err.find("spring 'spring'"), std::string::npos) << negative.err;
}

}  // namespace
