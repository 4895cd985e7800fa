#include "py_convert.h"

#include <nanobind/stl/string.h>
#include <toml++/toml.h>

#include <sstream>

namespace seasim::py {

namespace {

std::string typeName(nb::handle value) { return nb::cast<std::string>(nb::type_name(value.type())); }

// Where emit() puts a node: a table under a key, or the end of an array (one type, so that emit's
// recursion does not instantiate a new template per level).
struct Sink {
  toml::table* table = nullptr;
  std::string key;
  toml::array* array = nullptr;
  template <class T>
  void operator()(T&& node) const {
    if (table) table->insert_or_assign(key, std::forward<T>(node));
    else array->push_back(std::forward<T>(node));
  }
};

// Hands `value` as a TOML node to `sink`; `path` names it in errors. bool before int: Python's bool
// is an int.
void emit(nb::handle value, const std::string& path, const Sink& sink) {
  if (nb::isinstance<nb::bool_>(value)) {
    sink(nb::cast<bool>(value));
  } else if (nb::isinstance<nb::int_>(value)) {
    sink(nb::cast<int64_t>(value));
  } else if (nb::isinstance<nb::float_>(value)) {
    sink(nb::cast<double>(value));
  } else if (nb::isinstance<nb::str>(value)) {
    sink(nb::cast<std::string>(value));
  } else if (nb::isinstance<nb::dict>(value)) {
    toml::table table;
    for (auto [k, v] : nb::borrow<nb::dict>(value)) {
      if (!nb::isinstance<nb::str>(k))
        throw nb::type_error((kDictFile + std::string(": key '") + path + "': keys must be strings, not " + typeName(k)).c_str());
      const std::string key = nb::cast<std::string>(k);
      emit(v, path.empty() ? key : path + "." + key, Sink{&table, key, nullptr});
    }
    sink(std::move(table));
  } else if (nb::isinstance<nb::list>(value) || nb::isinstance<nb::tuple>(value)) {
    toml::array array;
    size_t i = 0;
    for (nb::handle item : value) emit(item, path + "[" + std::to_string(i++) + "]", Sink{nullptr, "", &array});
    sink(std::move(array));
  } else if (nb::hasattr(value, "__fspath__")) {
    sink(pathArg(value));
  } else if (nb::hasattr(value, "tolist")) {  // NumPy arrays and scalars
    emit(value.attr("tolist")(), path, sink);
  } else {
    throw nb::type_error((std::string(kDictFile) + ": key '" + path +
                          "': a scene value is a bool, number, string, list or dict, not " + typeName(value))
                             .c_str());
  }
}

}  // namespace

std::string pathArg(nb::handle path) {
  if (!nb::isinstance<nb::str>(path) && !nb::hasattr(path, "__fspath__"))
    throw nb::type_error(("a path is a str or os.PathLike, not " + typeName(path)).c_str());
  return nb::cast<std::string>(nb::module_::import_("os").attr("fspath")(path));
}

std::string dictToToml(nb::handle scene) {
  if (!nb::isinstance<nb::dict>(scene))
    throw nb::type_error(("Scene.from_dict expects a dict of sections, not " + typeName(scene)).c_str());
  toml::table holder;  // the dict as holder["scene"], printed as the scene's own sections
  emit(scene, "", Sink{&holder, "scene", nullptr});
  std::ostringstream out;
  out << *holder.get_as<toml::table>("scene");
  return out.str();
}

std::vector<Override> overridesFrom(nb::handle mapping) {
  std::vector<Override> out;
  if (mapping.is_none()) return out;
  if (!nb::isinstance<nb::dict>(mapping))
    throw nb::type_error(("overrides are a dict {\"sun.zenith_deg\": 40, ...}, not " + typeName(mapping)).c_str());
  for (auto [k, v] : nb::borrow<nb::dict>(mapping)) {
    if (!nb::isinstance<nb::str>(k)) throw nb::type_error(("override keys are strings, not " + typeName(k)).c_str());
    const std::string key = nb::cast<std::string>(k);
    if (nb::isinstance<nb::dict>(v))
      throw nb::type_error((std::string(kOverridesFile) + ": key '" + key +
                            "': give each key of a table on its own ('" + key + ".name'), not a dict")
                               .c_str());
    // The value's TOML text, as --set would carry it: written as "v = ..." and cut after "v = ".
    toml::table holder;
    emit(v, key, Sink{&holder, "v", nullptr});
    std::ostringstream text;
    holder.get("v")->visit([&](const auto& node) { text << node; });
    out.push_back(Override{key, text.str(), SourceLoc{kOverridesFile, 0}});
  }
  return out;
}

nb::object jsonToPython(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null: return nb::none();
    case nlohmann::json::value_t::boolean: return nb::bool_(value.get<bool>());
    case nlohmann::json::value_t::number_integer: return nb::int_(value.get<int64_t>());
    case nlohmann::json::value_t::number_unsigned: return nb::int_(value.get<uint64_t>());
    case nlohmann::json::value_t::number_float: return nb::float_(value.get<double>());
    case nlohmann::json::value_t::string: return nb::str(value.get<std::string>().c_str());
    case nlohmann::json::value_t::array: {
      nb::list list;
      for (const auto& item : value) list.append(jsonToPython(item));
      return list;
    }
    case nlohmann::json::value_t::object: {
      nb::dict dict;
      for (const auto& [k, v] : value.items()) dict[k.c_str()] = jsonToPython(v);
      return dict;
    }
    default: return nb::none();
  }
}

}  // namespace seasim::py
