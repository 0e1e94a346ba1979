// File writing (io/recording/word_file.hpp): MilOWS frames (20,352 words, 163 kB each) streamed
// through the word-file writer into a crash-safe file in the system's temporary folder and
// committed — with and without the fsync at commit — and read back through the streaming reader.
// Each iteration writes or reads 32 frames (5.2 MB); bytes are the words' bytes.
#include <benchmark/benchmark.h>
#include <stdlib.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "io/recording/word_file.hpp"

namespace owsim {
namespace {

constexpr int kFramesPerIteration = 32;
constexpr std::size_t kWordsPerFrame = 128 * 159;

// A fresh folder under the system's temporary directory, removed with its contents at the end.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "owsim_bench_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp " + pattern);
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

std::vector<std::uint64_t> frame_words() {
  std::vector<std::uint64_t> words(kWordsPerFrame);
  for (std::size_t k = 0; k < words.size(); ++k) words[k] = 0x9E3779B97F4A7C15ull * (k + 1);
  return words;
}

void write_file(const std::filesystem::path& path, const std::vector<std::uint64_t>& words,
                bool sync) {
  MilowsWordWriter writer(path, AtomicOutputOptions{sync});
  for (int frame = 0; frame < kFramesPerIteration; ++frame) {
    writer.write(std::span<const std::uint64_t>(words));
  }
  writer.commit();
}

// Arg: 1 = fsync at commit (what `owsim run` does), 0 = none.
void BM_WriteMilowsFrames(benchmark::State& state) {
  const ScratchFolder folder;
  const std::vector<std::uint64_t> words = frame_words();
  const std::filesystem::path path = folder.path() / "flight.d64";
  for (auto _ : state) {
    write_file(path, words, state.range(0) != 0);
    state.PauseTiming();
    std::filesystem::remove(path);
    state.ResumeTiming();
  }
  state.SetBytesProcessed(state.iterations() * kFramesPerIteration *
                          static_cast<std::int64_t>(kWordsPerFrame * 8));
  state.SetLabel(state.range(0) != 0 ? "fsync" : "no fsync");
}
BENCHMARK(BM_WriteMilowsFrames)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReadMilowsFrames(benchmark::State& state) {
  const ScratchFolder folder;
  const std::vector<std::uint64_t> words = frame_words();
  const std::filesystem::path path = folder.path() / "flight.d64";
  write_file(path, words, false);
  std::vector<std::uint64_t> frame(kWordsPerFrame);
  for (auto _ : state) {
    MilowsWordReader reader(path);
    while (reader.read(frame) > 0) benchmark::DoNotOptimize(frame.data());
  }
  state.SetBytesProcessed(state.iterations() * kFramesPerIteration *
                          static_cast<std::int64_t>(kWordsPerFrame * 8));
}
BENCHMARK(BM_ReadMilowsFrames)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace owsim
