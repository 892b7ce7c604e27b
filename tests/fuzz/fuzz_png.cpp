// libFuzzer target for the depth-image reader's PNG check (src/io/png_check.h) with OpenCV's
// decoder behind it, as read_depth_image and read_mask_image use them. For any bytes that start
// like a PNG, check_png either throws InvalidInput with one line naming the file, or OpenCV decodes
// the image at the size its header declares. Anything else is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include <opencv2/imgcodecs.hpp>

#include "io/png_check.h"
#include "rangefill/core/errors.h"

namespace {

constexpr const char* kName = "fuzz-input.png";

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_png: %s\n", what.c_str());
  std::abort();
}

std::uint32_t big_endian(const std::uint8_t* bytes) {
  return std::uint32_t{bytes[0]} << 24 | std::uint32_t{bytes[1]} << 16 |
         std::uint32_t{bytes[2]} << 8 | bytes[3];
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  if (!rangefill::detail::is_png(bytes)) return 0;
  try {
    rangefill::detail::check_png(bytes, kName);
  } catch (const rangefill::InvalidInput& error) {
    const std::string_view message = error.what();
    if (message.find('\n') != std::string_view::npos) finding("message of several lines");
    if (message.rfind(std::string(kName) + ": corrupt PNG: ", 0) != 0) {
      finding("message does not name the file: " + std::string(message));
    }
    return 0;
  }
  // Accepted: IHDR is the first chunk, so its width and height are at bytes 16–23.
  const cv::Mat image =
      cv::imdecode(cv::Mat(1, static_cast<int>(size), CV_8U, const_cast<std::uint8_t*>(data)),
                   cv::IMREAD_UNCHANGED);
  if (image.empty()) finding("accepted by check_png, not decoded by OpenCV");
  if (static_cast<std::uint32_t>(image.cols) != big_endian(data + 16) ||
      static_cast<std::uint32_t>(image.rows) != big_endian(data + 20)) {
    finding("decoded at another size than the header declares");
  }
  return 0;
}
