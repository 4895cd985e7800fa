#include "plan/features.h"

namespace seasim {

void FeatureList::flag(const char* feature, const char* define, bool on) {
  defines_.push_back(std::string(define) + (on ? "=1" : "=0"));
  features_.push_back(std::string(feature) + (on ? "=1" : "=0"));
}

void FeatureList::value(const char* feature, const char* define, int v) {
  defines_.push_back(std::string(define) + "=" + std::to_string(v));
  features_.push_back(std::string(feature) + "=" + std::to_string(v));
}

std::vector<std::string> kernelDefines(const PassFeatures* features, bool fast_math) {
  FeatureList list;
  if (features) features->list(list);
  std::vector<std::string> defines = list.defines();
  if (fast_math) defines.push_back("SEASIM_FAST_MATH=1");
  return defines;
}

std::string featuresText(const PassFeatures* features) {
  if (!features) return "";
  FeatureList list;
  features->list(list);
  std::string text;
  for (const std::string& f : list.features()) text += (text.empty() ? "" : " ") + f;
  return text;
}

}  // namespace seasim
