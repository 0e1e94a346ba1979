// truth.csv's cost per frame (evaluation/frame_truth.hpp, io/run/truth_csv.hpp): the ground truth
// of the benchmark scenario's middle frame — the objects within range, their nearest points and
// clips against the scanned field — with its returns, and the rows formatted; one thread. Items
// are rows. Compare with bench_receiver's frame and `owsim bench`'s "words + truth" figure.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "bench/bench_fixture.hpp"
#include "evaluation/frame_truth.hpp"
#include "io/run/flight_summary.hpp"
#include "io/run/truth_csv.hpp"

namespace owsim {
namespace {

struct TruthFixture {
  TruthFixture()
      : model(fixture.scene, fixture.scenario.scan, fixture.scenario.mount, fixture.trajectory),
        rows(fixture.scene) {
    FlightSummary::tally(named_object_count(fixture.scene), fixture.traced.pulses,
                         fixture.traced.returns, tally);
  }
  const bench::BenchFixture& fixture = bench::bench_fixture();
  FrameTruthModel model;
  TruthCsvRows rows;
  FrameTally tally;
};

const TruthFixture& truth_fixture() {
  static const TruthFixture fixture;
  return fixture;
}

// Empties the caches between frames, untimed, by writing 64 MB (arg 1) or 4 MB (arg 2); arg 0
// leaves them warm.
class CacheEmptier {
 public:
  explicit CacheEmptier(std::int64_t arg)
      : other_(arg == 0 ? 0 : std::size_t{arg == 1 ? 64U : 4U} << 20) {}
  void operator()(benchmark::State& state) {
    if (other_.empty()) return;
    state.PauseTiming();
    for (std::size_t i = 0; i < other_.size(); i += 64) ++other_[i];
    benchmark::ClobberMemory();
    state.ResumeTiming();
  }

 private:
  std::vector<char> other_;
};

// Arg 0: the same frame again and again, its data in the cache; arg 1: with 64 MB written
// between frames (untimed), as in a flight, where the tracer's data fills the cache between one
// frame's ground truth and the next: then the bytes the ground truth reads are what it costs
// (`owsim run` on the corridor spends about this much a frame on it); arg 2: with 4 MB written,
// the L2 cache emptied but not the L3.
void BM_FrameTruth(benchmark::State& state) {
  const TruthFixture& f = truth_fixture();
  CacheEmptier empty_caches(state.range(0));
  FrameTruth truth;
  for (auto _ : state) {
    empty_caches(state);
    f.model.frame_truth(f.fixture.frame, f.fixture.traced.sweep, f.tally.object_hits, truth);
    benchmark::DoNotOptimize(truth.rows.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(truth.rows.size()));
  state.counters["rows"] = static_cast<double>(truth.rows.size());
}
BENCHMARK(BM_FrameTruth)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

// A frame's ground truth and its rows, as owsim run makes them (the cost `owsim bench`'s
// "words + truth" line adds); the arguments as BM_FrameTruth's.
void BM_FrameTruthAndRows(benchmark::State& state) {
  const TruthFixture& f = truth_fixture();
  CacheEmptier empty_caches(state.range(0));
  FrameTruth truth;
  std::string text;
  for (auto _ : state) {
    empty_caches(state);
    text.clear();
    f.model.frame_truth(f.fixture.frame, f.fixture.traced.sweep, f.tally.object_hits, truth);
    f.rows.encode(truth, text);
    benchmark::DoNotOptimize(text.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(truth.rows.size()));
}
BENCHMARK(BM_FrameTruthAndRows)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

void BM_TruthRows(benchmark::State& state) {
  const TruthFixture& f = truth_fixture();
  FrameTruth truth;
  f.model.frame_truth(f.fixture.frame, f.fixture.traced.sweep, f.tally.object_hits, truth);
  std::string text;
  for (auto _ : state) {
    text.clear();
    f.rows.encode(truth, text);
    benchmark::DoNotOptimize(text.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(truth.rows.size()));
}
BENCHMARK(BM_TruthRows)->Unit(benchmark::kMicrosecond);

// The per-pulse tally truth.csv's returns come from: the returns on objects alone, from the
// receiver's object_returns bits as owsim run has them (arg 0) or read from the returns (arg 1),
// or with summary.json's counts (arg 2).
void BM_TallyFrame(benchmark::State& state) {
  const TruthFixture& f = truth_fixture();
  const TallyScope scope = state.range(0) < 2 ? TallyScope::object_hits : TallyScope::summary;
  const std::span<const std::uint8_t> bits =
      state.range(0) == 0 ? std::span<const std::uint8_t>(f.fixture.traced.object_returns)
                          : std::span<const std::uint8_t>();
  FrameTally tally;
  for (auto _ : state) {
    FlightSummary::tally(named_object_count(f.fixture.scene), f.fixture.traced.pulses,
                         f.fixture.traced.returns, tally, scope, bits);
    benchmark::DoNotOptimize(tally.object_hits.data());
  }
  state.SetItemsProcessed(state.iterations() * f.fixture.pulses_per_frame());
}
BENCHMARK(BM_TallyFrame)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace owsim
