#include "scene/scene_writer.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/atomic_file.h"
#include "scene/toml_reader.h"
#include "util/error.h"

namespace seasim {

namespace {

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (std::error_code ec; !in || std::filesystem::is_directory(path, ec))
    throw InputError(path, 1, "", "cannot open scene file");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::string sceneTextWithOverrides(const std::string& scene_file, const std::vector<Override>& overrides) {
  // Parsed with the overrides first: the values are validated, and the scene knows the absolute
  // path of every file it names.
  const Scene scene = loadScene(scene_file, overrides);
  toml::table root = parseTomlText(readText(scene_file), scene_file);
  TomlSource source(scene_file);
  for (const Override& o : overrides) applyOverride(root, o, source);
  const SourceLoc here{"<scene writer>", 0};
  for (const ImageInputRef& image : scene.images) applyOverride(root, {image.key, quoted(image.path), here}, source);
  // The phase table is a data file too: absolute, so the written scene reads it from any folder.
  if (!scene.water.phase_file.empty())
    applyOverride(root, {"water.phase_file", quoted(scene.water.phase_file), here}, source);
  if (const toml::table* spectral = root["spectral"].as_table(); spectral && spectral->contains("camera_dir"))
    applyOverride(root, {"spectral.camera_dir", quoted(scene.spectral.camera_dir), here}, source);
  std::ostringstream text;
  text << "# " << scene.name << ": " << scene.file << " with";
  if (overrides.empty()) text << " no changes";
  for (const Override& o : overrides) text << " " << o.key << "=" << o.value_toml;
  text << "\n" << root << "\n";
  return text.str();
}

std::string writeSceneWithOverrides(const std::string& scene_file, const std::vector<Override>& overrides,
                                    const std::string& out_path) {
  const std::string text = sceneTextWithOverrides(scene_file, overrides);
  (void)parseScene(text, out_path);  // never write a file that `seasim render` would refuse
  writeTextAtomic(out_path, text);
  return out_path;
}

}  // namespace seasim
