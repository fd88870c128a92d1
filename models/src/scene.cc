#include "ltp/models/scene.h"

#include <cmath>
#include <filesystem>

#include "expression.h"
#include "ltp/core/error.h"
#include "ltp/core/text.h"

namespace ltp {
namespace {

std::string ParameterList(const Scene& scene) {
  std::string list;
  for (const auto& p : scene.parameters) list += (list.empty() ? "" : ", ") + p.name;
  return list.empty() ? "none" : list;
}

}  // namespace

ParameterMap Scene::Resolve(
    const std::vector<std::pair<std::string, std::string>>& overrides) const {
  ParameterMap values;
  for (const auto& p : parameters) values[p.name] = p.value;
  for (const auto& [name, text] : overrides) {
    if (values.count(name) == 0)
      throw InputError("unknown parameter '" + name + "' for scene '" + this->name +
                       "' (parameters: " + ParameterList(*this) + ")");
    double value = 0;
    try {
      value = internal::EvaluateConstant(text);
    } catch (const internal::ExpressionError& e) {
      throw InputError("parameter '" + name + "': " + e.what());
    }
    if (!std::isfinite(value))
      throw InputError("parameter '" + name + "' = '" + text + "' is " +
                       internal::FormatValue(value) + ", not a finite number");
    values[name] = value;
  }
  return values;
}

PeriodicSystem Scene::Build(
    const std::vector<std::pair<std::string, std::string>>& overrides) const {
  if (!build) throw InputError("scene '" + name + "' has no builder");
  return build(Resolve(overrides));
}

std::pair<std::string, std::string> SplitAssignment(const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos) throw InputError("expected name=value, got '" + text + "'");
  std::string name = Trim(text.substr(0, equals));
  std::string value = Trim(text.substr(equals + 1));
  if (name.empty()) throw InputError("missing parameter name in '" + text + "'");
  if (value.empty()) throw InputError("missing value for parameter '" + name + "'");
  return {std::move(name), std::move(value)};
}

Scene LoadScene(const std::string& name_or_path) {
  std::string names;
  for (const Scene& scene : BuiltinScenes()) {
    if (scene.name == name_or_path) return scene;
    names += (names.empty() ? "" : ", ") + scene.name;
  }
  std::error_code error;
  if (std::filesystem::exists(name_or_path, error)) {
    // A named pipe or device would block reading forever.
    if (!std::filesystem::is_regular_file(name_or_path, error))
      throw InputError("'" + name_or_path + "' is not a regular file (a scene is a YAML file)");
    return LoadSceneFile(name_or_path);
  }
  throw InputError("unknown scene '" + name_or_path + "': not a built-in (" + names +
                   ") and no such file");
}

}  // namespace ltp
