// The back-ends on the image of the FoE and MLS speed targets: 256×256 pixels of a smooth depth
// surface (a tilted quadric with a few bumps, normalised to [0, 1] like a range image, eq. 7–8)
// with 15 % of its pixels masked in blobs. cv::inpaint NS (radius 5, CV_32F) runs in the same
// process as the baseline. Report medians: --benchmark_repetitions=9
// --benchmark_report_aggregates_only=true.
#include <cmath>
#include <string>

#include <benchmark/benchmark.h>
#include <opencv2/photo.hpp>

#include "rangefill/eval/patches.h"
#include "rangefill/inpaint/inpainters.h"

namespace {

constexpr int kSize = 256;
constexpr double kMasked = 0.15;

cv::Mat test_depth() {
  cv::Mat depth(kSize, kSize, CV_32F);
  for (int row = 0; row < kSize; ++row) {
    for (int col = 0; col < kSize; ++col) {
      const double u = col / double(kSize) - 0.5, v = row / double(kSize) - 0.5;
      depth.at<float>(row, col) =
          static_cast<float>(0.5 + 0.3 * u - 0.2 * v + 0.4 * (u * u - 0.5 * u * v + 0.7 * v * v) +
                             0.03 * std::sin(12 * u) * std::cos(9 * v));
    }
  }
  return depth;
}

const cv::Mat& depth() {
  static const cv::Mat image = test_depth();
  return image;
}

const cv::Mat& mask() {
  static const cv::Mat blobs =
      rangefill::blob_mask(cv::Size(kSize, kSize), kMasked, kMasked, 8, /*seed=*/7);
  return blobs;
}

void inpaint_with(benchmark::State& state, const std::string& name) {
  const std::unique_ptr<rangefill::Inpainter> inpainter = rangefill::make_inpainter(name);
  cv::Mat out;
  for (auto _ : state) {
    inpainter->inpaint(depth(), mask(), out);
    benchmark::DoNotOptimize(out.data);
  }
  state.counters["masked"] = cv::countNonZero(mask());
}

void cv_inpaint_ns(benchmark::State& state) {
  cv::Mat out;
  for (auto _ : state) {
    cv::inpaint(depth(), mask(), out, 5, cv::INPAINT_NS);
    benchmark::DoNotOptimize(out.data);
  }
  state.counters["masked"] = cv::countNonZero(mask());
}

}  // namespace

BENCHMARK(cv_inpaint_ns)->Name("cv::inpaint NS")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(inpaint_with, ns, std::string("ns"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(inpaint_with, telea, std::string("telea"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(inpaint_with, harmonic, std::string("harmonic"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(inpaint_with, mls, std::string("mls"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(inpaint_with, foe, std::string("foe"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(inpaint_with, foe_roth_black, std::string("foe:roth-black"))
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
