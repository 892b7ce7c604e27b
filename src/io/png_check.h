// Internal: a check of a PNG file's structure before OpenCV decodes it. Not installed.
//
// libpng, under OpenCV, prints its errors to stderr ("libpng error: Not enough image data") and
// OpenCV allocates the image its header declares before any pixel is read (1.8 GB for a 74-byte
// file declaring 30000×30000 16-bit pixels). So the container is checked first, with zlib: every
// chunk's length and CRC, a valid IHDR within OpenCV's size limits, no unknown critical chunk,
// one run of IDAT chunks whose data inflates to exactly the size the header declares with a valid
// filter type on every row. A file that passes decodes without a libpng error.
#pragma once

#include <string>
#include <string_view>

namespace rangefill::detail {

/// True if `bytes` begin with the PNG signature.
bool is_png(std::string_view bytes);

/// Throws InvalidInput("<name>: corrupt PNG: <why>") unless the PNG in `bytes` is sound as above.
/// Memory is constant in the image size. Precondition: is_png(bytes).
void check_png(std::string_view bytes, const std::string& name);

}  // namespace rangefill::detail
