#include "rangefill/inpaint/foe_model.h"

#include <cmath>
#include <complex>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>

#include "inpaint/shipped_models.h"
#include "rangefill/core/errors.h"

namespace rangefill {

namespace {

[[noreturn]] void malformed(const std::string& name, const std::string& what) {
  throw InvalidInput(name + ": " + what);
}

// Roth & Black's ASCII format: "s K", the x and y offsets of the s² taps, K alphas, K rows of s²
// coefficients. Their filters were learned on grey levels 0–255: inputs in [0, 1] are scaled up.
FoeModel parse_roth_black(std::string_view text, const std::string& name) {
  std::istringstream in{std::string(text)};
  FoeModel model;
  int count = 0;
  if (!(in >> model.size >> count) || model.size < 1 || model.size > 15 || model.size % 2 == 0 ||
      count < 1 || count > 1024) {
    malformed(name, "bad FoE header (filter size and count)");
  }
  const int taps = model.size * model.size;
  std::vector<int> xs(taps), ys(taps);
  for (int& x : xs) in >> x;
  for (int& y : ys) in >> y;
  model.alphas.resize(count);
  for (double& alpha : model.alphas) in >> alpha;
  for (int i = 0; i < count; ++i) {
    cv::Mat filter = cv::Mat::zeros(model.size, model.size, CV_64F);
    for (int k = 0; k < taps; ++k) {
      double value = 0;
      in >> value;
      if (xs[k] < 0 || xs[k] >= model.size || ys[k] < 0 || ys[k] >= model.size) {
        malformed(name, "tap offset outside the filter");
      }
      filter.at<double>(ys[k], xs[k]) = value;
    }
    // The filters were learned in a basis without the constant function, but the printed taps sum
    // to up to 1e-3 of their magnitude: remove that mean, or a constant image is not a minimiser
    // (at grey-level scale a flat 0.25 would read as responses of 0.5).
    filter -= cv::mean(filter)[0];
    model.filters.push_back(filter);
  }
  if (!in) malformed(name, "truncated FoE file");
  model.name = name;
  model.input_scale = 255;
  model.normalisation = "image values in [0, 1], seen by the filters as grey levels 0-255";
  model.training = "Roth & Black, natural images (BSDS), contrastive divergence";
  return model;
}

void check(const FoeModel& model, const std::string& name) {
  if (model.size < 1 || model.size % 2 == 0) malformed(name, "filter size must be odd");
  if (model.filters.empty() || model.filters.size() != model.alphas.size()) {
    malformed(name, "needs as many alphas as filters, at least one");
  }
  for (double alpha : model.alphas) {
    if (!(alpha > 0) || !std::isfinite(alpha)) malformed(name, "alphas must be positive");
  }
  if (!(model.input_scale > 0) || !std::isfinite(model.input_scale)) {
    malformed(name, "input_scale must be positive");
  }
}

}  // namespace

FoeModel parse_foe_model(std::string_view text, const std::string& name) {
  if (text.substr(0, 5) != "%YAML") {
    FoeModel model = parse_roth_black(text, name);
    check(model, name);
    return model;
  }
  FoeModel model;
  try {
    cv::FileStorage storage(std::string(text), cv::FileStorage::READ | cv::FileStorage::MEMORY);
    if ((int)storage["format_version"] != FoeModel::kFormatVersion) {
      malformed(name, "unsupported FoE model format_version");
    }
    storage["name"] >> model.name;
    model.size = (int)storage["filter_size"];
    const int count = (int)storage["filter_count"];
    storage["input_scale"] >> model.input_scale;
    model.known_rms = (int)storage["known_rms"] != 0;
    storage["normalisation"] >> model.normalisation;
    storage["training"] >> model.training;
    cv::Mat alphas, filters;
    storage["alphas"] >> alphas;
    storage["filters"] >> filters;
    if (alphas.total() != static_cast<size_t>(count) || filters.rows != count ||
        filters.cols != model.size * model.size || count < 1) {
      malformed(name, "alphas and filters do not match filter_size and filter_count");
    }
    alphas.convertTo(alphas, CV_64F);
    filters.convertTo(filters, CV_64F);
    for (int i = 0; i < count; ++i) {
      model.alphas.push_back(alphas.at<double>(i));
      model.filters.push_back(filters.row(i).reshape(1, model.size).clone());
    }
  } catch (const cv::Exception& error) {
    malformed(name, "not a readable FoE model (" + std::string(error.err) + ")");
  }
  check(model, name);
  return model;
}

std::string serialize_foe_model(const FoeModel& model) {
  cv::FileStorage storage(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  storage << "format_version" << FoeModel::kFormatVersion;
  storage << "name" << model.name;
  storage << "filter_size" << model.size;
  storage << "filter_count" << model.count();
  storage << "input_scale" << model.input_scale;
  storage << "known_rms" << static_cast<int>(model.known_rms);
  storage << "normalisation" << model.normalisation;
  storage << "training" << model.training;
  storage << "alphas" << cv::Mat(model.alphas, true).reshape(1, 1);
  cv::Mat filters(model.count(), model.size * model.size, CV_64F);
  for (int i = 0; i < model.count(); ++i) {
    model.filters[i].reshape(1, 1).copyTo(filters.row(i));
  }
  storage << "filters" << filters;
  return storage.releaseAndGetString();
}

std::vector<std::string> shipped_foe_models() {
  std::vector<std::string> names;
  for (const ShippedModel& model : shipped_models()) names.emplace_back(model.name);
  return names;
}

FoeModel load_foe_model(const std::string& name_or_path) {
  for (const ShippedModel& model : shipped_models()) {
    if (name_or_path == model.name) return parse_foe_model(model.text, model.name);
  }
  std::ifstream file(name_or_path, std::ios::binary);
  if (!file) {
    std::string known;
    for (const std::string& name : shipped_foe_models())
      known += (known.empty() ? "" : ", ") + name;
    throw InvalidInput(name_or_path + ": neither a shipped FoE model (" + known +
                       ") nor a readable file");
  }
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return parse_foe_model(text, name_or_path);
}

double foe_input_divisor(const FoeModel& model, const cv::Mat& image, const cv::Mat& mask) {
  if (!model.known_rms) return 1;
  cv::Mat values;
  image.convertTo(values, CV_64F);
  double sum = 0;  // in row order, the same whatever OpenCV's threads do
  int count = 0;
  for (int row = 0; row < values.rows; ++row) {
    for (int col = 0; col < values.cols; ++col) {
      if (mask.at<std::uint8_t>(row, col)) continue;
      sum += values.at<double>(row, col) * values.at<double>(row, col);
      ++count;
    }
  }
  const double rms = count > 0 ? std::sqrt(sum / count) : 0;
  return rms > 0 ? rms : 1;
}

}  // namespace rangefill
