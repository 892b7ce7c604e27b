// libFuzzer target for the image decoders (src/io/image_codecs.h: PNG behind the PNG check, JPEG,
// TIFF, EXR), as the depth, mask and colour readers use them. For any bytes, decode_color_image
// either returns an image or throws InvalidInput with one line naming the file. Anything else
// (another exception, a crash, a sanitizer report, an image of another size than a PNG header
// declares) is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "io/image_codecs.h"
#include "io/png_check.h"
#include "rangefill/core/errors.h"

namespace {

constexpr const char* kName = "fuzz-input";

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_image: %s\n", what.c_str());
  std::abort();
}

std::uint32_t big_endian(const std::uint8_t* bytes) {
  return std::uint32_t{bytes[0]} << 24 | std::uint32_t{bytes[1]} << 16 |
         std::uint32_t{bytes[2]} << 8 | bytes[3];
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  cv::Mat image;
  try {
    image = rangefill::detail::decode_color_image(bytes, kName);
  } catch (const rangefill::InvalidInput& error) {
    const std::string_view message = error.what();
    if (message.find('\n') != std::string_view::npos) finding("message of several lines");
    if (message.rfind(std::string(kName) + ": ", 0) != 0) {
      finding("message does not name the file: " + std::string(message));
    }
    return 0;
  } catch (const std::exception& error) {
    finding(std::string("not an InvalidInput: ") + error.what());
  }
  if (image.empty()) finding("decoded to an empty image");
  // A PNG accepted: IHDR is the first chunk, so its width and height are at bytes 16–23.
  if (rangefill::detail::is_png(bytes) &&
      (static_cast<std::uint32_t>(image.cols) != big_endian(data + 16) ||
       static_cast<std::uint32_t>(image.rows) != big_endian(data + 20))) {
    finding("decoded at another size than the header declares");
  }
  return 0;
}
