#include "rangefill/inpaint/inpainters.h"

#include <functional>

#include <opencv2/photo.hpp>

#include "rangefill/core/errors.h"
#include "rangefill/inpaint/harmonic.h"

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
         return std::make_unique<OpenCvInpainter>(cv::INPAINT_TELEA, o.opencv.radius);
       }},
      {"ns",
       [](const InpainterOptions& o) {
         return std::make_unique<OpenCvInpainter>(cv::INPAINT_NS, o.opencv.radius);
       }},
      {"harmonic", [](const InpainterOptions&) { return std::make_unique<HarmonicInpainter>(); }},
      {"foe",
       [](const InpainterOptions& o) {
         if (!(o.foe.tolerance >= 0) || o.foe.iterations < 0) {
           throw InvalidInput("foe: the tolerance and the iterations must not be negative");
         }
         if (o.foe.start.rfind("foe", 0) == 0) {
           throw InvalidInput("foe: cannot start from " + o.foe.start);
         }
         FoeMapOptions map;
         map.function_tolerance = o.foe.tolerance;
         map.max_iterations = o.foe.iterations;
         std::unique_ptr<Inpainter> start;
         if (o.foe.start != "harmonic") start = make_inpainter(o.foe.start, o);
         return std::make_unique<FoeInpainter>(load_foe_model(o.foe.model), map, std::move(start));
       }},
      {"mls",
       [](const InpainterOptions& o) { return std::make_unique<MlsHeightInpainter>(o.mls); }},
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
    with_model.foe.model = std::string(spec.substr(colon + 1));
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

}  // namespace rangefill
