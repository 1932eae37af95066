// sweep.csv shards as merged by `gaitopt sweep-merge` (io/sweep_file.hpp): the input is split at
// its first NUL byte into two shards; only std::invalid_argument may come out.
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "gaitopt/io/sweep_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t cut = input.find('\0');
  std::vector<std::string> texts{input.substr(0, cut)};
  if (cut != std::string::npos) texts.push_back(input.substr(cut + 1));
  try {
    gaitopt::mergeSweepCsvs(texts, {"shard0/sweep.csv", "shard1/sweep.csv"});
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
