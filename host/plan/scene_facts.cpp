#include "plan/scene_facts.h"

#include <cmath>

namespace seasim {

bool cameraUnderwater(const Scene& scene) { return scene.water.present && scene.camera.position.y < 0.0; }

bool seaSeenFromAbove(const Scene& scene) { return scene.water.present && !cameraUnderwater(scene); }

bool fftWaves(const Scene& scene) { return scene.surface.type == SurfaceDesc::Type::Fft && scene.water.present; }

bool spotlightsInAir(const Scene& scene) {
  return !scene.spotlights.empty() && scene.air.present && !scene.water.present;
}

const char* underwaterLampsModel(const Scene& scene) {
  const auto model = scene.quality.find("lamps_model"), older = scene.quality.find("lamps_delta_m");
  const double id = model != scene.quality.end()   ? model->second.value
                    : older != scene.quality.end() ? (older->second.value != 0 ? 1.0 : 0.0)
                                                   : 2.0;
  return id == 0.0 ? "single" : id == 1.0 ? "delta_m" : "orders";
}

bool sunUp(const Scene& scene) {
  return scene.sun.enabled && scene.sun.irradiance > 0 && scene.sun.zenith < M_PI / 2;
}

int underwaterCausticsMode(const Scene& scene) {
  if (!sunUp(scene)) return 0;
  switch (scene.underwater.caustics) {
    case UnderwaterDesc::Caustics::Texture: return 1;
    case UnderwaterDesc::Caustics::Map: return 2;
    default: return 0;
  }
}

bool oceanForUnderwaterCaustics(const Scene& scene) {
  return cameraUnderwater(scene) && fftWaves(scene) && underwaterCausticsMode(scene) == 2;
}

bool oceanForSea(const Scene& scene) { return fftWaves(scene) && seaSeenFromAbove(scene) && !scene.shallow.present; }

bool seaBottomCausticsPlanned(const Scene& scene) {
  return oceanForSea(scene) && scene.bottom.type != BottomDesc::Type::None && sunUp(scene) &&
         scene.sea.bottom_caustics;
}

bool underwaterPointSpread(const Scene& scene) {
  return scene.underwater.model == UnderwaterDesc::Model::DiscreteOrdinates && scene.underwater.point_spread &&
         scene.water.g > 0;
}

int skyModelOf(const SkyDesc& sky) {
  return sky.model == SkyDesc::Model::Analytic   ? 1
         : sky.model == SkyDesc::Model::Image    ? 2
         : sky.model == SkyDesc::Model::Preetham ? 3
                                                 : 0;
}

}  // namespace seasim
