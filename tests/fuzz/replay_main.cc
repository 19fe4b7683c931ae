// Replays fuzz corpora without libFuzzer: `fuzz_replay NAME PATH...` sends every regular file of
// the given directories (or the given files), in name order, once through the harness NAME, as
// `fuzz_NAME -runs=0 corpus/` would. Built with the project's own compiler, so that CI replays the
// corpora under ASan+UBSan without a clang toolchain. Fails on an unknown harness or an empty corpus.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "harness.h"

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const vstcal::fuzz::Body body = argc > 1 ? vstcal::fuzz::Find(argv[1]) : nullptr;
  if (body == nullptr) {
    std::string names;
    for (const std::string& n : vstcal::fuzz::Names()) names += " " + n;
    std::fprintf(stderr, "fuzz_replay: usage: fuzz_replay NAME PATH...; NAME is one of:%s\n", names.c_str());
    return 2;
  }
  std::vector<fs::path> inputs;
  for (int i = 2; i < argc; ++i) {
    if (fs::is_directory(argv[i])) {
      for (const auto& entry : fs::directory_iterator(argv[i])) {
        if (entry.is_regular_file()) inputs.push_back(entry.path());
      }
    } else {
      inputs.emplace_back(argv[i]);
    }
  }
  std::sort(inputs.begin(), inputs.end());
  for (const fs::path& p : inputs) {
    std::ifstream in(p, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    vstcal::fuzz::RunOne(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), body);
  }
  std::printf("replayed %zu inputs through %s\n", inputs.size(), argv[1]);
  return inputs.empty() ? 1 : 0;
}
