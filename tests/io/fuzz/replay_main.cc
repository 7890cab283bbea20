// A stand-in for libFuzzer's driver when the fuzz targets are built without clang: feeds
// every seed file given on the command line (files or directories) to
// LLVMFuzzerTestOneInput, followed by hostile variants of each -- every prefix, and
// deterministic byte overwrites -- so g++ builds compile and exercise the same entry points.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/io/fuzz/fuzz_check.h"

namespace {

// Seeds are tiny; bigger files get a sampled subset of variants to keep the run short.
constexpr size_t kMaxVariantPositions = 2048;
constexpr uint8_t kOverwrites[] = {0x00, 0xff, 0x7f, 0x80, '9', '-', ' ', '\n'};

void Run(const std::string& bytes, size_t* runs) {
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  ++*runs;
}

void RunVariants(const std::string& seed, size_t* runs) {
  Run(seed, runs);
  const size_t step = seed.size() / kMaxVariantPositions + 1;
  for (size_t size = 0; size < seed.size(); size += step) Run(seed.substr(0, size), runs);
  for (size_t position = 0; position < seed.size(); position += step) {
    std::string variant = seed;
    for (uint8_t value : kOverwrites) {
      variant[position] = static_cast<char>(value);
      Run(variant, runs);
    }
  }
}

bool ReadSeed(const std::filesystem::path& path, std::string* bytes) {
  std::ifstream in(path, std::ios::binary);
  bytes->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return !in.bad();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> seeds;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path arg = argv[i];
    if (std::filesystem::is_directory(arg)) {
      for (const auto& entry : std::filesystem::directory_iterator(arg)) {
        if (entry.is_regular_file()) seeds.push_back(entry.path());
      }
    } else {
      seeds.push_back(arg);
    }
  }
  if (seeds.empty()) {
    std::fprintf(stderr, "usage: %s SEED_FILE_OR_DIR...\n", argv[0]);
    return 2;
  }
  size_t runs = 0;
  for (const std::string& generic :
       {std::string(), std::string(1, '\0'), std::string(4096, '\xff'), std::string("\n\n\n")}) {
    Run(generic, &runs);
  }
  for (const std::filesystem::path& path : seeds) {
    std::string seed;
    if (!ReadSeed(path, &seed)) {
      std::fprintf(stderr, "cannot read seed %s\n", path.c_str());
      return 2;
    }
    RunVariants(seed, &runs);
  }
  std::printf("replayed %zu inputs from %zu seeds\n", runs, seeds.size());
  return 0;
}
