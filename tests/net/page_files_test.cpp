// Which file of the page's folder a URL names: index.html for "/", queries ignored, and nothing
// outside the folder however the path is spelled.

#include "net/page_files.hpp"

#include <unistd.h>

#include <fstream>

#include <gtest/gtest.h>

namespace felt::net {
namespace {

class PageFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ =
        std::filesystem::temp_directory_path() / ("felt-page-files-" + std::to_string(::getpid()));
    std::filesystem::create_directories(root_ / "page" / "assets");
    std::ofstream(root_ / "page" / "index.html") << "page";
    std::ofstream(root_ / "page" / "assets" / "app.js") << "js";
    std::ofstream(root_ / "page" / "assets" / "app.js.map") << "{}";
    std::ofstream(root_ / "outside.txt") << "secret";
    std::filesystem::create_symlink(root_ / "outside.txt", root_ / "page" / "link.txt");
  }
  void TearDown() override { std::filesystem::remove_all(root_); }
  std::optional<PageFile> file(std::string_view target) {
    return page_file(root_ / "page", target);
  }
  std::filesystem::path root_;
};

TEST_F(PageFilesTest, NamesThePagesFilesWithTheirTypes) {
  ASSERT_TRUE(file("/"));
  EXPECT_EQ(file("/")->path.filename(), "index.html");
  EXPECT_EQ(file("/")->content_type, "text/html; charset=utf-8");
  ASSERT_TRUE(file("/assets/app.js?scene=default#top"));
  EXPECT_EQ(file("/assets/app.js")->content_type, "text/javascript; charset=utf-8");
  EXPECT_EQ(file("/assets/app.js.map")->content_type, "application/json");
  EXPECT_EQ(file("/?join=4294967296")->path.filename(), "index.html");
}

TEST_F(PageFilesTest, NothingOutsideTheFolderOrNotAFile) {
  for (std::string_view target :
       {"/../outside.txt", "/assets/../../outside.txt", "/assets/../index.html", "/./index.html",
        "/%2e%2e/outside.txt", "/link.txt", "/assets", "/assets/", "//index.html", "index.html", "",
        "/missing.js", "/assets/app.js/..", "/..", "/\\..\\outside.txt"}) {
    EXPECT_FALSE(file(target)) << target;
  }
}

}  // namespace
}  // namespace felt::net
