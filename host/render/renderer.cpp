#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "device/enqueue.h"
#include "render/layer_readback.h"
#include "render/radiance_target.h"
#include "util/error.h"

namespace seasim {

namespace {

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

bool anyMatch(const std::vector<std::string>& patterns, const std::string& key) {
  for (const auto& p : patterns)
    if (keyMatches(p, key)) return true;
  return false;
}

// Keys that need no pass to claim them (no full rebuild when none does): the exposure and [display] are
// applied when the PNG is written and the name labels the outputs. Passes that do read the exposure (the shafts'
// cone clipping, the "auto" quality searches) claim it through "camera.*" and are marked as usual.
bool changesNoPass(const std::string& key) {
  return keyMatches("camera.exposure_ev", key) || keyMatches("display.*", key) || keyMatches("scene.*", key) ||
         keyMatches("name", key);
}

}  // namespace

Renderer::Renderer(Device& device, const Scene& scene, PassRegistry registry)
    : Renderer(device, registry.planChoices(device, scene), scene, std::move(registry)) {}

// `registry` is a reference so that the choice above is made before the registry moves into the member.
Renderer::Renderer(Device& device, const std::optional<Scene>& chosen, const Scene& scene, PassRegistry&& registry)
    : device_(device), registry_(std::move(registry)), follow_scene_(true), plan_(makePlan(chosen ? *chosen : scene)),
      ctx_(device, chosen ? *chosen : scene) {}

Renderer::Renderer(Device& device, const Scene& scene, Plan plan, PassRegistry registry)
    : device_(device), registry_(std::move(registry)), follow_scene_(false), plan_(std::move(plan)),
      ctx_(device, scene) {}

namespace {

std::string readSceneText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path)) throw InputError(path, 1, "", "cannot open scene file");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

Renderer::Renderer(Device& device, const std::string& scene_file, std::vector<Override> overrides,
                   PassRegistry registry)
    : Renderer(device, scene_file, readSceneText(scene_file), std::move(overrides), std::move(registry)) {}

Renderer::Renderer(Device& device, const std::string& scene_file, std::string scene_text,
                   std::vector<Override> overrides, PassRegistry registry)
    : Renderer(device, parseScene(scene_text, scene_file, overrides), std::move(registry)) {
  scene_file_ = scene_file;
  scene_text_ = std::move(scene_text);
  overrides_ = std::move(overrides);
}

void Renderer::build() {
  nodes_.clear();
  resources_.clear();
  const Scene& scene = ctx_.scene();
  bool image = false;
  for (const auto& entry : plan_.passes) image = image || contains(entry.writes, "rgb");
  if (!image) throw RuntimeError("scene '" + scene.name + "' has nothing to render (no water in view, no spotlights)");
  for (size_t i = 0; i < plan_.passes.size(); ++i) {
    const PassPlan& entry = plan_.passes[i];
    if (!entry.implemented) {
      throw RuntimeError("scene '" + scene.name + "' needs pass '" + entry.name + "' (" + entry.why +
                         "), which is not implemented yet: " + entry.missing + ". `seasim plan` shows the plan.");
    }
    // Every resource a pass reads is written by an earlier pass (or by itself, adding into it).
    for (const auto& r : entry.reads) {
      if (r == "scene") continue;
      bool written = contains(entry.writes, r);
      for (size_t j = 0; j < i && !written; ++j) written = contains(plan_.passes[j].writes, r);
      if (!written) {
        throw RuntimeError("renderer: plan entry '" + entry.name + "' reads '" + r +
                           "', which no earlier pass writes (plan/plan.cpp orders the passes)");
      }
    }
    Node node;
    node.entry = &entry;
    node.pass = registry_.make(entry, plan_, scene);
    node.keys = node.pass->keys();
    nodes_.push_back(std::move(node));
  }
}

void Renderer::update(const Scene& next, const std::vector<std::string>& changed_keys) {
  if (changed_keys.empty()) return;
  bool unclaimed = false;
  for (const auto& key : changed_keys) {
    if (changesNoPass(key)) continue;
    bool claimed = false;
    for (const Node& n : nodes_) claimed = claimed || anyMatch(n.keys.rebuild_on, key) || anyMatch(n.keys.rerun_on, key);
    unclaimed = unclaimed || !claimed;
  }
  // The plan's measured choices are made again for the next scene: one decision per scene as its
  // search keys it (the shafts' method leaves the camera's pose out, so a moving camera reads the cache).
  const std::optional<Scene> chosen = follow_scene_ ? registry_.planChoices(device_, next) : std::nullopt;
  ctx_.setScene(chosen ? *chosen : next, changed_keys);
  if (follow_scene_) {
    Plan next_plan = makePlan(ctx_.scene());
    if (next_plan.toText() != plan_.toText()) {
      plan_ = std::move(next_plan);
      nodes_.clear();  // a different graph: build() makes it on the next render
      return;
    }
  }
  if (unclaimed) {  // no pass says it depends on the key: set everything up again rather than guess
    nodes_.clear();
    return;
  }
  for (Node& n : nodes_) {
    for (const auto& key : changed_keys) {
      if (anyMatch(n.keys.rebuild_on, key)) n.rebuild = true;
      else if (anyMatch(n.keys.rerun_on, key)) n.rerun = true;
    }
  }
}

void Renderer::update(const std::vector<Override>& overrides) {
  if (scene_file_.empty()) {
    throw RuntimeError("Renderer::update(overrides) needs a renderer made from a scene file");
  }
  std::vector<std::string> changed;
  std::vector<Override> next = overrides_;  // kept only when the scene with them parses: a bad value changes nothing
  for (const Override& o : overrides) {
    // The last override of a key is the one in effect (they apply in order): compare with it, then
    // keep only the new one, so an earlier duplicate can never shadow a later update.
    auto last = std::find_if(next.rbegin(), next.rend(), [&](const Override& x) { return x.key == o.key; });
    if (last != next.rend() && last->value_toml == o.value_toml) continue;
    next.erase(std::remove_if(next.begin(), next.end(), [&](const Override& x) { return x.key == o.key; }), next.end());
    next.push_back(o);
    changed.push_back(o.key);
  }
  if (changed.empty()) return;
  Scene scene = parseScene(scene_text_, scene_file_, next);
  overrides_ = std::move(next);
  update(scene, changed);
}

void Renderer::rerunAll() {
  for (Node& n : nodes_) n.rerun = true;
}

bool Renderer::readsReplaced(const Node& node) const {
  for (const auto& r : node.entry->reads) {
    if (r == "scene") continue;
    const auto it = node.seen_generation.find(r);
    if (it == node.seen_generation.end() || it->second != resources_.generation(r)) return true;
  }
  return false;
}

bool Renderer::readsWritten(const Node& node) const {
  for (const auto& r : node.entry->reads) {
    if (r == "scene") continue;
    const auto it = node.seen_version.find(r);
    if (it == node.seen_version.end() || it->second != resources_.version(r)) return true;
  }
  return false;
}

// Which passes run this frame: forward, a pass runs when it is new, marked, or reads a resource that
// changed since it last ran or that an earlier running pass writes; backward, a pass that adds into
// a resource it reads makes that resource's earlier writer run too. Repeated until nothing changes.
std::vector<bool> Renderer::passesToRun() const {
  const size_t n = nodes_.size();
  std::vector<bool> forced(n, false), run(n, false);
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::string> written;
    for (size_t i = 0; i < n; ++i) {
      const Node& node = nodes_[i];
      bool r = forced[i] || !node.prepared || node.rebuild || node.rerun || readsWritten(node) || readsReplaced(node);
      for (const auto& res : node.entry->reads) r = r || contains(written, res);
      run[i] = r;
      if (r)
        for (const auto& w : node.entry->writes) written.push_back(w);
    }
    for (size_t i = 0; i < n; ++i) {
      if (!run[i]) continue;
      for (const auto& res : nodes_[i].entry->reads) {
        if (!contains(nodes_[i].entry->writes, res)) continue;
        for (size_t j = i; j-- > 0;) {
          if (!contains(nodes_[j].entry->writes, res)) continue;
          if (!run[j] && !forced[j]) {
            forced[j] = true;
            changed = true;
          }
          break;
        }
      }
    }
  }
  return run;
}

FrameResult Renderer::render() {
  const auto t0 = std::chrono::steady_clock::now();
  const double build_before = device_.totalBuildMs();
  if (nodes_.empty()) build();
  ctx_.timings.clear();
  ctx_.nonfinite = nonfinite_;
  last_prepared_.clear();
  last_executed_.clear();

  const std::vector<bool> run = passesToRun();
  for (size_t i = 0; i < nodes_.size(); ++i) {
    Node& node = nodes_[i];
    if (!run[i]) continue;
    PassResources view(resources_, node.entry->name, node.entry->reads, node.entry->writes);
    if (!node.prepared || node.rebuild || readsReplaced(node)) {
      node.pass->prepare(ctx_, view);
      node.prepared = true;
      last_prepared_.push_back(node.entry->name);
    }
    node.pass->execute(ctx_, view);
    last_executed_.push_back(node.entry->name);
    for (const auto& w : node.entry->writes) resources_.touch(w);
    node.rebuild = node.rerun = false;
    for (const auto& r : node.entry->reads) {
      node.seen_generation[r] = resources_.generation(r);
      node.seen_version[r] = resources_.version(r);
    }
  }
  nonfinite_ = ctx_.nonfinite;
  ctx_.frameDone();

  FrameResult result;
  result.timings = ctx_.timings;
  result.nonfinite = nonfinite_;
  result.wavelengths_nm = ctx_.grid().centers_nm;
  const Scene& scene = ctx_.scene();
  const size_t pixels = static_cast<size_t>(scene.camera.width) * static_cast<size_t>(scene.camera.height);
  result.rgb.width = scene.camera.width;
  result.rgb.height = scene.camera.height;
  result.rgb.channels = 3;
  result.rgb.channel_names = {"R", "G", "B"};
  result.rgb.pixels.resize(3 * pixels);
  if (!resources_.has("rgb")) {
    throw RuntimeError("scene '" + scene.name + "' has nothing to render (no pass of its plan writes 'rgb')");
  }
  RadianceTarget& target = resources_.get<RadianceTarget>("rgb");
  onDevice("reading the frame back", [&] {
    device_.queue().enqueueReadBuffer(target.rgb, CL_TRUE, 0, sizeof(float) * 3 * pixels, result.rgb.pixels.data());
    if (scene.spectral.spectral_exr && target.hasSpectral()) {
      result.spectral.resize(pixels * target.bands);
      device_.queue().enqueueReadBuffer(target.spectral, CL_TRUE, 0, sizeof(float) * result.spectral.size(),
                                        result.spectral.data());
    }
  });
  readLayers(device_, resources_, plan_, scene.camera.width, scene.camera.height, result);
  for (const PassPlan& p : plan_.passes)
    for (const auto& w : p.writes)
      if (resources_.holds<TextOutput>(w)) result.texts.push_back(resources_.get<TextOutput>(w));
  result.build_ms = device_.totalBuildMs() - build_before;
  result.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace seasim
