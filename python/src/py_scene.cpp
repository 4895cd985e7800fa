#include "py_scene.h"

#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <fstream>
#include <sstream>

#include "plan/plan.h"
#include "py_convert.h"
#include "scene/scene_inputs.h"
#include "util/paths.h"

namespace nb = nanobind;

namespace seasim::py {

bool PyScene::fromDict() const { return path == kDictFile; }

namespace {

PyScene makeScene(std::string path, std::string text, std::vector<Override> overrides) {
  PyScene s{std::move(path), std::move(text), std::move(overrides), {}};
  s.scene = parseScene(s.text, s.path, s.overrides);
  checkSceneInputs(s.scene);  // textures and data files readable, as `seasim validate` checks
  return s;
}

PyScene loadScene(nb::handle path_arg, nb::handle overrides) {
  const std::string path = pathArg(path_arg);
  if (const std::string problem = inputFileProblem(path); !problem.empty()) {
    PyErr_SetString(PyExc_FileNotFoundError, ("scene " + problem).c_str());
    throw nb::python_error();
  }
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return makeScene(path, text.str(), overridesFrom(overrides));
}

nb::dict overridesDict(const PyScene& s) {
  nb::dict d;
  for (const Override& o : s.overrides) d[o.key.c_str()] = nb::str(o.value_toml.c_str());
  return d;
}

}  // namespace

void bindScene(nb::module_& m) {
  nb::class_<PyScene>(m, "Scene",
                      "A validated scene: a scene file or a dict with the same sections and keys "
                      "(scenes/README.md), with overrides as `seasim render --set` takes them.")
      .def_static("load", &loadScene, nb::arg("path"), nb::arg("overrides") = nb::none(),
                  "Reads and validates a scene file. `overrides` maps dotted keys to values, e.g. "
                  "{'sun.zenith_deg': 40, 'water.jerlov': 'IB'}.\n\n"
                  "Raises FileNotFoundError for a missing file and seasim.SceneError (file, line, key) "
                  "for bad content.")
      .def_static(
          "from_dict",
          [](nb::handle scene, nb::handle overrides) { return makeScene(kDictFile, dictToToml(scene), overridesFrom(overrides)); },
          nb::arg("scene"), nb::arg("overrides") = nb::none(),
          "A scene from a dict of sections, e.g. {'camera': {'width': 64, ...}, 'water': {'jerlov': 'IB'}}. "
          "Relative paths resolve against the current folder.\n\n"
          "Raises seasim.SceneError whose key is the dict path of the bad value, TypeError for values "
          "no scene file can hold.")
      .def("with_overrides",
           [](const PyScene& s, nb::handle overrides) {
             std::vector<Override> all = s.overrides;
             for (Override& o : overridesFrom(overrides)) all.push_back(std::move(o));
             return makeScene(s.path, s.text, all);
           },
           nb::arg("overrides"), "The same scene with more overrides (later ones win).")
      .def_prop_ro("name", [](const PyScene& s) { return s.scene.name; })
      .def_prop_ro("file", [](const PyScene& s) -> nb::object {
        return s.fromDict() ? nb::none() : nb::object(nb::str(s.path.c_str()));
      }, nb::for_getter(nb::sig("def file(self, /) -> str | None")), "The scene file; None for a scene made from a dict.")
      .def_prop_ro("width", [](const PyScene& s) { return s.scene.camera.width; })
      .def_prop_ro("height", [](const PyScene& s) { return s.scene.camera.height; })
      .def_prop_ro("toml", [](const PyScene& s) { return s.text; }, "The TOML text (a dict's as written for it).")
      .def_prop_ro("overrides", &overridesDict, "The overrides in effect: key -> TOML value text.")
      .def_prop_ro("plan", [](const PyScene& s) { return makePlan(s.scene).toText(); }, "What `seasim plan` prints.")
      .def("__repr__", [](const PyScene& s) {
        return "<seasim.Scene '" + s.scene.name + "' " + std::to_string(s.scene.camera.width) + "x" +
               std::to_string(s.scene.camera.height) + (s.fromDict() ? " from a dict" : " from " + s.path) + ">";
      });
}

}  // namespace seasim::py
