// Catenary solve and sampling (geometry/catenary.hpp, geometry/span.hpp): the scene set-up cost of
// one span — solving for the parameter a, sampling the polyline to 1 mm chord error, and building
// a 7-conductor (sept) span of the corridor's size.
#include <benchmark/benchmark.h>

#include "geometry/catenary.hpp"
#include "geometry/conductor_layout.hpp"
#include "geometry/span.hpp"
#include "geometry/terrain.hpp"

namespace owsim {
namespace {

// The corridor's transmission-line span: 400 m, supports 50 m and 55 m, lowest point 37 m.
constexpr CatenaryProfile kUnequal{400.0, 50.0, 55.0, 37.0};
constexpr CatenaryProfile kEqual{400.0, 50.0, 50.0, 36.0};

void BM_CatenarySolveEqualSupports(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(Catenary::solve(kEqual));
}
BENCHMARK(BM_CatenarySolveEqualSupports);

void BM_CatenarySolveUnequalSupports(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(Catenary::solve(kUnequal));
}
BENCHMARK(BM_CatenarySolveUnequalSupports);

// Sampling at 1 mm chord error (DESIGN.md "Wires"); items are the points.
void BM_CatenarySample1mm(benchmark::State& state) {
  const Catenary catenary = Catenary::solve(kUnequal);
  std::size_t points = 0;
  for (auto _ : state) {
    const std::vector<double> x = catenary.sample_x(0.001);
    points += x.size();
    benchmark::DoNotOptimize(x.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(points));
}
BENCHMARK(BM_CatenarySample1mm);

// Heights along the sampled polyline; items are the points.
void BM_CatenaryHeightAt(benchmark::State& state) {
  const Catenary catenary = Catenary::solve(kUnequal);
  const std::vector<double> x = catenary.sample_x(0.001);
  for (auto _ : state) {
    for (const double xi : x) benchmark::DoNotOptimize(catenary.height_at(xi));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(x.size()));
}
BENCHMARK(BM_CatenaryHeightAt);

// A whole span: every conductor of the sept layout solved, sampled and placed; items are spans.
void BM_BuildSeptSpan(benchmark::State& state) {
  SpanSpec spec;
  spec.id = "hv-3";
  spec.from_en = {-200.0, 0.0};
  spec.to_en = {200.0, 0.0};
  spec.support_height_1_m = 50.0;
  spec.support_height_2_m = 55.0;
  spec.lowest_point_m = 37.0;
  spec.offsets = conductor_offsets(LayoutKind::sept);
  spec.conductor_diameter_m = 0.021;
  spec.support_poles = false;
  const Terrain terrain;
  for (auto _ : state) benchmark::DoNotOptimize(build_span(spec, terrain));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_BuildSeptSpan)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace owsim
