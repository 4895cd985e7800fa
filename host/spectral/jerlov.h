// jerlov.h — water optical properties per wavelength band: the Jerlov water types, or explicit spectra.
//
// Data (provenance in data/README.md §3):
//   a(λ), b(λ)  Solonenko & Mobley (2015), Appl. Opt. 54, 5392, Tables 4–8: jerlov_a.csv, jerlov_b.csv
//               (300–700 nm, 17 wavelengths, 1/m).
//   Kd(λ)       Jerlov (1976), Marine Optics, Table XXVII: jerlov_kd.csv (350–700 nm at 25 nm, 1/m).
//               (Not the modelled Kd column of Solonenko & Mobley, jerlov_kd_solonenko2015.csv.)
// Outside the tabulated range Spectrum::at holds the end values (e.g. below 350 nm Kd(350) is used).
// Caveat (Austin & Petzold 1986): Jerlov's type I Kd falls below the tabulated a at some wavelengths
// (e.g. 525 nm: Kd 0.043 < a 0.046), so K_d ω_y - σ_t in 002 eq. 4.7 can cross zero; the kernel must
// use its stable form there.
//
// Empty cells. jerlov_a.csv and jerlov_b.csv leave 3C at 675–700 nm and 5C at 600–700 nm empty (the
// published rows are duplicated by mistake, data/README.md §3). Holding the last value would be badly
// wrong for a — pure-water absorption rises about sevenfold from 575 to 700 nm — so each gap is filled
// from the spectral shape of the nearest MORE turbid type R that has values there (7C for both), anchored
// at the type's own last published wavelength λ0 below the gap:
//   b_T(λ) = b_T(λ0) · b_R(λ) / b_R(λ0)                                    (particle scattering scales)
//   a_T(λ) = a_I(λ) + [a_T(λ0) − a_I(λ0)] · [a_R(λ) − a_I(λ)] / [a_R(λ0) − a_I(λ0)]
// i.e. the absorption above that of type I (≈ the water itself in their model) keeps R's spectral
// shape. Check: this gives a_5C(600, 700) = 0.257, 0.598 and b_5C(600, 700) = 1.145, 0.880 1/m; over
// all 14 filled cells it is within 5 % of the values Williamson & Hollins (2022) substituted for them
// in their dataset (e.g. 0.259, 0.598; 1.147, 0.883; largest gap a_3C(675): 0.456 vs 0.477), which
// are themselves estimates. Jerlov's Kd table has no empty cells.
//
// Kd when explicit spectra give none: the model Solonenko & Mobley fitted their a and b with, their
// eq. (3) (a Kirk-type model), with η = b_w/b the fraction of scattering by the water itself,
// b_w(λ) = 0.00583 (400/λ)^4.322 1/m (their eq. (8), after Haltrin 1999) and μ_w the cosine of the
// refracted solar zenith angle:
//   Kd = (a/μ_w) sqrt(1 + (b/a) [(0.451 + 2.584 η) μ_w − (0.205 + 0.521 η)])
// written as sqrt(a² + a·b·G)/μ_w so that a → 0 is finite. With their a and b it reproduces their
// Kd column (jerlov_kd_solonenko2015.csv) to within 7 % (tested). Default μ_w = 0.85: a sun 45° from
// the zenith (the scene default) refracted into water (n = 1.333) is 32° from the vertical.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"
#include "spectral/spectrum.h"
#include "spectral/wavelength_grid.h"

namespace seasim {

// "I", "IA", "IB", "II", "III", "1C", "3C", "5C", "7C", "9C": clearest oceanic to most turbid coastal.
const std::vector<std::string>& jerlovTypes();

struct WaterSpectra {
  Spectrum a;   // absorption, 1/m
  Spectrum b;   // scattering, 1/m
  Spectrum kd;  // diffuse downwelling attenuation, 1/m
};

// One Jerlov type, with the empty cells filled as above. The name is matched ignoring case ("ib");
// RuntimeError listing the valid names otherwise. The tables are read once per process.
WaterSpectra jerlovWater(const std::string& type);

// Solonenko & Mobley (2015) eq. (3): Kd from a, b (1/m) at lambda_nm for the refracted sun cosine mu_w.
double kdFromIops(double a, double b, double lambda_nm, double mu_w = 0.85);

// Per band of the grid (values at the band centres), 1/m.
struct BandOptics {
  std::vector<double> a, b, c, kd;  // c = a + b (beam attenuation σ_t)
};

// The water of a scene on a grid. With a Jerlov name the Jerlov spectra are used, and any explicit
// spectrum in `water` replaces the Jerlov one of the same quantity. Without a name, a and b must be
// given. Kd: explicit, else Jerlov's, else kdFromIops(a, b, λ, mu_w). mu_w must be in [0.6, 1].
// RuntimeError on a missing a/b, an unknown type, or a negative or non-finite value (naming the band).
BandOptics resolveWater(const WaterDesc& water, const WavelengthGrid& grid, double mu_w = 0.85);

}  // namespace seasim
