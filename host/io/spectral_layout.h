// spectral_layout.h — channel names of the spectral OpenEXR layout (Fichet, Pacanowski & Wilkie,
// "An OpenEXR Layout for Spectral Images", JCGT 10(3), 2021). Emissive channels are
// "S<stokes>.<value><prefix><unit>" with a decimal COMMA (a dot separates OpenEXR layers), the
// value in metres (with an SI prefix) or Hz. We write unpolarised emissive bands, "S0.", in nm
// with six decimals, as the authors' reference code does: 550 nm -> "S0.550,000000nm".
#pragma once
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace seasim {

inline constexpr const char* kSpectralLayoutVersion = "1.0";
// The layout's unit string for emissive spectra; our bands hold spectral radiance per nm.
inline constexpr const char* kSpectralEmissiveUnits = "W.m^-2.sr^-1";

// "S0.550,000000nm" for 550. Throws RuntimeError for a non-finite or non-positive wavelength.
std::string spectralChannelName(double wavelength_nm);

// A per-band ground-truth layer's channel (scene/output_layers.h): "direct.S0.550,000000nm" (the dot
// makes "direct" an OpenEXR layer holding that band).
std::string spectralLayerChannelName(const std::string& layer, double wavelength_nm);

// The file's values per pixel: the n bands of `bands`, then the k values of `layers` (the per-band layers'
// channels), for `pixels` pixels; both pixel-major (the .npy writer's array).
inline std::vector<float> bandsThenLayers(const std::vector<float>& bands, std::size_t n,
                                          const std::vector<float>& layers, std::size_t k, std::size_t pixels) {
  std::vector<float> all(pixels * (n + k));
  for (std::size_t i = 0; i < pixels; ++i) {
    std::copy_n(bands.data() + i * n, n, all.data() + i * (n + k));
    std::copy_n(layers.data() + i * k, k, all.data() + i * (n + k) + n);
  }
  return all;
}

// True for an emissive Stokes-0 channel name ("S0.<value><prefix>m" or "...Hz"); sets the
// wavelength in nm (frequencies converted with c = 299792458 m/s). False for anything else
// (R, G, B, S1..S3 polarisation, reflective "T." channels).
bool parseSpectralChannelName(const std::string& name, double& wavelength_nm);

}  // namespace seasim
