#include "preview/preview_settings.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "plan/plan.h"
#include "scene/toml_reader.h"
#include "spectral/jerlov.h"
#include "util/error.h"

namespace seasim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerPixel = 0.3;   // mouse orbit / look speed
constexpr double kSunStepDeg = 5.0;
constexpr double kDepthStep = 0.5;     // m, PAGE_UP / PAGE_DOWN
constexpr double kMaxElevationDeg = 89.0;

const std::vector<std::string>& keyNames() {
  static const std::vector<std::string> names = {
      "I", "K", "J", "L", "U", "O", "PAGE_UP", "PAGE_DOWN", "UP", "DOWN", "LEFT", "RIGHT", "LEFT_BRACKET",
      "RIGHT_BRACKET", "MINUS", "EQUAL", "Q", "T", "SPACE", "S", "ESCAPE", "1", "2", "3", "4", "5", "6", "7", "8", "9"};
  return names;
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

double parseNumber(const std::string& text, const std::string& token) {
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw RuntimeError("--script: '" + token + "': '" + text + "' is not a number");
}

// Rotates `offset` about the vertical by `yaw_deg` and tilts it by `pitch_deg`, keeping its length
// and its elevation within +-89 degrees (never through the pole, where the camera's up flips).
Vec3 rotateOffset(Vec3 offset, double yaw_deg, double pitch_deg) {
  const double r = length(offset);
  if (!(r > 0)) return offset;
  double azimuth = std::atan2(offset.z, offset.x);
  double elevation = std::asin(std::clamp(offset.y / r, -1.0, 1.0));
  azimuth += yaw_deg * kPi / 180.0;
  elevation = std::clamp(elevation + pitch_deg * kPi / 180.0, -kMaxElevationDeg * kPi / 180.0,
                         kMaxElevationDeg * kPi / 180.0);
  return {r * std::cos(elevation) * std::cos(azimuth), r * std::sin(elevation),
          r * std::cos(elevation) * std::sin(azimuth)};
}


}  // namespace

std::string tomlNumber(double v) { return formatNumber(v); }

std::string tomlVec3(const Vec3& v) {
  return "[" + tomlNumber(v.x) + ", " + tomlNumber(v.y) + ", " + tomlNumber(v.z) + "]";
}

bool isPreviewKey(const std::string& name) {
  const auto& names = keyNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::vector<PreviewInput> parseKeyScript(const std::string& script) {
  std::vector<PreviewInput> out;
  std::istringstream in(script);
  std::string token;
  while (in >> token) {
    std::string body = upper(token);
    int repeat = 1;
    if (const size_t star = body.find('*'); star != std::string::npos) {
      const double n = parseNumber(body.substr(star + 1), token);
      if (n < 1 || n > 10000 || n != std::floor(n))
        throw RuntimeError("--script: '" + token + "': the repeat count must be a whole number from 1 to 10000");
      repeat = static_cast<int>(n);
      body = body.substr(0, star);
    }
    PreviewInput input;
    if (const size_t colon = body.find(':'); colon != std::string::npos) {
      const std::string kind = body.substr(0, colon), args = body.substr(colon + 1);
      const size_t comma = args.find(',');
      if (kind == "ORBIT" || kind == "LOOK") {
        if (comma == std::string::npos)
          throw RuntimeError("--script: '" + token + "': " + kind + " expects dx,dy in pixels, e.g. ORBIT:40,0");
        input.kind = kind == "ORBIT" ? PreviewInput::Kind::Orbit : PreviewInput::Kind::Look;
        input.dx = parseNumber(args.substr(0, comma), token);
        input.dy = parseNumber(args.substr(comma + 1), token);
      } else if (kind == "ZOOM") {
        input.kind = PreviewInput::Kind::Zoom;
        input.dy = parseNumber(args, token);
      } else {
        throw RuntimeError("--script: '" + token + "': unknown mouse input '" + kind + "' (ORBIT, LOOK or ZOOM)");
      }
    } else if (body == "WAIT") {
      input.kind = PreviewInput::Kind::Wait;
    } else if (isPreviewKey(body)) {
      input.key = body;
    } else {
      std::string known;
      for (const auto& k : keyNames()) known += " " + k;
      throw RuntimeError("--script: unknown key '" + token + "'; keys:" + known + ", WAIT, ORBIT:dx,dy, LOOK:dx,dy, ZOOM:n");
    }
    for (int i = 0; i < repeat; ++i) out.push_back(input);
  }
  return out;
}

PreviewSettings::PreviewSettings(const Scene& scene)
    : position_(scene.camera.position),
      look_at_(scene.camera.look_at),
      // Degrees as the file wrote them (the parser's radians back, rounded off the last bit).
      sun_zenith_deg_(std::round(scene.sun.zenith * 180.0 / kPi * 1e9) / 1e9),
      sun_azimuth_deg_(std::round(scene.sun.azimuth * 180.0 / kPi * 1e9) / 1e9),
      band_count_(scene.spectral.count),
      jerlov_(scene.water.present ? scene.water.jerlov : ""),
      time_(scene.surface.time) {
  // Pass switches for the passes this scene's plan runs.
  const Plan plan = makePlan(scene);
  auto has = [&](const std::string& name) {
    return std::any_of(plan.passes.begin(), plan.passes.end(), [&](const PassPlan& p) { return p.name == name; });
  };
  if (has("sea_single")) {
    switches_.push_back({"sea.reflection", scene.sea.reflection, "true"});
    switches_.push_back({"sea.single_scattering", scene.sea.single_scattering, "true"});
    switches_.push_back({"sea.second_order", scene.sea.second_order, "true"});
    if (scene.bottom.type != BottomDesc::Type::None && scene.surface.type == SurfaceDesc::Type::Fft)
      switches_.push_back({"sea.bottom_caustics", scene.sea.bottom_caustics, "true"});
  }
  if (has("kd_multiple")) {
    switches_.push_back({"underwater.multiple_scattering", scene.underwater.multiple_scattering, "true"});
    switches_.push_back({"underwater.single_scattering", scene.underwater.single_scattering, "true"});
    if (scene.underwater.caustics != UnderwaterDesc::Caustics::None)
      switches_.push_back({"underwater.caustics", true,
                           scene.underwater.caustics == UnderwaterDesc::Caustics::Map ? "\"map\"" : "\"texture\""});
  }
  // Time moves the waves (FFT surface) and the caustics under water.
  time_applies_ = scene.surface.type == SurfaceDesc::Type::Fft || has("kd_multiple");

  original_["camera.position"] = tomlVec3(position_);
  original_["camera.look_at"] = tomlVec3(look_at_);
  original_["sun.zenith_deg"] = tomlNumber(sun_zenith_deg_);
  original_["sun.azimuth_deg"] = tomlNumber(sun_azimuth_deg_);
  original_["spectral.count"] = std::to_string(band_count_);
  original_["water.jerlov"] = "\"" + jerlov_ + "\"";
  original_["surface.time"] = tomlNumber(time_);
  for (const auto& s : switches_) original_[s.key] = s.on ? s.on_value : (s.key == "underwater.caustics" ? "\"none\"" : "false");
}

void PreviewSettings::set(const std::string& key, const std::string& value_toml) {
  if (!current_.count(key)) order_.push_back(key);
  current_[key] = value_toml;
}

void PreviewSettings::setCamera() {
  set("camera.position", tomlVec3(position_));
  set("camera.look_at", tomlVec3(look_at_));
}

PreviewEffect PreviewSettings::moveCamera(const PreviewInput& input) {
  const Vec3 view = look_at_ - position_;
  const double distance = length(view);
  switch (input.kind) {
    case PreviewInput::Kind::Orbit:  // drag right: the camera goes round to the right of the target
      position_ = look_at_ + rotateOffset(position_ - look_at_, -input.dx * kDegPerPixel, input.dy * kDegPerPixel);
      break;
    case PreviewInput::Kind::Look:
      look_at_ = position_ + rotateOffset(view, input.dx * kDegPerPixel, -input.dy * kDegPerPixel);
      break;
    case PreviewInput::Kind::Zoom:  // wheel up: 10 % closer per click, never onto the target
      position_ = look_at_ - view * std::clamp(std::pow(0.9, input.dy), 0.01, 100.0);
      break;
    default: {
      // Fly: a step of 5 % of the distance to the target (at least 5 cm), target moved along.
      const double step = std::max(0.05, 0.05 * distance);
      const Vec3 forward = normalize(view);
      Vec3 right = cross(forward, Vec3{0, 1, 0});
      right = length(right) > 1e-9 ? normalize(right) : Vec3{1, 0, 0};
      Vec3 move{};
      if (input.key == "I") move = forward * step;
      if (input.key == "K") move = forward * -step;
      if (input.key == "L") move = right * step;
      if (input.key == "J") move = right * -step;
      if (input.key == "U") move = Vec3{0, step, 0};
      if (input.key == "O") move = Vec3{0, -step, 0};
      if (input.key == "PAGE_UP") move = Vec3{0, kDepthStep, 0};
      if (input.key == "PAGE_DOWN") move = Vec3{0, -kDepthStep, 0};
      position_ = position_ + move;
      look_at_ = look_at_ + move;
    }
  }
  setCamera();
  return {true, false, false};
}

PreviewEffect PreviewSettings::apply(const PreviewInput& input) {
  if (input.kind == PreviewInput::Kind::Wait) return {};
  if (input.kind != PreviewInput::Kind::Key) return moveCamera(input);
  const std::string& k = input.key;
  if (k == "I" || k == "K" || k == "J" || k == "L" || k == "U" || k == "O" || k == "PAGE_UP" || k == "PAGE_DOWN")
    return moveCamera(input);
  if (k == "UP" || k == "DOWN") {
    sun_zenith_deg_ = std::clamp(sun_zenith_deg_ + (k == "UP" ? -kSunStepDeg : kSunStepDeg), 0.0, 89.0);
    set("sun.zenith_deg", tomlNumber(sun_zenith_deg_));
    return {true, false, false};
  }
  if (k == "LEFT" || k == "RIGHT") {
    sun_azimuth_deg_ = std::fmod(sun_azimuth_deg_ + (k == "LEFT" ? -kSunStepDeg : kSunStepDeg) + 360.0, 360.0);
    set("sun.azimuth_deg", tomlNumber(sun_azimuth_deg_));
    return {true, false, false};
  }
  if (k == "LEFT_BRACKET" || k == "RIGHT_BRACKET") {
    if (jerlov_.empty()) return {};
    const auto& types = jerlovTypes();
    const auto at = std::find(types.begin(), types.end(), jerlov_);
    const long i = at == types.end() ? 0 : at - types.begin();
    const long n = static_cast<long>(types.size());
    jerlov_ = types[static_cast<size_t>(((k == "RIGHT_BRACKET" ? i + 1 : i - 1) % n + n) % n)];
    set("water.jerlov", "\"" + jerlov_ + "\"");
    return {true, false, false};
  }
  if (k == "MINUS" || k == "EQUAL") {
    const int next = k == "MINUS" ? std::max(1, band_count_ / 2) : std::min(1000, band_count_ * 2);
    if (next == band_count_) return {};
    band_count_ = next;
    set("spectral.count", std::to_string(band_count_));
    return {true, false, false};
  }
  if (k == "Q") {
    preset_ = preset_ >= 3 ? -1 : preset_ + 1;
    return {true, false, false};
  }
  if (k == "T" || k == "SPACE") {
    if (time_applies_) playing_ = !playing_;
    return {};
  }
  if (k.size() == 1 && k[0] >= '1' && k[0] <= '9') {
    const size_t i = static_cast<size_t>(k[0] - '1');
    if (i >= switches_.size()) return {};
    PassSwitch& s = switches_[i];
    s.on = !s.on;
    set(s.key, s.on ? s.on_value : (s.key == "underwater.caustics" ? "\"none\"" : "false"));
    return {true, false, false};
  }
  if (k == "S") return {false, true, false};
  if (k == "ESCAPE") return {false, false, true};
  return {};
}

bool PreviewSettings::advanceTime(double seconds) {
  if (!playing_ || !(seconds > 0)) return false;
  time_ += seconds;
  set("surface.time", tomlNumber(time_));
  return true;
}

std::vector<Override> PreviewSettings::overrides() const {
  std::vector<Override> out;
  for (const auto& key : order_) out.push_back({key, current_.at(key), SourceLoc{"<preview setting " + key + ">", 0}});
  return out;
}

std::string PreviewSettings::differences() const {
  std::string out;
  for (const auto& key : order_) {
    const auto it = original_.find(key);
    if (it != original_.end() && it->second == current_.at(key)) continue;
    out += (out.empty() ? "" : " ") + key + "=" + current_.at(key);
  }
  return out;
}

}  // namespace seasim
