// features.h — a pass's optional kernel features as a typed struct (STYLE.md rule 5: `#if SEASIM_*`
// chosen by the planner). Each pass's struct (beside its pass class, e.g. SeaSingleFeatures) lists
// every feature once, with the name `seasim plan` prints and the OpenCL define the kernel tests; the
// define strings are generated from that list here and nowhere else. Passes read the struct's
// fields, never the strings.
#pragma once
#include <memory>
#include <string>
#include <vector>

namespace seasim {

// What a features struct writes itself into: each call is one feature and one define.
class FeatureList {
 public:
  // NAME=1 or NAME=0.
  void flag(const char* feature, const char* define, bool on);
  // NAME=value (an enumeration the kernel switches on, or a count).
  void value(const char* feature, const char* define, int v);

  const std::vector<std::string>& defines() const { return defines_; }
  // "feature=value" per feature, in the same order as the defines.
  const std::vector<std::string>& features() const { return features_; }

 private:
  std::vector<std::string> defines_;
  std::vector<std::string> features_;
};

class PassFeatures {
 public:
  virtual ~PassFeatures() = default;
  // Writes every feature of this pass, in the order its kernel's defines are passed.
  virtual void list(FeatureList& out) const = 0;
};

// The defines the kernel is built with: the features' own, then SEASIM_FAST_MATH=1 when the pass is
// built with -cl-fast-relaxed-math (Device::program reads that define).
std::vector<std::string> kernelDefines(const PassFeatures* features, bool fast_math);

// "bottom=1 sky_model=2" ("" without features), what `seasim plan` prints beside the defines.
std::string featuresText(const PassFeatures* features);

}  // namespace seasim
