// von_kries.h — chromatic adaptation of paper 003 §5 (Belyaev): CIE XYZ -> LMS cone space by the
// matrix of 003 eq. 15, each cone signal divided by the white point's (eq. 17, the von Kries
// proportionality law), back to XYZ by the inverse of eq. 15. The white point and the image are both
// scaled to luminance 1 first (eq. 16), so only chromaticity is adapted.
//
// As a sensor (sensor.h, `[spectral] sensor = "vonkries"` or "vonkries:<kelvin>"): the white point is
// a black body at that colour temperature (default 6504 K, near D65), and the adapted cone signals
// are multiplied by the display white's (D65) before going back, so the white point shows as sRGB
// (1, 1, 1): a picture lit by a 3200 K lamp looks as the eye adapted to that lamp sees it. The whole
// chain is linear in the spectrum, so it is one more set of band weights, usable by every model.
// The tone-mapping operator of eq. 18 is not part of this (the display transform is io/tonemap.h).
#pragma once
#include <array>
#include <string>

namespace seasim {

using Mat3 = std::array<double, 9>;  // row-major
using Vec3d = std::array<double, 3>;

// 003 eq. 15: LMS = M XYZ.
const Mat3& xyzToLmsMatrix();
// Its inverse (computed once).
const Mat3& lmsToXyzMatrix();

// XYZ -> XYZ: adapts a colour seen under white `white_src_xyz` to one seen under `white_dst_xyz`
// (both luminance-normalised by the caller): M⁻¹ diag(LMS_dst / LMS_src) M.
Mat3 vonKriesXyzTransform(const Vec3d& white_src_xyz, const Vec3d& white_dst_xyz);

// Planck's law, relative spectral radiance of a black body (any scale), λ in nm, T in K.
double blackbody(double lambda_nm, double kelvin);

// "vonkries" -> 6504 K, "vonkries:<kelvin>" with kelvin in [1000, 40000] -> that; true when `name`
// names this sensor. A malformed or out-of-range temperature throws InputError-free RuntimeError
// naming the sensor (the parser reports it at the key).
bool parseVonKriesSensor(const std::string& name, double* kelvin);

Mat3 multiply(const Mat3& a, const Mat3& b);
Vec3d apply(const Mat3& m, const Vec3d& v);

}  // namespace seasim
