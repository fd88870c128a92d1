#include "ltp/models/scene_input.h"

#include <optional>

#include "ltp/core/error.h"
#include "ltp/models/lin_scene.h"
#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"

namespace ltp {

LoadedScene LoadSceneInput(const std::vector<std::string>& names,
                           const std::vector<std::string>& assignments) {
  if (names.empty()) throw InputError("no scene given");
  std::optional<LinOperatingPoint> op;
  Scene scene;
  if (names.size() > 1 && !LooksLikeLinInput(names.front()))
    throw InputError("unexpected argument '" + names[1] + "' after scene '" + names.front() +
                     "': only OpenFAST .lin input takes several files");
  if (names.size() > 1 || LooksLikeLinInput(names.front())) {
    op = ReadLinOperatingPoint(names);
    scene = MakeLinScene(*op);
  } else {
    scene = LoadScene(names.front());
  }
  std::vector<std::pair<std::string, std::string>> overrides;
  for (const std::string& a : assignments) overrides.push_back(SplitAssignment(a));
  ParameterMap parameters = scene.Resolve(overrides);
  PeriodicSystem system = scene.build(parameters);
  std::vector<std::string> notes;
  if (op)  // the caveats of the coordinates actually analysed
    notes = LinCaveats(parameters.at("mbc") == 1 ? InMultiBladeCoordinates(*op, Mbc3(*op)) : *op);
  return {std::move(scene), std::move(parameters), std::move(system), std::move(notes)};
}

}  // namespace ltp
