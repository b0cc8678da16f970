// SPDX-License-Identifier: GPL-3.0-or-later
// Stage benchmark: bench_stages MODEL [--up y|z] [Google Benchmark flags]
// Times load, placement + BVH build, raster, segmentation, slicing and the exact plan (vectorization,
// folds, validity) of the default sheet
// (210 x 297 mm at 4 px/mm, W = 3 mm) for one model, then prints the process's peak resident memory.
#include <sys/resource.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "origamic/mesh_io.hpp"
#include "origamic/placement.hpp"
#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/segment.hpp"
#include "origamic/slice.hpp"

namespace {

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: bench_stages MODEL [--up y|z] [benchmark flags]\n");
    return 2;
  }
  const std::string model = argv[1];
  origamic::PlacementOptions placement_options;
  std::vector<char*> rest = {argv[0]};
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--up") == 0 && i + 1 < argc) {
      placement_options.up = std::strcmp(argv[++i], "z") == 0 ? origamic::UpAxis::Z : origamic::UpAxis::Y;
    } else {
      rest.push_back(argv[i]);
    }
  }
  int rest_argc = static_cast<int>(rest.size());
  benchmark::Initialize(&rest_argc, rest.data());

  const origamic::Sheet sheet;
  const origamic::LoadedMesh loaded = origamic::load_mesh(model);
  const origamic::Placement placement = origamic::place(loaded.mesh, sheet, placement_options);
  const origamic::RayScene scene(origamic::apply(placement, loaded.mesh));

  benchmark::RegisterBenchmark("load", [&](benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(origamic::load_mesh(model));
    state.counters["triangles"] = static_cast<double>(loaded.mesh.triangles.size());
  })->Unit(benchmark::kMillisecond)->Iterations(3);
  benchmark::RegisterBenchmark("place+bvh", [&](benchmark::State& state) {
    for (auto _ : state) {
      const origamic::Placement p = origamic::place(loaded.mesh, sheet, placement_options);
      const origamic::RayScene s(origamic::apply(p, loaded.mesh));
      benchmark::DoNotOptimize(&s);
    }
  })->Unit(benchmark::kMillisecond)->Iterations(5);
  benchmark::RegisterBenchmark("raster", [&](benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(origamic::raster(scene, sheet, origamic::RasterOptions{}));
    state.counters["Mpx"] = static_cast<double>(origamic::PixelGrid::covering(sheet, 4).cols) *
                            origamic::PixelGrid::covering(sheet, 4).rows / 1e6;
  })->Unit(benchmark::kMillisecond)->MinTime(2.0);

  const origamic::RasterMaps maps = origamic::raster(scene, sheet, origamic::RasterOptions{});
  const origamic::Segmentation segmentation = origamic::segment(maps, origamic::SegmentOptions{});
  benchmark::RegisterBenchmark("segment", [&](benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(origamic::segment(maps, origamic::SegmentOptions{}));
    state.counters["segments"] = segmentation.count;
  })->Unit(benchmark::kMillisecond)->MinTime(1.0);
  benchmark::RegisterBenchmark("slice", [&](benchmark::State& state) {
    std::size_t faces = 0;
    for (auto _ : state) {
      const origamic::RasterPlan raster_plan = origamic::slice(maps, segmentation, origamic::SliceOptions{});
      faces = raster_plan.faces.size();
    }
    state.counters["faces"] = static_cast<double>(faces);
  })->Unit(benchmark::kMillisecond)->MinTime(1.0);

  const origamic::RasterPlan raster_plan = origamic::slice(maps, segmentation, origamic::SliceOptions{});
  benchmark::RegisterBenchmark("plan", [&](benchmark::State& state) {
    origamic::Plan plan;
    for (auto _ : state) plan = origamic::build_plan(maps, raster_plan, sheet, origamic::PlanOptions{});
    state.counters["arr_faces"] = plan.arrangement_faces;
    state.counters["simplified"] = plan.simplified;
  })->Unit(benchmark::kMillisecond)->MinTime(1.0);

  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::printf("peak_rss_MB %.1f  (%s)\n", peak_rss_mb(), model.c_str());
  return 0;
}
