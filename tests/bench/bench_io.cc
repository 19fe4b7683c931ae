// The strict JSON reader (duplicate keys, nesting and value limits, positions for messages:
// docs/reliability.md#strict-json) beside nlohmann-json's own DOM parser, the peer, on the same
// text in the same run; and the whole correspondences reader. Sizes from 600 to 600,000 points
// show how the cost grows.
#include <benchmark/benchmark.h>

#include <map>
#include <nlohmann/json.hpp>

#include "support/scenes.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace {

// A volume of n points as a correspondences@1 text (one view per 100 points).
const std::string& VolumeText(size_t n) {
  static std::map<size_t, std::string> texts;
  std::string& text = texts[n];
  if (text.empty()) {
    const auto scene = vstcal::testing::RandomVolumeScene(n, 0.2, 42);
    vstcal::Correspondences c;
    c.image_size = scene.camera.image_size;
    for (size_t i = 0; i < n; ++i) {
      if (i % 100 == 0) c.views.push_back({"view-" + std::to_string(i / 100), "", std::nullopt, {}, std::nullopt});
      c.views.back().observations.push_back(scene.observations[i]);
    }
    text = vstcal::DumpJson(vstcal::CorrespondencesToJson(c, {"bench_io", {}, std::nullopt}));
  }
  return text;
}

void BM_StrictJsonParse(benchmark::State& state) {
  const std::string& text = VolumeText(static_cast<size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(vstcal::JsonDocument::Parse(text, "bench.json"));
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(text.size()));
}

void BM_NlohmannParse(benchmark::State& state) {
  const std::string& text = VolumeText(static_cast<size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(nlohmann::json::parse(text));
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(text.size()));
}

void BM_ReadCorrespondences(benchmark::State& state) {
  const std::string& text = VolumeText(static_cast<size_t>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(vstcal::CorrespondencesFromJson(vstcal::JsonDocument::Parse(text, "bench.json")));
  }
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(text.size()));
}

BENCHMARK(BM_StrictJsonParse)->Arg(600)->Arg(60000)->Arg(600000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NlohmannParse)->Arg(600)->Arg(60000)->Arg(600000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadCorrespondences)->Arg(600)->Arg(60000)->Arg(600000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
