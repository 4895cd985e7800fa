// py_convert.h — Python values to and from seasim's own forms: a dict as a scene's TOML, a value as
// an override's TOML text (what --set takes), report JSON as Python objects, vectors as NumPy arrays
// that own their memory (no copy).
#pragma once
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "scene/scene_parser.h"

namespace seasim::py {

namespace nb = nanobind;

// The name parseScene gets for a scene made from a dict: errors read "<dict>: key 'camera.width': ...".
inline const char* kDictFile = "<dict>";
// Where overrides given from Python come from, in errors: "<overrides>: key 'sun.zenith_deg': ...".
inline const char* kOverridesFile = "<overrides>";

// A scene dict (same sections and keys as a scene file) as TOML text. Values may be bool, int,
// float, str, os.PathLike, list/tuple, dict, or anything with .tolist() (NumPy). Throws
// nb::type_error naming the dict path ("camera.position[1]") of a value that is none of those.
std::string dictToToml(nb::handle scene);

// {"sun.zenith_deg": 40, "water.jerlov": "IB"} as overrides in that order; nothing for None.
std::vector<Override> overridesFrom(nb::handle mapping);

// A str or os.PathLike as a path string.
std::string pathArg(nb::handle path);

// report.json's values as dict / list / str / float / int / bool / None.
nb::object jsonToPython(const nlohmann::json& value);

// A vector handed to NumPy without a copy: the array owns it (freed with the array).
template <class T>
nb::ndarray<nb::numpy, T> ownedArray(std::vector<T>&& data, std::initializer_list<size_t> shape) {
  auto* heap = new std::vector<T>(std::move(data));
  nb::capsule owner(heap, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  return nb::ndarray<nb::numpy, T>(heap->data(), shape, owner);
}

}  // namespace seasim::py
