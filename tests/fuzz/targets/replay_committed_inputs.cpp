// A fuzz target's committed inputs, replayed as a test of the suite: its seed corpus
// (tests/fuzz/corpus/TARGET) and every input that once crashed it (tests/fuzz/crashes/TARGET),
// each once, through the target's own checks. A failed check aborts the test binary; the last
// input it names is the one.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz_target.hpp"

namespace {

namespace fs = std::filesystem;

/// The files of `directory`, sorted by name; none when it does not exist.
std::vector<fs::path> inputs_in(const fs::path& directory) {
  std::vector<fs::path> files;
  if (!fs::is_directory(directory)) return files;
  for (const auto& entry : fs::directory_iterator(directory)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(FuzzTarget, ReplaysItsCorpusAndEveryCrashItOnceHad) {
  std::size_t replayed = 0;
  for (const fs::path& directory : {fs::path(FELT_FUZZ_CORPUS), fs::path(FELT_FUZZ_CRASHES)}) {
    for (const fs::path& file : inputs_in(directory)) {
      std::cout << "replaying " << file.string() << std::endl;
      std::ifstream in(file, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++replayed;
    }
  }
  EXPECT_GT(replayed, 0u) << "no inputs in " << FELT_FUZZ_CORPUS;
}

}  // namespace
