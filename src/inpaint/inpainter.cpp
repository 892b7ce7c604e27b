#include "rangefill/inpaint/inpainter.h"

#include <functional>

#include <opencv2/photo.hpp>

#include "rangefill/core/errors.h"
#include "rangefill/inpaint/foe.h"
#include "rangefill/inpaint/harmonic.h"
#include "rangefill/inpaint/mls_height.h"
#include "rangefill/inpaint/opencv_inpaint.h"

namespace rangefill {

namespace {

struct Registration {
  const char* name;
  std::function<std::unique_ptr<Inpainter>(const InpainterOptions&)> make;
};

// Every back-end of inpaint/, by name.
const std::vector<Registration>& registry() {
  static const std::vector<Registration> backends = {
      {"telea",
       [](const InpainterOptions& o) {
         return std::make_unique<OpenCvInpainter>(cv::INPAINT_TELEA, o.radius);
       }},
      {"ns",
       [](const InpainterOptions& o) {
         return std::make_unique<OpenCvInpainter>(cv::INPAINT_NS, o.radius);
       }},
      {"harmonic", [](const InpainterOptions&) { return std::make_unique<HarmonicInpainter>(); }},
      {"foe",
       [](const InpainterOptions& o) {
         if (!(o.foe_tolerance >= 0) || o.foe_iterations < 0) {
           throw InvalidInput("foe: the tolerance and the iterations must not be negative");
         }
         if (o.foe_start.rfind("foe", 0) == 0) {
           throw InvalidInput("foe: cannot start from " + o.foe_start);
         }
         FoeMapOptions map;
         map.function_tolerance = o.foe_tolerance;
         map.max_iterations = o.foe_iterations;
         std::unique_ptr<Inpainter> start;
         if (o.foe_start != "harmonic") start = make_inpainter(o.foe_start, o);
         return std::make_unique<FoeInpainter>(load_foe_model(o.model), map, std::move(start));
       }},
      {"mls", [](const InpainterOptions& o) { return std::make_unique<MlsHeightInpainter>(o); }},
  };
  return backends;
}

}  // namespace

std::vector<std::string> inpainter_names() {
  std::vector<std::string> names;
  for (const Registration& backend : registry()) names.emplace_back(backend.name);
  return names;
}

std::unique_ptr<Inpainter> make_inpainter(std::string_view spec, const InpainterOptions& options) {
  const size_t colon = spec.find(':');
  const std::string_view name = spec.substr(0, colon);
  if (name == "foe" && colon != std::string_view::npos) {
    InpainterOptions with_model = options;
    with_model.model = std::string(spec.substr(colon + 1));
    return make_inpainter(name, with_model);
  }
  for (const Registration& backend : registry()) {
    if (spec == backend.name) return backend.make(options);
  }
  std::string known;
  for (const std::string& n : inpainter_names()) known += (known.empty() ? "" : ", ") + n;
  throw InvalidInput("unknown inpainter '" + std::string(spec) + "' (known: " + known +
                     ", foe:MODEL)");
}

int start_inpainting(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out,
                     const std::string& who) {
  check_inpaint_arguments(depth, mask, who);
  depth.copyTo(out);
  const int masked = cv::countNonZero(mask);
  if (masked == static_cast<int>(mask.total())) out.setTo(0);
  return masked;
}

void check_inpaint_arguments(cv::InputArray depth, cv::InputArray mask, const std::string& who) {
  if (depth.type() != CV_32FC1) throw InvalidInput(who + ": depth must be CV_32FC1");
  if (mask.type() != CV_8UC1) throw InvalidInput(who + ": mask must be CV_8UC1");
  if (depth.size() != mask.size()) {
    throw InvalidInput(who + ": mask size differs from depth size");
  }
}

}  // namespace rangefill
