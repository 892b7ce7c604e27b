// Internal: the model files of models/, compiled into the library (shipped_models.cpp is generated
// by CMake from them), so that the library works from any directory and once installed.
#pragma once

#include <vector>

namespace rangefill {

struct ShippedModel {
  const char* name;  // the name load_foe_model() knows it by
  const char* text;  // the file's contents
};

const std::vector<ShippedModel>& shipped_models();

}  // namespace rangefill
