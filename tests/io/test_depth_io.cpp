// Depth and mask image files: round trips, errors that name the file, damaged PNGs.
#include "rangefill/io/depth_io.h"

#include <cstring>
#include <functional>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "rangefill/core/errors.h"
#include "rangefill/io/mesh_io.h"
#include "support.h"

namespace rangefill {
namespace {

namespace fs = std::filesystem;

cv::Mat sample_depth(int type) {
  cv::Mat depth(37, 53, type);
  cv::randu(depth, 0, type == CV_16UC1 ? 65535 : 9.5);
  depth(cv::Rect(3, 4, 5, 6)).setTo(0);
  if (type == CV_32FC1) depth.at<float>(10, 10) = std::numeric_limits<float>::quiet_NaN();
  return depth;
}

bool bit_identical(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() &&
         std::memcmp(a.data, b.data, a.total() * a.elemSize()) == 0;
}

// 16-bit PNG and TIFF, float TIFF and EXR come back bit for bit (NaN included); the write is atomic
// (no temporary file left).
TEST(DepthFiles, RoundTripsBitForBit) {
  const fs::path dir = testing::temporary_directory("depth-files");
  for (const char* name : {"a.png", "a.tif", "b.TIFF"}) {
    const cv::Mat depth = sample_depth(CV_16UC1);
    write_depth_image(depth, dir / name);
    EXPECT_TRUE(bit_identical(read_depth_image(dir / name), depth)) << name;
  }
  for (const char* name : {"c.tiff", "c.exr"}) {
    const cv::Mat depth = sample_depth(CV_32FC1);
    write_depth_image(depth, dir / name);
    EXPECT_TRUE(bit_identical(read_depth_image(dir / name), depth)) << name;
  }
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 5);
  fs::remove_all(dir);
}

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "no exception";
}

// Files are exchanged with OpenCV's own codecs bit for bit, both ways: 16-bit PNG and TIFF, float
// TIFF and EXR, and 8-bit masks.
TEST(DepthFiles, AreExchangedWithOpenCvBitForBit) {
  const fs::path dir = testing::temporary_directory("depth-opencv");
  for (const auto& [name, type] : std::vector<std::pair<std::string, int>>{
           {"a.png", CV_16UC1}, {"a.tif", CV_16UC1}, {"b.tif", CV_32FC1}, {"c.exr", CV_32FC1}}) {
    SCOPED_TRACE(name);
    const cv::Mat depth = sample_depth(type);
    ASSERT_TRUE(cv::imwrite((dir / ("opencv-" + name)).string(), depth));
    EXPECT_TRUE(bit_identical(read_depth_image(dir / ("opencv-" + name)), depth));
    write_depth_image(depth, dir / ("ours-" + name));
    EXPECT_TRUE(
        bit_identical(cv::imread((dir / ("ours-" + name)).string(), cv::IMREAD_UNCHANGED), depth));
  }
  const cv::Mat mask = sample_depth(CV_16UC1) > 30000;
  write_mask_image(mask, dir / "mask.png");
  EXPECT_TRUE(bit_identical(cv::imread((dir / "mask.png").string(), cv::IMREAD_UNCHANGED), mask));
  fs::remove_all(dir);
}

// Colour images read as OpenCV reads them: JPEG (libjpeg) and PNG, colour (BGR) and grey; a
// truncated JPEG or a 16-bit one is refused naming the file.
TEST(ColorFiles, ReadAsOpenCvReadsThem) {
  const fs::path dir = testing::temporary_directory("colour-files");
  cv::Mat colour(24, 32, CV_8UC3);
  cv::randu(colour, 0, 256);
  cv::Mat grey;
  cv::extractChannel(colour, grey, 1);
  for (const auto& [name, image] : std::vector<std::pair<std::string, cv::Mat>>{
           {"c.jpg", colour}, {"g.jpg", grey}, {"c.png", colour}, {"g.png", grey}}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(cv::imwrite((dir / name).string(), image));
    const cv::Mat expected = cv::imread((dir / name).string(), cv::IMREAD_UNCHANGED);
    EXPECT_TRUE(bit_identical(read_color_image(dir / name), expected));
  }
  const std::string jpeg = read_file(dir / "c.jpg");
  write_file_atomically(jpeg.substr(0, jpeg.size() / 3), dir / "cut.jpg");
  EXPECT_THROW(read_color_image(dir / "cut.jpg"), InvalidInput);
  try {
    read_color_image(dir / "cut.jpg");
  } catch (const InvalidInput& error) {
    EXPECT_EQ(std::string(error.what()).rfind((dir / "cut.jpg").string() + ": ", 0), 0u);
  }
  write_depth_image(sample_depth(CV_16UC1), dir / "deep.png");
  EXPECT_THROW(read_color_image(dir / "deep.png"), InvalidInput);
  fs::remove_all(dir);
}

// Truncated or damaged TIFF and EXR files are refused with one line naming the file; libtiff and
// OpenEXR print nothing.
TEST(DepthFiles, DamagedTiffAndExrAreRefusedSilently) {
  const fs::path dir = testing::temporary_directory("depth-damaged");
  for (const char* name : {"a.tif", "a.exr"}) {
    write_depth_image(sample_depth(CV_32FC1), dir / name);
    const std::string bytes = read_file(dir / name);
    std::string scrambled = bytes;
    for (size_t i = 8; i < scrambled.size(); i += 7) scrambled[i] = static_cast<char>(i * 31);
    for (const std::string& damaged :
         {bytes.substr(0, bytes.size() / 2), bytes.substr(0, 12), scrambled}) {
      SCOPED_TRACE(std::string(name) + " of " + std::to_string(damaged.size()) + " bytes");
      const fs::path path = dir / ("damaged-" + std::string(name));
      write_file_atomically(damaged, path);
      ::testing::internal::CaptureStderr();
      const std::string message = message_of([&] { read_depth_image(path); });
      EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
      EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos);
    }
  }
  // An EXR whose data window declares 30 000 × 30 000 pixels is refused before anything is
  // reserved for them (3.6 GB).
  std::string exr = read_file(dir / "a.exr");
  const size_t window = exr.find(std::string("dataWindow\0box2i\0", 17));
  ASSERT_NE(window, std::string::npos);
  const std::int32_t large = 29999;
  for (int corner : {2, 3}) std::memcpy(&exr[window + 17 + 4 + 4 * corner], &large, 4);
  write_file_atomically(exr, dir / "large.exr");
  EXPECT_NE(message_of([&] { read_depth_image(dir / "large.exr"); }).find("bytes can hold"),
            std::string::npos);
  // One row of 32768 pixels fits the file's ~9 MB, but DWAB's decompressor reserves 256 rows at
  // once (32 MB): the same file with ZIP's 16 rows gets past the size check and fails later.
  exr = read_file(dir / "a.exr");
  const std::int32_t row[] = {0, 0, 32767, 0};
  std::memcpy(&exr[window + 17 + 4], row, sizeof(row));
  const size_t compression = exr.find(std::string("compression\0compression\0", 24));
  ASSERT_NE(compression, std::string::npos);
  for (const auto& [method, refused] : {std::pair{9, true}, std::pair{3, false}}) {
    exr[compression + 24 + 4] = static_cast<char>(method);
    write_file_atomically(exr, dir / "row.exr");
    const std::string message = message_of([&] { read_depth_image(dir / "row.exr"); });
    EXPECT_EQ(message.find("bytes can hold") != std::string::npos, refused) << message;
  }
  // A second channel is refused before OpenEXR reads the file.
  exr = read_file(dir / "a.exr");
  const size_t channels = exr.find(std::string("channels\0chlist\0", 16));
  ASSERT_NE(channels, std::string::npos);
  std::int32_t size = 0;
  std::memcpy(&size, &exr[channels + 16], 4);
  const std::string entry = exr.substr(channels + 20, size - 1);  // one channel, no end mark
  const std::int32_t doubled = size + static_cast<std::int32_t>(entry.size());
  std::memcpy(&exr[channels + 16], &doubled, 4);
  exr.insert(channels + 20 + entry.size(), "Z" + entry.substr(1));
  write_file_atomically(exr, dir / "two.exr");
  EXPECT_EQ(message_of([&] { read_depth_image(dir / "two.exr"); }),
            (dir / "two.exr").string() + ": has 2 channels; a depth or mask image has one");
  fs::remove_all(dir);
}

// Unreadable files and images that are not depth give one-line errors naming the file; formats
// that cannot hold the type are refused before writing.
TEST(DepthFiles, ClearErrorsForBadFiles) {
  const fs::path dir = testing::temporary_directory("depth-bad");
  const std::string missing = (dir / "missing.png").string();
  EXPECT_THROW(read_depth_image(missing), IoError);
  EXPECT_EQ(message_of([&] { read_depth_image(missing); }).rfind(missing + ": cannot open", 0), 0u);

  write_file_atomically("not an image at all", dir / "text.png");
  EXPECT_EQ(message_of([&] { read_depth_image(dir / "text.png"); }),
            (dir / "text.png").string() + ": not a PNG, TIFF or EXR image");
  const std::string png16 = [&] {
    write_depth_image(sample_depth(CV_16UC1), dir / "full.png");
    return read_file(dir / "full.png");
  }();
  write_file_atomically(png16.substr(0, png16.size() / 2), dir / "truncated.png");
  EXPECT_THROW(read_depth_image(dir / "truncated.png"), InvalidInput);

  cv::imwrite((dir / "gray8.png").string(), cv::Mat(4, 4, CV_8U, cv::Scalar(7)));
  EXPECT_EQ(message_of([&] { read_depth_image(dir / "gray8.png"); }),
            (dir / "gray8.png").string() +
                ": CV_8UC1 is not depth: expected 16-bit unsigned (millimetres) or 32-bit float "
                "(metres)");
  cv::imwrite((dir / "rgb.png").string(), cv::Mat(4, 4, CV_16UC3, cv::Scalar(7, 8, 9)));
  EXPECT_EQ(message_of([&] { read_depth_image(dir / "rgb.png"); }),
            (dir / "rgb.png").string() + ": has 3 channels; a depth or mask image has one");
  EXPECT_EQ(cv::countNonZero(read_mask_image(dir / "gray8.png")), 16);

  EXPECT_EQ(message_of([&] { write_depth_image(sample_depth(CV_32FC1), dir / "f.png"); }),
            (dir / "f.png").string() +
                ": PNG holds 16-bit depth only; write float depth to .tif or .exr");
  EXPECT_THROW(write_depth_image(sample_depth(CV_16UC1), dir / "f.exr"), InvalidInput);
  EXPECT_THROW(write_depth_image(sample_depth(CV_16UC1), dir / "f.jpg"), InvalidInput);
  EXPECT_THROW(write_depth_image(sample_depth(CV_16UC1), dir / "no-such-dir" / "f.png"), IoError);
  fs::remove_all(dir);
}

// A damaged PNG is refused by the PNG check (src/png_check.h) before OpenCV sees it: one line
// naming the file, and nothing printed by libpng (which, under OpenCV, reports to stderr).
TEST(DepthFiles, DamagedPngsAreRefusedWithoutLibpngOutput) {
  const fs::path dir = testing::temporary_directory("depth-png");
  const cv::Mat depth = sample_depth(CV_16UC1);
  write_depth_image(depth, dir / "full.png");
  const std::string png = read_file(dir / "full.png");
  std::string crc = png;
  crc[png.size() - 20] ^= 0x40;  // a byte of the last IDAT chunk (IEND takes the last 12)
  std::string type = png;
  type[12] = '1';  // IHDR's type
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"truncated.png", png.substr(0, png.size() / 2)},
      {"crc.png", crc},
      {"type.png", type},
      {"no-iend.png", png.substr(0, png.size() - 12)},
      {"header-only.png", png.substr(0, 33) + png.substr(png.size() - 12)},
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    const fs::path path = dir / name;  // a lambda may not capture a structured binding in C++17
    write_file_atomically(bytes, path);
    ::testing::internal::CaptureStderr();
    const std::string message = message_of([&] { read_depth_image(path); });
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(message.rfind(path.string() + ": corrupt PNG: ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  EXPECT_TRUE(bit_identical(read_depth_image(dir / "full.png"), depth));
  fs::remove_all(dir);

  // The image fuzzer's corpus (tests/fuzz/corpus/image, with its findings): each file is read or
  // refused with one line naming it, silently.
  const fs::path corpus = fs::path(RANGEFILL_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "image";
  int read = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(corpus)) {
    SCOPED_TRACE(entry.path().filename().string());
    ::testing::internal::CaptureStderr();
    const std::string message = message_of([&] { read_depth_image(entry.path()); });
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    read += message == "no exception";
    if (message != "no exception") {
      EXPECT_EQ(message.rfind(entry.path().string() + ": ", 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos);
    }
  }
  // 16-bit PNGs (interlaced or not) and TIFF, float TIFF, EXR in ZIP and the 7 other compressions
  EXPECT_EQ(read, 12);
}

}  // namespace
}  // namespace rangefill
